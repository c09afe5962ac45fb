"""Plot the floating boxes of share/validate_archimedes.sh: the body's centre z(t) for each
case, one panel per solver and relative density, one line per resolution (and, dashed, the
runs released off their expected draft), with each run's rest centre expected from its
measured water level (dotted: mean level over 6-10 s - rel a + a / 2).

    python3 share/validation/plot_archimedes.py WORK OUT.png

WORK holds the runs' thermo CSV files, named SOLVER_relREL_nN[_TAG].csv."""
import csv
import glob
import os
import re
import sys

A = 0.1  # the body's height (m)


def load(path):
    rows = list(csv.DictReader(line for line in open(path) if not line.startswith("#")))
    return {key: [float(r[key]) for r in rows] for key in rows[0]}


def level(d, i):
    gauges = [k for k in d if k.startswith("g.h")]
    return sum(d[k][i] for k in gauges) / len(gauges)


def main():
    if len(sys.argv) != 3:
        sys.exit("plot_archimedes.py: error: usage: plot_archimedes.py WORK OUT.png")
    work, out = sys.argv[1], sys.argv[2]
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    runs = {}
    for path in sorted(glob.glob(os.path.join(work, "*.csv"))):
        m = re.match(r"(pbf|wcsph)_rel([0-9.]+)_n(\d+)(?:_(\w+))?\.csv$", os.path.basename(path))
        if m:
            runs[(m.group(1), float(m.group(2)), int(m.group(3)), m.group(4) or "")] = load(path)
    if not runs:
        sys.exit(f"plot_archimedes.py: error: no SOLVER_relREL_nN.csv in {work}")
    solvers = [s for s in ("pbf", "wcsph") if any(k[0] == s for k in runs)]
    rels = sorted({k[1] for k in runs})
    ns = sorted({k[2] for k in runs})
    colours = dict(zip(ns, ["tab:blue", "tab:orange", "tab:green", "tab:red"]))
    fig, axes = plt.subplots(len(rels), len(solvers), figsize=(6.5 * len(solvers), 3.2 * len(rels)),
                             squeeze=False, sharex=True)
    for col, solver in enumerate(solvers):
        for row, rel in enumerate(rels):
            ax = axes[row][col]
            for (s, r, n, tag), d in sorted(runs.items()):
                if s != solver or r != rel:
                    continue
                t, z = d["time"], [1000 * v for v in d["b.z"]]
                label = f"a/s = {n}" + (f", released {tag}" if tag else "")
                ax.plot(t, z, color=colours[n], lw=1.0, ls="--" if tag else "-", label=label)
                late = [i for i, ti in enumerate(t) if ti >= 6]
                if late and not tag:
                    rest = sum(level(d, i) for i in late) / len(late) - rel * A + A / 2
                    ax.axhline(1000 * rest, color=colours[n], lw=0.8, ls=":")
            ax.set_title(f"{solver.upper()}, relative density {rel:g}", fontsize=10)
            ax.set_ylabel("body centre z (mm)")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=6.5, loc="upper right", ncol=3 if len(ax.get_lines()) > 6 else 1)
            if row == len(rels) - 1:
                ax.set_xlabel("t (s)")
    fig.suptitle("Floating box, heave only: centre z(t); dotted: the rest centre Archimedes gives for the measured "
                 "water level (runs released at draft)", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
