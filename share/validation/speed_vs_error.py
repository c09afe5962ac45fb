#!/usr/bin/env python3
"""Speed against error: what each setting of PBF, WCSPH and DFSPH costs and what it buys.

Runs the tall column of Martin & Moyce (1952) through scenarios/dambreak.lua (the runner and
scores of share/validation/martin_moyce.py: a = 0.05715 m, 2a high, front = 99.5th percentile
of x plus s/2, T <= 3), changing one setting at a time around the defaults:

    PBF    iterations 1 to 32; accuracy targets (error = mean compression 1%, 0.3%, 0.1%);
           time step x1/2 and x2; resolution; precision (double against the default float)
    WCSPH  sound speed x1/2 and x2 (its stiffness); Courant number x1/2 and x2; resolution;
           precision
    DFSPH  density tolerance 0.1%, 0.03%, 0.001% (default 0.01%); divergence tolerance x10;
           Courant number x1/2 and x2 (the scenario's step, PBF's, caps it: x2 doubles the cap too);
           the Laplacian viscosity nu 1e-4 in place of 1e-3 (its explicit limit on the step, (h/2)^2
           / (8 nu), binds at fine resolution), at the defaults' resolution and twice it;
           resolution; precision

and records for each run

    cost          seconds per simulated second on one core: the run's CPU time (median of
                  --repeats runs) with one OpenMP thread, which is its wall time on an idle
                  core and, unlike wall time, does not grow when other jobs share the machine
    compression   the mean compression, mean of max(rho/rho0 - 1, 0), averaged over the run
    worst         the largest rho/rho0 - 1 of any particle at any thermo line
    RMS(Z)        the front's error against the experiment (and the farthest particle's)

It prints a Markdown table (the Pareto-optimal runs marked: no other run is both cheaper and
closer to the experiment) and the observed order of convergence of Z(T = 1, 2, 3) and of the
compression from the resolution runs (8, 16, 32 particles across a for PBF), and draws error
against cost, each solver a curve through its own Pareto front, the overall front marked
(docs/validation/speed_vs_error.png unless -o).

    /usr/bin/python3 share/validation/speed_vs_error.py [--binary build/pbfengine]
        [--double-binary build-double/pbfengine] [--across 16] [--repeats 3] [--only pbf|wcsph|dfsph]
        [--merge TABLE] [--no-plot] [-o PNG]

--merge takes the other solvers' rows from the table an earlier run printed (with --only, one
solver is measured again and the table and plot still show all three).
"""
import argparse
import math
import os
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import martin_moyce as mm  # noqa: E402  (the runner and the scores)

ROOT = mm.ROOT


def variants(across):
    """(solver, axis, label, particles across a, precision, -v settings) around the defaults."""
    s = mm.A / across
    dt = 0.4 * 2 * s / math.sqrt(2 * mm.G * 2 * mm.A)  # dambreak.lua's PBF step, 0.4 h at the free-fall speed
    c0 = 10 * math.sqrt(2 * mm.G * 2 * mm.A)           # wcsph's default sound speed
    courant = 0.15                                     # cfl's default
    runs = [("pbf", "default", "defaults (4 iterations)", across, "float", [])]
    runs += [("pbf", "iterations", f"{k} iteration" + ("s" if k > 1 else ""), across, "float", [f"iterations={k}"]) for k in (1, 2, 8, 16, 32)]
    runs += [("pbf", "target", f"error {e:g}", across, "float", [f"error={e}", "max_iterations=100"])
             for e in (0.01, 0.003, 0.001)]
    runs += [("pbf", "time step", f"dt x{f:g}", across, "float", [f"dt={f * dt}"]) for f in (0.5, 2)]
    runs += [("pbf", "resolution", f"{n} across a", n, "float", []) for n in (8, 12, 24, 32) if n != across]
    runs += [("pbf", "precision", "double", across, "double", [])]
    w = ["solver=wcsph"]
    runs += [("wcsph", "default", "defaults (c0 = 10 sqrt(2 g H), Courant 0.15)", across, "float", w)]
    runs += [("wcsph", "stiffness", f"c0 x{f:g}", across, "float", w + [f"sound_speed={f * c0}"]) for f in (0.5, 2)]
    runs += [("wcsph", "time step", f"Courant {f * courant:g}", across, "float", w + [f"courant={f * courant}"])
             for f in (0.5, 2)]
    runs += [("wcsph", "resolution", f"{n} across a", n, "float", w) for n in (8, 12, 24, 32) if n != across]
    runs += [("wcsph", "precision", "double", across, "double", w)]
    d = ["solver=dfsph"]
    runs += [("dfsph", "default", "defaults (error 0.01%, divergence 0.1%, Courant 0.4)", across, "float", d)]
    runs += [("dfsph", "target", f"error {100 * e:g}%", across, "float", d + [f"error={e}", "max_iterations=1000"])
             for e in (0.001, 0.0003, 0.00001)]
    runs += [("dfsph", "divergence", "divergence 1%", across, "float", d + ["divergence_error=0.01"])]
    runs += [("dfsph", "time step", "Courant 0.2", across, "float", d + ["courant=0.2"])]
    runs += [("dfsph", "time step", "Courant 0.8, dt cap x2", across, "float", d + ["courant=0.8", f"dt={2 * dt}"])]
    runs += [("dfsph", "viscosity", "nu 1e-4", across, "float", d + ["nu=1e-4"])]
    runs += [("dfsph", "resolution", f"{n} across a", n, "float", d) for n in (8, 12, 24, 32) if n != across]
    runs += [("dfsph", "viscosity", f"nu 1e-4, {2 * across} across a", 2 * across, "float", d + ["nu=1e-4"])]
    runs += [("dfsph", "precision", "double", across, "double", d)]
    return runs


def read_table(path):
    """The rows of a table this script printed (for --merge)."""
    rows = []
    try:
        f = open(path)
    except OSError as e:
        sys.exit(f"speed_vs_error.py: --merge {path}: {e.strerror}")
    with f:
        for line in f:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) != 11 or cells[0] not in ("pbf", "wcsph", "dfsph"):
                continue
            solver, axis, label, across, precision, cost, compression, worst, rms, far, z = cells
            rows.append(dict(solver=solver, axis=axis, label=label.removesuffix(" *"), across=int(across),
                             precision=precision, cost=float(cost.split()[0]),
                             compression=float(compression.rstrip("%")) / 100, worst=float(worst.rstrip("%")) / 100,
                             rms=float(rms), far=float(far), Z=[float(v) for v in z.split(",")]))
    if not rows:
        sys.exit(f"speed_vs_error.py: no table rows in {path}")
    return rows


def pareto(points):
    """Indices of the points (cost, error) that no other point beats on both."""
    front = []
    for i, (c, e) in enumerate(points):
        if not any((c2 <= c and e2 <= e) and (c2 < c or e2 < e) for c2, e2 in points):
            front.append(i)
    return sorted(front, key=lambda i: points[i][0])


def order(coarse, mid, fine):
    """Observed order from three resolutions, each twice the last: log2 of the ratio of changes."""
    a, b = abs(mid - coarse), abs(fine - mid)
    return math.log2(a / b) if a > 0 and b > 0 else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "pbfengine"))
    ap.add_argument("--double-binary", default=os.path.join(ROOT, "build-double", "pbfengine"),
                    help="a build with -DPBF_REAL=double (its runs are left out if it is missing)")
    ap.add_argument("--across", type=int, default=16, help="particles across a at the defaults")
    ap.add_argument("--repeats", type=int, default=3, help="runs per variant; the cost is their median")
    ap.add_argument("--only", choices=["pbf", "wcsph", "dfsph"], help="one solver's runs only")
    ap.add_argument("--merge", help="an earlier run's printed table: its rows of the solvers not run now are kept")
    ap.add_argument("--no-plot", action="store_true")
    ap.add_argument("-o", "--output", default=os.path.join(ROOT, "docs", "validation", "speed_vs_error.png"))
    args = ap.parse_args()
    os.environ["OMP_NUM_THREADS"] = "1"  # the runs inherit it
    if args.repeats < 1:
        sys.exit("speed_vs_error.py: --repeats must be at least 1")
    merged = read_table(args.merge) if args.merge else []  # before the runs: a bad file fails now
    table = mm.read_table(os.path.join(mm.DATA, "martin_moyce_1952_n2_2_front.csv"), 3.0)
    t_end = mm.COLUMNS[2][1] / math.sqrt(mm.G / mm.A)
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for solver, axis, label, across, precision, settings in variants(args.across):
            if args.only and solver != args.only:
                continue
            binary = args.double_binary if precision == "double" else args.binary
            if precision == "double" and not os.access(binary, os.X_OK):
                print(f"speed_vs_error.py: no double build at {binary}: its runs are left out", file=sys.stderr)
                continue
            results = [mm.run(binary, 2, across, settings, work) for _ in range(args.repeats)]
            r = results[0]
            cost = statistics.median(x.cpu for x in results) / t_end
            rows.append(dict(solver=solver, axis=axis, label=label, across=across, precision=precision, cost=cost,
                             compression=r.compression, worst=r.worst, rms=mm.rms(r.T, r.front, table),
                             far=mm.rms(r.T, r.far, table), Z=[mm.interpolate(r.T, r.front, t) for t in (1, 2, 3)]))
            print(f"  {solver} {label}: {cost:.1f} s per simulated s, RMS(Z) {rows[-1]['rms']:.3f}", file=sys.stderr)
    if args.merge:
        measured = {r["solver"] for r in rows}
        rows = [r for r in merged if r["solver"] not in measured] + rows
        order_of = {"pbf": 0, "wcsph": 1, "dfsph": 2}
        rows.sort(key=lambda r: order_of.get(r["solver"], 3))  # stable: each solver's own order kept
    best = set(pareto([(r["cost"], r["rms"]) for r in rows]))
    print(f"Tall column of Martin & Moyce, {len(table)} front points (T <= 3), t_end = {t_end:.3f} s; "
          f"cost = CPU seconds per simulated second at one thread, median of {args.repeats}; * = on the Pareto front "
          "(cost against RMS(Z))\n")
    print("| solver | axis | variant | across a | precision | cost | mean compression | worst rho/rho0 - 1 "
          "| RMS(Z) | RMS(Z), farthest | Z at T = 1, 2, 3 |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for k, r in enumerate(rows):
        mark = " *" if k in best else ""
        print(f"| {r['solver']} | {r['axis']} | {r['label']}{mark} | {r['across']} | {r['precision']} | {r['cost']:.1f} s "
              f"| {100 * r['compression']:.2f}% | {100 * r['worst']:.1f}% | {r['rms']:.3f} | {r['far']:.3f} "
              f"| {', '.join(f'{z:.3f}' for z in r['Z'])} |")
    for solver in ("pbf", "wcsph", "dfsph"):
        res = {r["across"]: r for r in rows if r["solver"] == solver and r["axis"] in ("default", "resolution")}
        trio = [args.across // 2, args.across, 2 * args.across]
        if all(n in res for n in trio):
            c, m, f = (res[n] for n in trio)
            orders = ", ".join(f"{order(c['Z'][k], m['Z'][k], f['Z'][k]):.2f}" for k in range(3))
            print(f"\n{solver}: observed order from {trio[0]}, {trio[1]}, {trio[2]} across a: Z at T = 1, 2, 3: "
                  f"{orders}; mean compression: {order(c['compression'], m['compression'], f['compression']):.2f}")
    if not args.no_plot:
        plot(rows, best, args.output)


def plot(rows, best, output):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.6))
    for ax, key, name in ((axes[0], "rms", "RMS(Z) against Martin & Moyce"),
                          (axes[1], "compression", "mean compression (time average)")):
        for solver, color in (("pbf", "tab:blue"), ("wcsph", "tab:red"), ("dfsph", "tab:green")):
            own = [r for r in rows if r["solver"] == solver]
            if not own:
                continue
            ax.scatter([r["cost"] for r in own], [r[key] for r in own], color=color, s=18, label=solver)
            for r in own:
                ax.annotate(r["label"].split(" (")[0], (r["cost"], r[key]), fontsize=6, xytext=(3, 2),
                            textcoords="offset points")
            front = [own[i] for i in pareto([(r["cost"], r[key]) for r in own])]
            ax.plot([r["cost"] for r in front], [r[key] for r in front], color=color, lw=1)
        overall = [rows[i] for i in pareto([(r["cost"], r[key]) for r in rows])]
        ax.scatter([r["cost"] for r in overall], [r[key] for r in overall], s=90, facecolors="none",
                   edgecolors="k", label="Pareto front (all solvers)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("seconds per simulated second (one core)")
        ax.set_ylabel(name)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    axes[0].set_title("Front error against cost")
    axes[1].set_title("Density error against cost")
    fig.tight_layout()
    fig.savefig(output, dpi=110)
    print(f"\nspeed_vs_error.py: figure written to {output}")


if __name__ == "__main__":
    main()
