#!/usr/bin/env python3
"""Resting columns under DFSPH: how still, at which tolerances, resolutions, depths and walls.

Runs scenarios/hydrostatic.lua with -v solver=dfsph for each case (a column `height` deep on a
square floor `width` wide, at spacing s, in the box or in a mesh container) to t = 1.2 s and
reports, after 1 s (the issue's bounds: a mean speed below 0.005 m/s and no particle above
0.02 m/s), the mean and the largest speed (the thermo lines from t = 1 s on: their largest),
the column's top against its start, the iterations per step of both solves, and the wall time.
Writes a Markdown table to stdout, for docs/validation/dfsph.md.

    /usr/bin/python3 share/validation/dfsph_still.py [--binary build/pbfengine] [--quick]

--quick runs the 1 cm cases only.
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from machine import machine  # noqa: E402

# (label, spacing m, height m, width m, walls, extra variables)
TIGHT = ["error=1e-5", "divergence_error=1e-4"]       # the scenario's defaults
DEFAULTS = ["error=1e-4", "divergence_error=1e-3"]    # the style's (SPlisHSPlasH's)
CASES = [
    ("10 mm, 10 cm, box", 0.01, 0.1, 0.1, "box", TIGHT),
    ("10 mm, 20 cm, box", 0.01, 0.2, 0.1, "box", TIGHT),
    ("10 mm, 20 cm, box, the style's tolerances", 0.01, 0.2, 0.1, "box", DEFAULTS),
    ("10 mm, 20 cm, box, water's viscosity", 0.01, 0.2, 0.1, "box", TIGHT + ["nu=1e-6"]),
    ("10 mm, 10 cm, mesh", 0.01, 0.1, 0.1, "mesh", TIGHT),
    ("10 mm, 20 cm, mesh", 0.01, 0.2, 0.1, "mesh", TIGHT),
    ("5 mm, 10 cm, box", 0.005, 0.1, 0.05, "box", TIGHT),
    ("5 mm, 20 cm, box", 0.005, 0.2, 0.05, "box", TIGHT),
    ("5 mm, 20 cm, mesh", 0.005, 0.2, 0.05, "mesh", TIGHT),
]


def run(binary, work, label, s, height, width, walls, extra):
    n = round(width / s) ** 2 * round(height / s)
    path = os.path.join(work, f"{abs(hash(label))}.csv")
    command = [binary, "run", os.path.join(ROOT, "scenarios", "hydrostatic.lua"), "-v", "solver=dfsph",
               "-v", f"particles={n}", "-v", f"height={height}", "-v", f"width={width}", "-v", f"walls={walls}",
               "-v", "t_end=1.2", "-v", f"csv={path}", "--log", "none"]
    for v in extra:
        command += ["-v", v]
    start = time.time()
    result = subprocess.run(command, capture_output=True, text=True)
    seconds = time.time() - start
    if result.returncode != 0:
        return f"| {label} | failed: {result.stdout.strip().splitlines()[-1] if result.stdout else result.stderr} |"
    with open(path) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    late = [r for r in rows if float(r["time"]) >= 1.0]
    mean = max(float(r["v.avg"]) for r in late)
    most = max(float(r["v.max"]) for r in late)
    top0, top = float(rows[0]["top"]), float(late[-1]["top"])
    iterations = sum(float(r["it.avg"]) for r in late) / len(late)
    divergence = sum(float(r["div.avg"]) for r in late) / len(late)
    ok = "yes" if mean < 0.005 and most < 0.02 else "no"
    return (f"| {label} | {n} | {mean * 1000:.2f} | {most * 1000:.1f} | {ok} | {(top - top0) * 1000:+.1f} | "
            f"{iterations:.0f} | {divergence:.1f} | {seconds:.0f} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "pbfengine"))
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    cases = [c for c in CASES if not args.quick or c[1] == 0.01]
    print(f"Measured {time.strftime('%Y-%m-%d', time.gmtime())} on {machine()} by "
          "`share/validation/dfsph_still.py`: scenarios/hydrostatic.lua with -v solver=dfsph (dfsph, a Laplacian "
          "viscosity nu = 1e-3 m^2/s unless said, cfl with courant 0.4 and at most 0.4 h / sqrt(2 g H)), to "
          "t = 1.2 s. Speeds: the largest thermo line's from t = 1 s on. Top: the 99th percentile of z, "
          "against its start. Iterations: per step, averaged from t = 1 s.\n")
    print("| case | particles | mean speed (mm/s) | fastest (mm/s) | within 5 and 20 mm/s | top (mm) "
          "| density iterations | divergence iterations | wall s |")
    print("|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as work:
        for case in cases:
            print(run(args.binary, work, *case), flush=True)


if __name__ == "__main__":
    main()
