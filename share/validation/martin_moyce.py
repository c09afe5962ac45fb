#!/usr/bin/env python3
"""The dam break's surge front against Martin & Moyce (1952), by resolution.

Runs scenarios/dambreak.lua with the experiment's column (a = 2.25 in = 0.05715 m wide, 2a
high, a slab a/2 deep between free-slip walls) at several resolutions (particles across a)
and scores each run's front against the table of ../shared/validation/
martin_moyce_1952_n2_2_front.csv (Z = x/a against T = t sqrt(2 g / a), T <= 3):

    front      Z = (99.5th percentile of x + s/2) / a     (s the particle spacing)
    farthest   Z = (largest x + s/2) / a
    RMS(Z)     root mean square of Z_sim(T_k) - Z_k over the table's points with T_k <= 3,
               Z_sim interpolated linearly between thermo lines (every 0.002 s)
    shift      the delay dT that minimises the RMS of Z_sim(T_k - dT) - Z_k (the shape of
               the curve, apart from when it starts), and that RMS

It prints a Markdown table (RMS of both fronts, Z at T = 1, 2, 3, wall time) and writes
docs/validation/martin_moyce.png (Z against T, each resolution a curve) unless --no-plot.
The table's own steps of 1/9 in Z limit any simulation to about 0.03 RMS.

    /usr/bin/python3 share/validation/martin_moyce.py [--binary build/pbfengine]
        [--across 12 16 24] [-v NAME=VALUE ...] [--label TEXT] [--no-plot]

-v passes variables to the scenario for every run (a variant: -v relaxation=1).
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TABLE = os.path.join(ROOT, "..", "shared", "validation", "martin_moyce_1952_n2_2_front.csv")
A = 0.05715   # m, the experiment's column width
G = 9.81
T_END = 3.2   # in T: past the last scored point (T <= 3)


def read_table(path):
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or line.startswith("T_"):
                continue
            t, z = line.strip().split(",")
            rows.append((float(t), float(z)))
    return [(t, z) for t, z in rows if t <= 3.0]


def interpolate(ts, zs, t):
    for k in range(1, len(ts)):
        if ts[k] >= t:
            w = (t - ts[k - 1]) / (ts[k] - ts[k - 1])
            return zs[k - 1] + w * (zs[k] - zs[k - 1])
    return float("nan")


def run(binary, across, extra, work):
    """One run; returns (T list, Z front list, Z farthest list, wall seconds, particles)."""
    csv_path = os.path.join(work, f"front_{across}.csv")
    t_end = T_END / math.sqrt(2 * G / A)
    cmd = [binary, "run", os.path.join(ROOT, "scenarios", "dambreak.lua"), "-v", f"particles={across ** 3}",
           "-v", f"a={A}", "-v", f"t_end={t_end}", "-v", "out=", "-v", f"csv={csv_path}",
           "-v", "percentile=99.5", "-v", "thermo=0.002"]
    for v in extra:
        cmd += ["-v", v]
    start = time.time()
    done = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - start
    if done.returncode != 0:
        sys.exit(f"martin_moyce.py: {' '.join(cmd)} failed:\n{done.stdout[-2000:]}{done.stderr[-2000:]}")
    s = A / across
    with open(csv_path) as f:
        rows = list(csv.DictReader(f))
    T = [float(r["time"]) * math.sqrt(2 * G / A) for r in rows]
    front = [(float(r["front"]) + s / 2) / A for r in rows]
    far = [(float(r["far"]) + s / 2) / A for r in rows]
    return T, front, far, wall


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
    ap.add_argument("-v", dest="vars", action="append", default=[], help="NAME=VALUE for every run")
    ap.add_argument("--label", default="", help="a name for this variant in the table")
    ap.add_argument("--no-plot", action="store_true")
    ap.add_argument("-o", "--output", default=os.path.join(ROOT, "docs", "validation", "martin_moyce.png"))
    args = ap.parse_args()
    table = read_table(TABLE)
    runs = {}
    with tempfile.TemporaryDirectory() as work:
        for n in args.across:
            runs[n] = run(args.binary, n, args.vars, work)
    label = args.label or (" ".join(args.vars) or "defaults")
    print("| variant | across a | RMS(Z), 99.5th percentile | RMS(Z), farthest | Z at T = 1, 2, 3 "
          "| best delay dT, RMS then | wall time |")
    print("|---|---|---|---|---|---|---|")
    for n, (T, front, far, wall) in runs.items():
        z = ", ".join(f"{interpolate(T, front, t):.3f}" for t in (1, 2, 3))
        shifted, dT = best_shift(T, front, table)
        print(f"| {label} | {n} | {rms(T, front, table):.3f} | {rms(T, far, table):.3f} | {z} "
              f"| {dT:.3f}, {shifted:.3f} | {wall:.1f} s |")
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
    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.plot([t for t, _ in table], [z for _, z in table], "ks", label="Martin & Moyce (1952)")
    for n, (T, front, far, _) in runs.items():
        line, = ax.plot(T, front, label=f"{n} across a, 99.5th percentile")
        ax.plot(T, far, ":", color=line.get_color(), label=f"{n} across a, farthest")
    ax.set_xlim(0, 3.2)
    ax.set_ylim(1, 4.2)
    ax.set_xlabel("T = t sqrt(2g/a)")
    ax.set_ylabel("Z = x / a")
    ax.set_title(f"Dam-break front, {label}")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)
    print(f"\nmartin_moyce.py: figure written to {args.output}")


if __name__ == "__main__":
    main()
