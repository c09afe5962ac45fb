#!/usr/bin/env python3
"""Where the water behind the box is in a SPHERIC Test 2 run, from its ParaView frames.

    spheric_lee_water.py [--measured CSV] [--from 0.85] [--to 1.1] [--spacing S] RUN

RUN is the output directory of `pbfengine run scenarios/spheric_dambreak.lua -v vtk=T
-v out=RUN` (holding vtk/frame.pvd and probes.csv). For each frame from --from to --to
seconds it prints one row:
  - the lee gauge's reading (x = 0.496 m, probes.csv, interpolated to the frame's time) and
    the measured height then;
  - the water in the 0.1 x 0.1 m column around the gauge's line, as a depth (particles times
    their volume s^3, s the spacing from RUN/run.log or --spacing, over the column's area), all of it and the part below z = 0.1 m,
    on the floor, and its mean vertical velocity;
  - the water in the box's lee (0 <= x <= 0.6635 m across the box's width, 0.2955 <= y <=
    0.6985 m), in litres: all of it, and the part above z = 0.2 m within 0.07 m of the wall
    x = 0 (the sheet that runs up that wall).
The gauge reads the highest level where the fluid fraction reaches 1/2 (compute `gauge`), so
water falling through its line counts; the column's floor part says whether the floor is wet.
"""
import argparse
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
sys.path.insert(0, HERE)
import vtu  # noqa: E402  (share/vtu.py)
from spheric_compare import MEASURED, read_csv  # noqa: E402

GAUGE_X, GAUGE_Y, HALF = 0.496, 0.5, 0.05   # the gauge's line, the column's half width (m)
LEE = (0.0, 0.6635, 0.2955, 0.6985)         # x and y bounds of the box's lee (m)
FLOOR, WALL_SHEET_X, WALL_SHEET_Z = 0.1, 0.07, 0.2


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run")
    ap.add_argument("--measured", default=MEASURED)
    ap.add_argument("--from", dest="t0", type=float, default=0.85)
    ap.add_argument("--to", dest="t1", type=float, default=1.1)
    ap.add_argument("--spacing", type=float, help="the lattice spacing (m), if RUN has no run.log")
    args = ap.parse_args()
    pvd = os.path.join(args.run, "vtk", "frame.pvd")
    if not os.path.exists(pvd):
        raise SystemExit(f"{pvd}: no such file (run the scenario with -v vtk=0.01)")
    probes = read_csv(os.path.join(args.run, "probes.csv"))
    measured = read_csv(args.measured)
    try:
        frames = [(t, path) for t, path in vtu.read_pvd(pvd) if args.t0 <= t <= args.t1]
    except vtu.VtuError as e:
        raise SystemExit(str(e))
    if not frames:
        raise SystemExit(f"{pvd}: no frame between {args.t0} and {args.t1} s")

    # The scenario's particles share one mass, rho0 s^3 (the lattice's spacing s).
    particle_volume = (args.spacing or logged_spacing(args.run)) ** 3
    print("| t (s) | gauge (m) | measured (m) | column water (mm) | on the floor (mm) "
          "| column's mean vz (m/s) | lee water (L) | wall sheet (L) |")
    print("|---|---|---|---|---|---|---|---|")
    for t, path in frames:
        try:
            points, arrays = vtu.read_vtu(path)
        except vtu.VtuError as e:
            raise SystemExit(str(e))
        volume = np.full(len(points), particle_volume)
        x, y, z = points[:, 0], points[:, 1], points[:, 2]
        column = (np.abs(x - GAUGE_X) < HALF) & (np.abs(y - GAUGE_Y) < HALF)
        lee = (x >= LEE[0]) & (x <= LEE[1]) & (y >= LEE[2]) & (y <= LEE[3])
        sheet = lee & (x < WALL_SHEET_X) & (z > WALL_SHEET_Z)
        area = (2 * HALF) ** 2
        vz = arrays["velocity"][column, 2].mean() if column.any() else math.nan
        gauge = np.interp(t, probes["time"], probes["H.x0496"])
        height = np.interp(t, measured["time_s"], measured["h_x0.496_m"])
        print(f"| {t:.3f} | {gauge:.3f} | {height:.3f} | {1e3 * volume[column].sum() / area:.1f} "
              f"| {1e3 * volume[column & (z < FLOOR)].sum() / area:.1f} | {vz:+.2f} "
              f"| {1e3 * volume[lee].sum():.1f} | {1e3 * volume[sheet].sum():.1f} |")


def logged_spacing(run):
    """The lattice spacing from the scenario's line '... particles, spacing S m' in RUN/run.log."""
    log = os.path.join(run, "run.log")
    if os.path.exists(log):
        with open(log) as f:
            for line in f:
                if line.startswith("spheric (") and "spacing" in line:
                    return float(line.split("spacing")[1].split()[0])
    raise SystemExit(f"{log}: no line giving the spacing; pass --spacing S")


if __name__ == "__main__":
    main()
