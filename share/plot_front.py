#!/usr/bin/env python3
"""Plot a dam break's surge front against Martin & Moyce (1952), column of height 2a.

Usage:
    python3 share/plot_front.py thermo.csv --a 0.2 -o front.png
    python3 share/plot_front.py coarse.csv fine.csv --a 0.2 --label "30k" --label "240k"
    python3 share/plot_front.py run.csv --a 0.2 --column front_p99 --time-column time

Each CSV is a thermo file written by pbfengine: one header row of column names, then
numeric rows. The front column (default 'front') holds the x position of the surge
front, best a high percentile of the particles' x rather than the farthest particle;
the time column (default 'time') holds t in seconds. Both are made dimensionless:

    Z = (x_front - x0) / a          T = t * sqrt(2 g / a)

where a is the initial column width (the column is 2a high) and x0 the x of the wall
behind the column (default 0). The figure shows each CSV as a curve, Martin & Moyce's
measured points for n^2 = 2, and the three reference points of the project's issue,
(T, Z) = (1, 1.32), (2, 2.35), (3, 3.70). A Markdown table on stdout gives each run's
Z interpolated at T = 1, 2, 3 ('n/a' outside the run's time range), ready to paste
into a report.

Needs numpy and matplotlib (on Debian: apt install python3-numpy python3-matplotlib,
then run with /usr/bin/python3).
"""
import argparse
import csv
import math
import os
import sys

try:
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")  # no display needed; must precede pyplot
    import matplotlib.pyplot as plt
except ImportError as e:
    sys.exit(f"plot_front.py: error: {e}; install python3-numpy and python3-matplotlib "
             "(Debian) and run with /usr/bin/python3")

# Martin & Moyce (1952), surge front for n^2 = 2 (column height 2a): measured (T, Z).
MARTIN_MOYCE = [(0.41, 1.11), (0.84, 1.22), (1.19, 1.44), (1.43, 1.67), (1.63, 1.89),
                (1.83, 2.11), (1.98, 2.33), (2.20, 2.56), (2.32, 2.78), (2.51, 3.00),
                (2.65, 3.22), (2.83, 3.44), (2.98, 3.67)]
# The reference values stated in the project's issue, checked at T = 1, 2, 3.
REFERENCE = [(1.0, 1.32), (2.0, 2.35), (3.0, 3.70)]


def fail(msg):
    sys.exit(f"plot_front.py: error: {msg}")


def read_csv(path, time_col, front_col):
    """Return (t, x) arrays from a thermo CSV, sorted by time."""
    try:
        with open(path, newline="") as f:
            reader = csv.reader(f)  # keep file line numbers for error messages
            rows = [(reader.line_num, r) for r in reader
                    if any(c.strip() for c in r) and not r[0].startswith("#")]  # "# units: ..."
    except OSError as e:
        fail(f"cannot read {path}: {e.strerror}")
    except (csv.Error, UnicodeDecodeError) as e:
        fail(f"{path}: not a readable CSV file ({e})")
    if not rows:
        fail(f"{path} is empty")
    header = [c.strip() for c in rows[0][1]]
    for col in (time_col, front_col):
        if col not in header:
            fail(f"{path}: no column {col!r}; the header has: {', '.join(header)}")
    it, ix = header.index(time_col), header.index(front_col)
    t, x = [], []
    for lineno, r in rows[1:]:
        try:
            tv, xv = float(r[it]), float(r[ix])
        except (IndexError, ValueError):
            fail(f"{path}:{lineno}: missing or non-numeric {time_col!r}/{front_col!r} value")
        if not (math.isfinite(tv) and math.isfinite(xv)):
            fail(f"{path}:{lineno}: non-finite value (NaN or inf)")
        t.append(tv)
        x.append(xv)
    if len(t) < 2:
        fail(f"{path}: fewer than two data rows; nothing to plot")
    order = np.argsort(t, kind="stable")  # np.interp needs increasing time
    return np.asarray(t)[order], np.asarray(x)[order]


def z_at(T, Z, t_query):
    """Z interpolated at t_query, or None outside the data's range."""
    if t_query < T[0] or t_query > T[-1]:
        return None
    return float(np.interp(t_query, T, Z))


def parse_args(argv):
    p = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], epilog=__doc__.split("\n\n", 1)[1],
        formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("csv", nargs="+", help="thermo CSV file(s), one curve each")
    p.add_argument("--a", type=float, required=True, help="initial column width a (m)")
    p.add_argument("--g", type=float, default=9.81, help="gravity (m/s^2, default 9.81)")
    p.add_argument("--column", default="front",
                   help="CSV column holding the front x position (default 'front')")
    p.add_argument("--time-column", default="time", help="CSV column of time (default 'time')")
    p.add_argument("--x0", type=float, default=0.0,
                   help="x of the wall behind the column (default 0)")
    p.add_argument("--label", action="append",
                   help="legend label, once per CSV in order (default: the file name)")
    p.add_argument("-o", "--output", default="front.png",
                   help="output image (default front.png; .pdf/.svg work too)")
    p.add_argument("--title", default=None, help="figure title")
    args = p.parse_args(argv)
    for name in ("a", "g"):
        v = getattr(args, name)
        if not (math.isfinite(v) and v > 0):
            fail(f"--{name} must be positive, got {v!r}")
    if not math.isfinite(args.x0):
        fail(f"--x0 must be finite, got {args.x0!r}")
    if args.label and len(args.label) != len(args.csv):
        fail(f"{len(args.label)} --label given for {len(args.csv)} CSV files; give one per file")
    out_dir = os.path.dirname(os.path.abspath(args.output))
    if not os.path.isdir(out_dir):
        fail(f"the directory for -o {args.output!r} does not exist")
    return args


def main(argv=None):
    args = parse_args(argv)
    labels = args.label or [os.path.basename(p) for p in args.csv]
    scale = math.sqrt(2.0 * args.g / args.a)

    fig, ax = plt.subplots(figsize=(7, 5), dpi=120)
    table = []
    t_max = 3.5
    for path, label in zip(args.csv, labels):
        t, x = read_csv(path, args.time_column, args.column)
        T, Z = t * scale, (x - args.x0) / args.a
        t_max = max(t_max, float(T[-1]))
        ax.plot(T, Z, "-", lw=1.8, label=label)
        table.append((label, [z_at(T, Z, tq) for tq, _ in REFERENCE], T[0], T[-1]))

    mT, mZ = zip(*MARTIN_MOYCE)
    ax.plot(mT, mZ, "o", mfc="none", mec="k", ms=6, label="Martin & Moyce (1952), $n^2=2$")
    rT, rZ = zip(*REFERENCE)
    ax.plot(rT, rZ, "*", color="crimson", ms=13, zorder=5, label="reference points (issue)")
    for tr, zr in REFERENCE:
        ax.annotate(f"{zr:.2f}", (tr, zr), textcoords="offset points", xytext=(8, -12),
                    color="crimson", fontsize=9)
    ax.set_xlim(0, min(t_max, 10.0))
    ax.set_ylim(bottom=0)
    ax.set_xlabel(r"$T = t\,\sqrt{2g/a}$")
    ax.set_ylabel(r"$Z = (x_{front} - x_0)\,/\,a$")
    ax.set_title(args.title or f"Dam-break surge front, column 2a high (a = {args.a:g} m)")
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", fontsize=9)
    fig.tight_layout()
    try:
        fig.savefig(args.output)
    except (OSError, ValueError) as e:
        fail(f"cannot write {args.output}: {e}")
    print(f"plot_front.py: figure written to {args.output}", file=sys.stderr)

    # Markdown table: reference row first, then one row per run.
    cols = " | ".join(f"Z at T={tq:g}" for tq, _ in REFERENCE)
    print(f"| run | {cols} | T range |")
    print("|---" * (len(REFERENCE) + 2) + "|")
    ref = " | ".join(f"{zr:.2f}" for _, zr in REFERENCE)
    print(f"| Martin & Moyce (reference) | {ref} | |")
    for label, zs, t0, t1 in table:
        cells = " | ".join("n/a" if z is None else f"{z:.2f} ({100 * (z / zr - 1):+.0f}%)"
                           for z, (_, zr) in zip(zs, REFERENCE))
        print(f"| {label} | {cells} | {t0:.2f}-{t1:.2f} |")


if __name__ == "__main__":
    main()
