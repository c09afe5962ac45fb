#!/usr/bin/env python3
"""The first sloshing mode of scenarios/standing_wave.lua against linear theory.

Reads the run's thermo CSV and fits, by least squares, a damped cosine

    d(t) = c + B exp(-gamma t) cos(omega t + phi)

to d = in.left - in.right, the water heights an eighth of the tank from each end (the first
mode's signal: the mean level and the even modes cancel; away from the walls by more than a
kernel radius). omega and gamma are searched on a grid and refined, c, B and phi solved
linearly at each. Reports the period 2 pi / omega against linear theory,

    omega_0^2 = g k tanh(k H),   k = pi / L,

and the amplitude kept per period, exp(-gamma 2 pi / omega) (1: no damping).

    /usr/bin/python3 share/validation/standing_wave.py thermo.csv [--length 0.4] [--depth 0.2]
"""
import argparse
import csv
import math
import sys

import numpy as np


def residual(t, d, omega, gamma):
    e = np.exp(-gamma * t)
    M = np.column_stack([np.ones_like(t), e * np.cos(omega * t), e * np.sin(omega * t)])
    coef, res, *_ = np.linalg.lstsq(M, d, rcond=None)
    r = d - M @ coef
    return float(r @ r), coef


def fit(t, d, omega0):
    best = (float("inf"), omega0, 0.0)
    for omega in np.linspace(0.5 * omega0, 1.5 * omega0, 201):
        for gamma in np.linspace(0, omega0 / 2, 51):
            r, _ = residual(t, d, omega, gamma)
            best = min(best, (r, omega, gamma))
    _, omega, gamma = best
    step_w, step_g = omega0 / 200, omega0 / 100
    for _ in range(40):  # pattern search around the grid's best
        moved = False
        for dw, dg in ((step_w, 0), (-step_w, 0), (0, step_g), (0, -step_g)):
            r, _ = residual(t, d, omega + dw, max(0.0, gamma + dg))
            if r < best[0]:
                best, omega, gamma, moved = (r, omega + dw, max(0.0, gamma + dg)), omega + dw, max(0.0, gamma + dg), True
        if not moved:
            step_w, step_g = step_w / 2, step_g / 2
    _, coef = residual(t, d, omega, gamma)
    return omega, gamma, math.hypot(coef[1], coef[2])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv")
    ap.add_argument("--length", type=float, default=0.4, help="L (m)")
    ap.add_argument("--depth", type=float, default=0.2, help="H (m)")
    args = ap.parse_args()
    try:
        with open(args.csv) as f:
            rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    except OSError as e:
        sys.exit(f"standing_wave.py: {args.csv}: {e.strerror}")
    if not rows or "in.left" not in rows[0] or "in.right" not in rows[0]:
        sys.exit(f"standing_wave.py: {args.csv}: needs columns time, in.left, in.right (scenarios/standing_wave.lua)")
    t = np.array([float(r["time"]) for r in rows])
    d = np.array([float(r["in.left"]) - float(r["in.right"]) for r in rows])
    k = math.pi / args.length
    omega0 = math.sqrt(9.81 * k * math.tanh(k * args.depth))
    omega, gamma, amplitude = fit(t, d, omega0)
    period, theory = 2 * math.pi / omega, 2 * math.pi / omega0
    print(f"period {period:.4f} s, linear theory {theory:.4f} s, error {100 * (period / theory - 1):+.1f}%, "
          f"amplitude kept per period {math.exp(-gamma * period):.3f}, fitted amplitude of d {amplitude:.4f} m")


if __name__ == "__main__":
    main()
