#!/usr/bin/env python3
"""The dam break in a tank periodic across its width against the closed tank (issue 32).

    share/validation/periodic_dambreak.py [--binary build/pbfengine] [--particles 8000 30000]

scenarios/dambreak.lua (Martin & Moyce's column, a wide and 2a high, in a tank a/2 wide) runs
twice at each resolution: with the box's side walls (y = 0 and y = a/2, free slip with the
wall density) and with the tank periodic along y (no side walls: an endless tank). The flow
is quasi-2D, so the surge fronts (99th percentile of x) should agree. Prints Z = front / a
against T = t sqrt(2 g / a) for both, and the largest relative difference until the front
reaches the far wall (Z = 5). Report: docs/validation/periodic.md.
"""
import argparse
import csv
import math
import os
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
A, G = 0.1, 9.81


def thermo(binary, particles, periodic, work):
    out = os.path.join(work, f"n{particles}{periodic}")
    command = [binary, "run", os.path.join(ROOT, "scenarios", "dambreak.lua"), "--log", "none",
               "-v", f"particles={particles}", "-v", "t_end=0.26", "-v", "restart_interval=0", "-v", f"out={out}"]
    if periodic:
        command += ["-v", f"periodic={periodic}"]
    subprocess.run(command, check=True, capture_output=True)
    with open(os.path.join(out, "thermo.csv")) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    return [(float(r["time"]), float(r["front"])) for r in rows]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "pbfengine"))
    parser.add_argument("--particles", type=int, nargs="+", default=[8000, 30000])
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as work:
        for n in args.particles:
            closed, periodic = thermo(args.binary, n, "", work), thermo(args.binary, n, "y", work)
            worst, at = 0.0, 0.0
            print(f"{n} particles: T, Z closed, Z periodic in y")
            for k, ((t, a), (_, b)) in enumerate(zip(closed, periodic)):
                if a / A < 4.9:  # until the front reaches the far wall
                    d = abs(b / a - 1)
                    worst, at = max((worst, at), (d, t * math.sqrt(2 * G / A)))
                if k % 5 == 0:
                    print(f"  {t * math.sqrt(2 * G / A):5.2f}  {a / A:6.3f}  {b / A:6.3f}")
            print(f"  largest relative difference {100 * worst:.2f}% at T = {at:.2f}")


if __name__ == "__main__":
    main()
