#!/usr/bin/env python3
"""The dam break's surge front and residual height against Martin & Moyce (1952), by resolution.

Runs scenarios/dambreak.lua with the experiment's column (a = 2.25 in = 0.05715 m wide, 2a
high, or a high with --square; a slab a/2 deep between free-slip walls) at several
resolutions (particles across a) and scores each run against the tables of
../shared/validation/martin_moyce_1952_n2_{2,1}_{front,height}.csv, with their time scales:
T = t sqrt(2 g / a) for the tall column's front, T = t sqrt(g / a) for the square column's
and for both residual heights. Fronts are scored over the points with T <= 3:

    front      Z = (99.5th percentile of x + s/2) / a     (s the particle spacing)
    farthest   Z = (largest x + s/2) / a
    RMS(Z)     root mean square of Z_sim(T_k) - Z_k over the table's points with T_k <= 3,
               Z_sim interpolated linearly between thermo lines (every 0.002 s)
    shift      the delay dT that minimises the RMS of Z_sim(T_k - dT) - Z_k (the shape of
               the curve, apart from when it starts), and that RMS
    height     H = (water height at the back wall, fix gauge) / (column height), RMS over
               the table's points the run covers (until the surge returns from the far wall)

It prints a Markdown table (RMS of both fronts, Z at T = 1, 2, 3, wall time) and writes
docs/validation/martin_moyce.png (Z against T, each resolution a curve) unless --no-plot.
The table's own steps of 1/9 in Z limit any simulation to about 0.03 RMS.

    /usr/bin/python3 share/validation/martin_moyce.py [--binary build/pbfengine] [--square]
        [--across 12 16 24] [-v NAME=VALUE ...] [--label TEXT] [--no-plot] [-o PNG]

-v passes variables to the scenario for every run (a variant: -v relaxation=1).
"""
import argparse
import collections
import csv
import math
import os
import resource
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, "..", "shared", "validation")
A = 0.05715   # m, the experiment's column width
G = 9.81
# Per column (n^2): the front's time scale sqrt(n^2 g / a) and how long to run, in t sqrt(g / a):
# past T = 3 for the front, and until the surge, back from the far wall 4a away, nears the
# back wall (tall: tau = 2.75; square: 3.1).
COLUMNS = {2: (math.sqrt(2 * G / A), 2.75), 1: (math.sqrt(G / A), 3.1)}


def read_table(path, t_max):
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line[0].isdigit():
                continue
            t, z = line.strip().split(",")[:2]
            rows.append((float(t), float(z)))
    return [(t, z) for t, z in rows if t <= t_max]


def interpolate(ts, zs, t):
    for k in range(1, len(ts)):
        if ts[k] >= t:
            w = (t - ts[k - 1]) / (ts[k] - ts[k - 1])
            return zs[k - 1] + w * (zs[k] - zs[k - 1])
    return float("nan")


# One run's record: front T, Z of the front and of the farthest particle, wall and CPU
# seconds, tau and H for the residual height, the time average of the mean compression and
# the largest rho/rho0 - 1 at any thermo line.
Run = collections.namedtuple("Run", "T front far wall cpu tau H compression worst")


def run(binary, n2, across, extra, work):
    """One run of dambreak.lua; returns a Run."""
    csv_path = os.path.join(work, f"front_{across}.csv")
    scale, tau_end = COLUMNS[n2]
    t_end = tau_end / math.sqrt(G / A)
    cmd = [binary, "run", os.path.join(ROOT, "scenarios", "dambreak.lua"), "-v", f"particles={across ** 3}",
           "-v", f"a={A}", "-v", f"height={n2}", "-v", f"t_end={t_end}", "-v", "out=", "-v", f"csv={csv_path}",
           "-v", "percentile=99.5", "-v", "thermo=0.002"]
    for v in extra:
        cmd += ["-v", v]
    if not os.access(binary, os.X_OK):
        sys.exit(f"martin_moyce.py: {binary}: no such executable (build it, or give --binary)")
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.time()
    done = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime + after.ru_stime - used.ru_utime - used.ru_stime
    if done.returncode != 0:
        sys.exit(f"martin_moyce.py: {' '.join(cmd)} failed:\n{done.stdout[-2000:]}{done.stderr[-2000:]}")
    s = A / across
    with open(csv_path) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))  # "# units: ..."
    T = [float(r["time"]) * scale for r in rows]
    front = [(float(r["front"]) + s / 2) / A for r in rows]
    far = [(float(r["far"]) + s / 2) / A for r in rows]
    tau = [float(r["time"]) * math.sqrt(G / A) for r in rows]
    H = [float(r["back"]) / (n2 * A) for r in rows]
    return Run(T, front, far, wall, cpu, tau, H, sum(float(r["err.compression"]) for r in rows) / len(rows),
               max(float(r["err.max"]) for r in rows))


def rms(T, Z, table):
    d = [interpolate(T, Z, t) - z for t, z in table]
    return math.sqrt(sum(x * x for x in d) / len(d))


def best_shift(T, Z, table):
    best = (float("inf"), 0.0)
    for k in range(-60, 61):
        dT = 0.005 * k
        d = [interpolate(T, Z, t - dT) - z for t, z in table if t - dT > 0]
        best = min(best, (math.sqrt(sum(x * x for x in d) / len(d)), dT))
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "pbfengine"))
    ap.add_argument("--across", type=int, nargs="+", default=[12, 16, 24], help="particles across a")
    ap.add_argument("--square", action="store_true", help="the square column (height a, n^2 = 1)")
    ap.add_argument("-v", dest="vars", action="append", default=[], help="NAME=VALUE for every run")
    ap.add_argument("--label", default="", help="a name for this variant in the table")
    ap.add_argument("--no-plot", action="store_true")
    ap.add_argument("-o", "--output", default=None, help="figure (default docs/validation/martin_moyce[_square].png)")
    args = ap.parse_args()
    n2 = 1 if args.square else 2
    table = read_table(os.path.join(DATA, f"martin_moyce_1952_n2_{n2}_front.csv"), 3.0)
    heights = read_table(os.path.join(DATA, f"martin_moyce_1952_n2_{n2}_height.csv"), COLUMNS[n2][1])
    runs = {}
    with tempfile.TemporaryDirectory() as work:
        for n in args.across:
            runs[n] = run(args.binary, n2, n, args.vars, work)
    label = args.label or (" ".join(args.vars) or "defaults")
    print(f"{'square column (height a)' if args.square else 'column 2a high'}, {len(table)} front points "
          f"(T <= 3), {len(heights)} height points\n")
    print("| variant | across a | RMS(Z), 99.5th percentile | RMS(Z), farthest | Z at T = 1, 2, 3 "
          "| best delay dT, RMS then | RMS(H) | wall time |")
    print("|---|---|---|---|---|---|---|---|")
    for n, (T, front, far, wall, _, tau, H, _, _) in runs.items():
        z = ", ".join(f"{interpolate(T, front, t):.3f}" for t in (1, 2, 3))
        shifted, dT = best_shift(T, front, table)
        print(f"| {label} | {n} | {rms(T, front, table):.3f} | {rms(T, far, table):.3f} | {z} "
              f"| {dT:.3f}, {shifted:.3f} | {rms(tau, H, heights):.3f} | {wall:.1f} s |")
    if len(runs) >= 2:
        ns = sorted(runs)
        fine, finer = runs[ns[-2]], runs[ns[-1]]
        change = max(abs(interpolate(finer[0], finer[1], t) / interpolate(fine[0], fine[1], t) - 1) for t in (1, 2, 3))
        print(f"\nLargest change of Z at T = 1, 2, 3 from {ns[-2]} to {ns[-1]} across a: {100 * change:.1f}%")
    if args.no_plot:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    output = args.output or os.path.join(ROOT, "docs", "validation",
                                         "martin_moyce_square.png" if args.square else "martin_moyce.png")
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4.2))
    ax.plot([t for t, _ in table], [z for _, z in table], "ks", label="Martin & Moyce (1952)")
    bx.plot([t for t, _ in heights], [z for _, z in heights], "ks", label="Martin & Moyce (1952)")
    for n, (T, front, far, _, _, tau, H, _, _) in runs.items():
        line, = ax.plot(T, front, label=f"{n} across a, 99.5th percentile")
        ax.plot(T, far, ":", color=line.get_color(), label=f"{n} across a, farthest")
        bx.plot(tau, H, color=line.get_color(), label=f"{n} across a")
    ax.set_xlim(0, 3.2)
    ax.set_ylim(1, max(z for _, z in table) + 0.5)
    ax.set_xlabel("T = t sqrt(g/a)" if args.square else "T = t sqrt(2g/a)")
    ax.set_ylabel("Z = x / a")
    ax.set_title(f"Front, {label}")
    bx.set_xlabel("t sqrt(g/a)")
    bx.set_ylabel("H = height at the back wall / initial height")
    bx.set_title("Residual height")
    for x in (ax, bx):
        x.legend(fontsize=7)
        x.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(output, dpi=110)
    print(f"\nmartin_moyce.py: figure written to {output}")


if __name__ == "__main__":
    main()
