#!/usr/bin/env python3
"""Wave height made by the piston of scenarios/wave_flume.lua against linear wavemaker theory.

    python3 share/validation/wave_flume.py --period T --stroke S [--depth d] [--plot PNG] GAUGES.csv

Reads the gauges' CSV (time, one water depth per gauge, columns named eta.xNNN for the gauge at
x = NNN/100 m), and for each gauge takes the waves (zero-down-crossing) from when the fully
grown wave train has reached the gauge (start + x / c_g + 3 T: the paddle's start, two periods
of ramp, one to settle) to the end of the record, and compares their mean height with the piston transfer function

    H / S = 2 (cosh 2kd - 1) / (sinh 2kd + 2kd),   omega^2 = g k tanh(kd)

(Dean & Dalrymple 1991, section 6.3). Prints one markdown table row per gauge. Needs numpy
(and matplotlib for --plot).
"""
import argparse
import csv
import math
import sys

G = 9.81


def wavenumber(period, depth):
    """k from the linear dispersion relation omega^2 = g k tanh(k d), by Newton's method."""
    omega = 2 * math.pi / period
    k = omega * omega / G / math.sqrt(math.tanh(omega * omega * depth / G))  # a close first guess
    for _ in range(50):
        f = G * k * math.tanh(k * depth) - omega * omega
        df = G * math.tanh(k * depth) + G * k * depth / math.cosh(k * depth) ** 2
        k -= f / df
    return k


def piston_height_over_stroke(k, depth):
    kd2 = 2 * k * depth
    return 2 * (math.cosh(kd2) - 1) / (math.sinh(kd2) + kd2)


def group_velocity(period, k, depth):
    c = 2 * math.pi / period / k
    return 0.5 * c * (1 + 2 * k * depth / math.sinh(2 * k * depth))


def wave_heights(t, eta, start):
    """Heights of the waves between zero-down-crossings of eta - mean after `start`."""
    import numpy as np

    keep = t >= start
    t, eta = t[keep], eta[keep]
    if len(eta) < 3:
        return []
    e = eta - eta.mean()
    down = np.where((e[:-1] > 0) & (e[1:] <= 0))[0]
    return [float(e[a:b + 1].max() - e[a:b + 1].min()) for a, b in zip(down[:-1], down[1:])]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("gauges")
    ap.add_argument("--period", type=float, required=True)
    ap.add_argument("--stroke", type=float, required=True)
    ap.add_argument("--depth", type=float,
                    help="still-water depth (m; default: the mean level the first gauge records in its window, "
                         "which is the scenario's depth less the fluid's compression)")
    ap.add_argument("--start", type=float, default=1.0, help="when the paddle started (s; the scenario's `start`)")
    ap.add_argument("--plot", help="write the gauge records with the theory's crest and trough to this PNG")
    args = ap.parse_args()
    import numpy as np

    with open(args.gauges) as f:
        rows = list(csv.reader(f))
    header, data = rows[0], np.array([[float(v) for v in r] for r in rows[1:]])
    t = data[:, 0]
    if args.depth is None:
        # The settled still-water level: the first gauge's mean over its window (the mean of a
        # wave record is the still level), found with the scenario's nominal depth first.
        x0 = int(header[1].split(".x")[-1]) / 100
        k0 = wavenumber(args.period, 0.3)
        window = t >= args.start + x0 / group_velocity(args.period, k0, 0.3) + 3 * args.period
        args.depth = float(data[window, 1].mean()) if window.any() else 0.3
    k = wavenumber(args.period, args.depth)
    ratio = piston_height_over_stroke(k, args.depth)
    H_theory = ratio * args.stroke
    cg = group_velocity(args.period, k, args.depth)
    print(f"T = {args.period} s, d = {args.depth} m: k = {k:.4g} 1/m (L = {2 * math.pi / k:.3g} m, kd = {k * args.depth:.3g}), "
          f"H/S = {ratio:.4g}, H = {H_theory * 1000:.1f} mm for S = {args.stroke * 1000:.0f} mm, c_g = {cg:.3g} m/s")
    print()
    print("| gauge x (m) | waves | H measured (mm) | H theory (mm) | error |")
    print("|---|---|---|---|---|")
    worst = 0.0
    records = []
    for col, name in enumerate(header[1:], start=1):
        x = int(name.split(".x")[-1]) / 100
        start = args.start + x / cg + 3 * args.period
        heights = wave_heights(t, data[:, col], start)
        records.append((x, data[:, col], start))
        if not heights:
            print(f"| {x:.2f} | 0 | - | {H_theory * 1000:.1f} | no full wave after t = {start:.2f} s |")
            worst = math.inf
            continue
        H = float(np.mean(heights))
        err = H / H_theory - 1
        worst = max(worst, abs(err))
        print(f"| {x:.2f} | {len(heights)} | {H * 1000:.1f} | {H_theory * 1000:.1f} | {err * 100:+.1f}% |")
    print()
    print(f"largest deviation from theory: {worst * 100:.1f}%")
    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, axes = plt.subplots(len(records), 1, figsize=(8, 2.2 * len(records)), sharex=True)
        for ax, (x, eta, start) in zip(np.atleast_1d(axes), records):
            ax.plot(t, (eta - args.depth) * 1000, lw=0.8, label=f"gauge at x = {x:.2f} m")
            for sign in (1, -1):
                ax.axhline(sign * H_theory / 2 * 1000, color="k", ls="--", lw=0.6)
            ax.axvline(start, color="gray", lw=0.6)
            ax.set_ylabel("eta (mm)")
            ax.legend(loc="upper left", fontsize=8)
        np.atleast_1d(axes)[-1].set_xlabel("t (s)")
        fig.suptitle(f"piston wavemaker, T = {args.period} s, S = {args.stroke * 1000:.0f} mm, d = {args.depth:.3f} m\n"
                     f"(dashed: linear theory's +-H/2; waves counted right of the grey line)", fontsize=9)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)
    return 0 if worst <= 0.10 else 1


if __name__ == "__main__":
    sys.exit(main())
