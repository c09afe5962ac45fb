#!/usr/bin/env python3
"""Plot a thermo CSV written by pbfengine (pbf.thermo{..., csv = FILE}) against time.

Usage:
    python3 share/plot_thermo.py out/thermo.csv                  # -> out/thermo.png
    python3 share/plot_thermo.py thermo.csv --columns err.avg,ke -o energy.png

The file is the engine's: a header line naming the columns (step,time,dt,particles,
then one per compute value, e.g. err.avg,err.max,ke,front), then one row per thermo
line. A run that changes its thermo columns writes a new header line part way; each
column is then plotted over the rows that have it. One subplot per column, sharing the
time axis (or the step, or the row number, when the file has no time column). Default
columns: all but step, time, dt and particles.

Needs numpy and matplotlib (Debian: apt install python3-numpy python3-matplotlib, then
run with /usr/bin/python3).
"""
import argparse
import math
import os
import sys

try:
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")  # no display needed; must precede pyplot
    import matplotlib.pyplot as plt
except ImportError as e:
    sys.exit(f"plot_thermo.py: error: {e}; install python3-numpy and python3-matplotlib "
             "(Debian) and run with /usr/bin/python3")

BUILTIN = ("step", "time", "dt", "particles")


def fail(msg):
    sys.exit(f"plot_thermo.py: error: {msg}")


def is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


def read_thermo(path):
    """{column: list of (row, value)} in file order, and the column names in order."""
    try:
        with open(path) as f:
            lines = f.read().splitlines()
    except (OSError, UnicodeDecodeError) as e:
        fail(f"cannot read {path}: {getattr(e, 'strerror', None) or e}")
    data, order, header, row = {}, [], None, 0
    for lineno, line in enumerate(lines, 1):
        fields = [f.strip() for f in line.split(",")]
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        if not all(is_number(f) for f in fields):  # a (new) header line
            header = fields
            for name in header:
                if name not in data:
                    data[name], order = [], order + [name]
            continue
        if header is None:
            fail(f"{path}:{lineno}: numbers before any header line")
        if len(fields) != len(header):
            fail(f"{path}:{lineno}: {len(fields)} fields, the header has {len(header)}")
        for name, value in zip(header, fields):
            data[name].append((row, float(value)))
        row += 1
    if row == 0:
        fail(f"{path}: no data rows")
    return data, order


def main(argv=None):
    p = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], epilog=__doc__.split("\n\n", 1)[1],
        formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("csv", help="thermo CSV file")
    p.add_argument("-o", "--output", help="PNG to write (default: the CSV's name with .png)")
    p.add_argument("--columns", help="comma-separated columns to plot (default: all but "
                   + ", ".join(BUILTIN) + ")")
    p.add_argument("--width", type=float, default=8.0, help="figure width in inches (default 8)")
    args = p.parse_args(argv)

    data, order = read_thermo(args.csv)
    if args.columns:
        columns = [c.strip() for c in args.columns.split(",") if c.strip()]
        unknown = [c for c in columns if c not in data]
        if unknown:
            fail(f"no column {', '.join(unknown)} in {args.csv}; it has: {', '.join(order)}")
    else:
        columns = [c for c in order if c not in BUILTIN]
    if not columns:
        fail(f"nothing to plot: {args.csv} has only {', '.join(order)}; "
             "name columns with --columns")
    xname = next((c for c in ("time", "step") if c in data), None)
    xof = dict(data[xname]) if xname else {}
    out = args.output or os.path.splitext(args.csv)[0] + ".png"

    fig, axes = plt.subplots(len(columns), 1, sharex=True, squeeze=False,
                             figsize=(args.width, 1.0 + 2.0 * len(columns)))
    for ax, name in zip(axes[:, 0], columns):
        rows = [(xof.get(r, math.nan) if xname else r, v) for r, v in data[name]]
        xy = np.array(rows, dtype=float).reshape(-1, 2)
        ax.plot(xy[:, 0], xy[:, 1], lw=1.2)
        ax.set_ylabel(name)
        ax.grid(True, alpha=0.3)
    axes[-1, 0].set_xlabel({"time": "time (s)", "step": "step"}.get(xname, "thermo row"))
    fig.suptitle(os.path.basename(args.csv))
    fig.tight_layout()
    try:
        fig.savefig(out, dpi=100)
    except OSError as e:
        fail(f"cannot write {out}: {e.strerror}")
    print(f"plot_thermo.py: {len(columns)} column(s) against {xname or 'row'} in {out}",
          file=sys.stderr)


if __name__ == "__main__":
    main()
