#!/usr/bin/env python3
"""Compare SPHERIC Test 2 runs (scenarios/spheric_dambreak.lua) with the MARIN measurements.

    spheric_compare.py [--measured CSV] [--t-max 2] [--threshold 0.02] [--out-dir DIR] [--table FILE]
                       [--no-plots] LABEL=RUN ...

RUN is a run's output directory (holding probes.csv and, if there, run.log) or its probes.csv.
LABEL names the run in the tables and plots (no '=' in it). The measurements default to
../shared/validation/spheric_test2_measured.csv relative to the repository root.

Over 0 <= t <= t-max (2 s) it computes, for the simulation and the measurement alike:
  - the arrival time at each gauge: the first time the height exceeds 0.02 m (--threshold; x = 0.496,
    0.992, 1.488 m, dry at t = 0); for the gauge in the reservoir (x = 2.638 m, wet at
    t = 0), the first time the height falls 0.02 m below its value at t = 0; the crossing
    is interpolated linearly between the samples on either side of it;
  - the RMS height error per gauge: the simulated heights interpolated linearly to the
    measurement's times (about 1 kHz), over the times both cover up to t-max;
  - the time P1 first exceeds 2 kPa (its rise), the peak of P1 (and P2-P4) and its time,
    raw and after a 5 ms running mean (both series on their own samples), and P1's mean
    from 0.6 to 1.0 s, after the impact.
It prints markdown tables (and writes them to --table) and writes DIR/spheric_heights.png
(the four gauges), DIR/spheric_pressures.png (P1-P4), DIR/spheric_p1_impact.png (P1
from 0.3 to 0.7 s, raw and smoothed) and DIR/spheric_lee.png (the gauge at x = 0.496 m
from 0.8 to 1.3 s), measured in black.
Simulated columns: time, P.P1..P.P8 (Pa), H.x0496, H.x0992, H.x1488, H.x2638 (m); a run
without P columns (run with -v probes=0, or a probe style without pressure) gets "n/a" in
the pressure table.
"""
import argparse
import math
import os
import re
import sys

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
MEASURED = os.path.join(ROOT, "..", "shared", "validation", "spheric_test2_measured.csv")
GAUGES = [  # simulated label, measured column, x (m), wet at t = 0
    ("x0496", "h_x0.496_m", 0.496, False),
    ("x0992", "h_x0.992_m", 0.992, False),
    ("x1488", "h_x1.488_m", 1.488, False),
    ("x2638", "h_x2.638_m", 2.638, True),
]
PRESSURES = [("P1", "p1_Pa"), ("P2", "p2_Pa"), ("P3", "p3_Pa"), ("P4", "p4_Pa")]
THRESHOLD = 0.02   # m
SMOOTH = 0.005     # s, running mean for the smoothed peaks
RISE = 2000.0      # Pa: P1's rise, the first time it exceeds this
PLATEAU = (0.6, 1.0)  # s: P1's mean over this window, after the impact
IMPULSES = [(0.35, 0.60), (0.35, 1.0)]  # s: P1's impulse over the first impact, and to 1 s


def read_csv(path):
    """A CSV with '#' comment lines and a header line: {column: numpy array}."""
    header, rows = None, []
    with open(path) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            if header is None:
                header = [c.strip() for c in line.split(",")]
                continue
            values = line.split(",")
            if len(values) != len(header):
                continue  # a row cut short (a run still writing)
            rows.append([float(v) if v.strip() not in ("", "nan") else math.nan for v in values])
    if header is None or not rows:
        raise SystemExit(f"{path}: no data")
    data = np.array(rows)
    return {name: data[:, i] for i, name in enumerate(header)}


def arrival(t, h, wet, threshold=THRESHOLD):
    """First time h > threshold (dry gauge), or h < h(0) - threshold (wet gauge); nan if never."""
    level = h[0] - threshold if wet else threshold
    hit = h < level if wet else h > level
    i = np.argmax(hit)
    if not hit[i]:
        return math.nan
    if i == 0:
        return t[0]
    # the crossing, interpolated linearly between the samples on either side of it
    return t[i - 1] + (t[i] - t[i - 1]) * (level - h[i - 1]) / (h[i] - h[i - 1])


def running_mean(t, y, width):
    """Mean of y over [t - width/2, t + width/2] at every sample (any sampling)."""
    c = np.concatenate([[0.0], np.cumsum(np.nan_to_num(y))])
    lo = np.searchsorted(t, t - width / 2, side="left")
    hi = np.searchsorted(t, t + width / 2, side="right")
    return (c[hi] - c[lo]) / np.maximum(hi - lo, 1)


def window_mean(t, y, t0, t1):
    m = (t >= t0) & (t <= t1) & np.isfinite(y)
    return float(np.mean(y[m])) if m.any() else math.nan


def impulse(t, p, t0, t1):
    """The integral of p over [t0, t1] (Pa s), trapezoids on the samples, the ends interpolated."""
    m = (t > t0) & (t < t1) & np.isfinite(p)
    if not m.any() or t[0] > t0 or t[-1] < t1:
        return math.nan
    tt = np.concatenate([[t0], t[m], [t1]])
    pp = np.concatenate([[np.interp(t0, t, p)], p[m], [np.interp(t1, t, p)]])
    return float(np.sum((pp[1:] + pp[:-1]) * np.diff(tt)) / 2)


def peak(t, p, t_max):
    m = (t <= t_max) & np.isfinite(p)
    if not m.any():
        return math.nan, math.nan
    i = np.argmax(p[m])
    return p[m][i], t[m][i]


def run_info(path):
    """Particles, steps and wall time from run.log next to probes.csv, if there."""
    log = os.path.join(os.path.dirname(path), "run.log")
    if not os.path.exists(log):
        return None
    text = open(log, errors="replace").read()
    timings = re.findall(r"Timing: (\d+) steps of (\d+) particles in ([0-9.]+) s", text)
    spacing = re.search(r"spacing ([0-9.]+) m", text)
    if not timings:
        return None
    steps = sum(int(x[0]) for x in timings)
    wall = sum(float(x[2]) for x in timings)
    return {"particles": int(timings[-1][1]), "steps": steps, "wall": wall,
            "spacing": float(spacing.group(1)) if spacing else math.nan}


def fmt(x, spec=".3f"):
    return "n/a" if x is None or not np.isfinite(x) else format(x, spec)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="LABEL=RUN (a run directory or its probes.csv)")
    ap.add_argument("--measured", default=MEASURED)
    ap.add_argument("--t-max", type=float, default=2.0)
    ap.add_argument("--out-dir", default=".", help="where the PNG plots go")
    ap.add_argument("--table", help="also write the markdown tables to this file")
    ap.add_argument("--threshold", type=float, default=THRESHOLD,
                    help="arrival: the height change that counts (m, default %(default)s)")
    ap.add_argument("--no-plots", action="store_true")
    args = ap.parse_args()
    t_max, threshold = args.t_max, args.threshold

    meas = read_csv(args.measured)
    tm = meas["time_s"]
    keep = tm <= t_max
    ref = {"arrival": {}, "peak": {}, "smooth": {}}
    for lab, col, x, wet in GAUGES:
        ref["arrival"][lab] = arrival(tm, meas[col], wet, threshold)
    ref["rise"] = arrival(tm, meas["p1_Pa"], False, RISE)
    ref["plateau"] = window_mean(tm, meas["p1_Pa"], *PLATEAU)
    ref["impulse"] = [impulse(tm, meas["p1_Pa"], *w) for w in IMPULSES]
    for lab, col in PRESSURES:
        ref["peak"][lab] = peak(tm, meas[col], t_max)
        ref["smooth"][lab] = peak(tm, running_mean(tm, meas[col], SMOOTH), t_max)

    runs = []
    for arg in args.runs:
        if "=" not in arg:
            raise SystemExit(f"expected LABEL=RUN, got {arg!r}")
        label, path = arg.split("=", 1)
        if os.path.isdir(path):
            path = os.path.join(path, "probes.csv")
        sim = read_csv(path)
        t = sim["time"]
        r = {"label": label, "t": t, "sim": sim, "info": run_info(path), "arrival": {}, "rms": {},
             "bias": {}, "peak": {}, "smooth": {}, "t_end": t[-1]}
        for lab, col, x, wet in GAUGES:
            key = "H." + lab
            if key not in sim:
                r["arrival"][lab] = r["rms"][lab] = r["bias"][lab] = math.nan
                continue
            r["arrival"][lab] = arrival(t, sim[key], wet, threshold)
            m = keep & (tm >= t[0]) & (tm <= t[-1])
            diff = np.interp(tm[m], t, sim[key]) - meas[col][m]
            r["rms"][lab] = math.sqrt(np.mean(diff ** 2)) if m.any() else math.nan
            r["bias"][lab] = np.mean(diff) if m.any() else math.nan
        r["rise"] = arrival(t, sim["P.P1"], False, RISE) if "P.P1" in sim else math.nan
        r["plateau"] = window_mean(t, sim["P.P1"], *PLATEAU) if "P.P1" in sim else math.nan
        r["impulse"] = [impulse(t, sim["P.P1"], *w) if "P.P1" in sim else math.nan for w in IMPULSES]
        for lab, col in PRESSURES:
            key = "P." + lab
            if key in sim:
                r["peak"][lab] = peak(t, sim[key], t_max)
                r["smooth"][lab] = peak(t, running_mean(t, sim[key], SMOOTH), t_max)
            else:
                r["peak"][lab] = r["smooth"][lab] = (math.nan, math.nan)
        runs.append(r)

    out = []
    out.append(f"Arrival times (s) over 0-{t_max:g} s: first time the height exceeds {threshold:g} m; at x = 2.638 m "
               f"(wet at t = 0) first time it falls {threshold:g} m below its t = 0 value. In brackets: "
               f"simulated minus measured; target |difference| <= 0.05 s.\n")
    out.append("| run | " + " | ".join(f"x = {x} m" for _, _, x, _ in GAUGES) + " | within 0.05 s |")
    out.append("|---|" + "---|" * (len(GAUGES) + 1))
    out.append("| measured | " + " | ".join(fmt(ref["arrival"][g[0]]) for g in GAUGES) + " | |")
    for r in runs:
        cells, met = [], 0
        for g in GAUGES:
            a, b = r["arrival"][g[0]], ref["arrival"][g[0]]
            d = a - b
            met += int(np.isfinite(d) and abs(d) <= 0.05)
            cells.append(f"{fmt(a)} ({fmt(d, '+.3f')})")
        out.append(f"| {r['label']} | " + " | ".join(cells) + f" | {met} of {len(GAUGES)} |")
    out.append("")
    out.append(f"RMS height error (m) over the measurement's samples up to {t_max:g} s (mean error, "
               f"simulated minus measured, in brackets).\n")
    out.append("| run | " + " | ".join(f"x = {x} m" for _, _, x, _ in GAUGES) + " |")
    out.append("|---|" + "---|" * len(GAUGES))
    for r in runs:
        out.append(f"| {r['label']} | " + " | ".join(
            f"{fmt(r['rms'][g[0]])} ({fmt(r['bias'][g[0]], '+.3f')})" for g in GAUGES) + " |")
    out.append("")
    out.append(f"Pressures over 0-{t_max:g} s: P1's rise (the first time it exceeds {RISE:g} Pa), its peak on the "
               f"raw samples and after a {1000 * SMOOTH:g} ms running mean, its mean from {PLATEAU[0]:g} to {PLATEAU[1]:g} s "
               f"(after the impact); the peaks of P2-P4 (Pa at s, raw). "
               f"Targets: P1 peak within 30% of the measured one, its time within 0.02 s.\n")
    out.append(f"| run | P1 rises at (s) | P1 peak (Pa) | P1 peak time (s) | P1 peak, 5 ms mean | "
               f"P1 mean {PLATEAU[0]:g}-{PLATEAU[1]:g} s (Pa) | P2 | P3 | P4 | P1 targets |")
    out.append("|---|---|---|---|---|---|---|---|---|---|")

    def pk(p):
        return f"{fmt(p[0], '.0f')} at {fmt(p[1])}"
    out.append(f"| measured | {fmt(ref['rise'])} | {fmt(ref['peak']['P1'][0], '.0f')} | {fmt(ref['peak']['P1'][1])} | "
               f"{pk(ref['smooth']['P1'])} | {fmt(ref['plateau'], '.0f')} | " + " | ".join(pk(ref["peak"][p]) for p in ("P2", "P3", "P4")) + " | |")
    for r in runs:
        p, t1 = r["peak"]["P1"]
        rp, rt = ref["peak"]["P1"]
        sp, st = r["smooth"]["P1"]
        if np.isfinite(p):
            ok_p = abs(p / rp - 1) <= 0.30
            ok_t = abs(t1 - rt) <= 0.02
            verdict = f"peak {'met' if ok_p else 'not met'}, time {'met' if ok_t else 'not met'}"
            cell_p = f"{p:.0f} ({100 * (p / rp - 1):+.0f}%)"
            cell_t = f"{t1:.3f} ({t1 - rt:+.3f})"
            cell_s = f"{sp:.0f} ({100 * (sp / ref['smooth']['P1'][0] - 1):+.0f}%) at {st:.3f}"
            cell_r = f"{fmt(r['rise'])} ({fmt(r['rise'] - ref['rise'], '+.3f')})"
            cell_m = f"{r['plateau']:.0f} ({100 * (r['plateau'] / ref['plateau'] - 1):+.0f}%)"
        else:
            verdict, cell_p, cell_t, cell_s, cell_r, cell_m = "n/a", "n/a", "n/a", "n/a", "n/a", "n/a"
        out.append(f"| {r['label']} | {cell_r} | {cell_p} | {cell_t} | {cell_s} | {cell_m} | "
                   + " | ".join(pk(r["peak"][q]) for q in ("P2", "P3", "P4")) + f" | {verdict} |")
    out.append("")
    out.append("P1's impulse, the integral of its pressure (Pa s), over the first impact and to 1 s; in brackets, "
               "against the measured one (target: within 10%).\n")
    out.append("| run | " + " | ".join(f"{a:g}-{b:g} s" for a, b in IMPULSES) + " |")
    out.append("|---|" + "---|" * len(IMPULSES))
    out.append("| measured | " + " | ".join(fmt(x, ".0f") for x in ref["impulse"]) + " |")
    for r in runs:
        out.append(f"| {r['label']} | " + " | ".join(
            f"{fmt(x, '.0f')} ({fmt(100 * (x / y - 1), '+.0f')}%)" for x, y in zip(r["impulse"], ref["impulse"])) + " |")
    if any(r["info"] for r in runs):
        out.append("")
        out.append("| run | spacing (m) | particles | steps | wall time (s) | simulated to (s) |")
        out.append("|---|---|---|---|---|---|")
        for r in runs:
            i = r["info"] or {}
            out.append(f"| {r['label']} | {fmt(i.get('spacing', math.nan), '.5f')} | {i.get('particles', 'n/a')} | "
                       f"{i.get('steps', 'n/a')} | {fmt(i.get('wall', math.nan), '.0f')} | {r['t_end']:.3f} |")
    text = "\n".join(out) + "\n"
    sys.stdout.write(text)
    if args.table:
        os.makedirs(os.path.dirname(os.path.abspath(args.table)), exist_ok=True)
        with open(args.table, "w") as f:
            f.write(text)

    if args.no_plots:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    os.makedirs(args.out_dir, exist_ok=True)

    def four_panels(panels, sim_prefix, t_lo, scale, lw_measured, lw_sim, ylabel, title, name):
        """A 2 x 2 figure: per panel (label, measured column, title), the measurement in black
        and each run's column sim_prefix + label, over t_lo <= t <= t_max, divided by scale."""
        fig, axes = plt.subplots(2, 2, figsize=(11, 7), sharex=True)
        for ax, (lab, col, panel_title) in zip(axes.flat, panels):
            m = keep & (tm >= t_lo)
            ax.plot(tm[m], meas[col][m] / scale, color="k", lw=lw_measured, label="measured (MARIN)")
            for k, r in enumerate(runs):
                if sim_prefix + lab in r["sim"]:
                    m = (r["t"] <= t_max) & (r["t"] >= t_lo)
                    ax.plot(r["t"][m], r["sim"][sim_prefix + lab][m] / scale, color=colors[k % len(colors)],
                            lw=lw_sim, label=r["label"])
            ax.set_title(panel_title)
            ax.set_ylabel(ylabel)
            ax.grid(alpha=0.3)
        for ax in axes[1]:
            ax.set_xlabel("t (s)")
        axes.flat[0].legend(fontsize=8)
        fig.suptitle(title)
        fig.tight_layout()
        fig.savefig(os.path.join(args.out_dir, name), dpi=110)
        plt.close(fig)

    four_panels([(lab, col, f"water height at x = {x} m" + (" (reservoir)" if wet else ""))
                 for lab, col, x, wet in GAUGES], "H.", -math.inf, 1, 1.4, 1, "height (m)",
                "SPHERIC Test 2: water heights", "spheric_heights.png")
    four_panels([(lab, col, f"pressure {lab}") for lab, col in PRESSURES], "P.", 0.3, 1000, 1.2, 0.9, "p (kPa)",
                "SPHERIC Test 2: pressures on the box's front face", "spheric_pressures.png")

    def one_panel(fig, ax, ylabel, title, name):
        """Labels, grid and legend of a one-panel close-up, then the file."""
        ax.set_xlabel("t (s)")
        ax.set_ylabel(ylabel)
        ax.set_title(title)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(args.out_dir, name), dpi=110)
        plt.close(fig)

    # The impact on P1, close up: raw samples (thin) and the 5 ms running mean (thick).
    fig, ax = plt.subplots(figsize=(8, 4.5))
    m = (tm >= 0.3) & (tm <= 0.7)
    ax.plot(tm[m], meas["p1_Pa"][m] / 1000, color="k", lw=0.8, alpha=0.6)
    ax.plot(tm[m], running_mean(tm, meas["p1_Pa"], SMOOTH)[m] / 1000, color="k", lw=1.8, label="measured (MARIN)")
    for k, r in enumerate(runs):
        if "P.P1" in r["sim"]:
            m = (r["t"] >= 0.3) & (r["t"] <= 0.7)
            c = colors[k % len(colors)]
            ax.plot(r["t"][m], r["sim"]["P.P1"][m] / 1000, color=c, lw=0.8, alpha=0.6)
            ax.plot(r["t"][m], running_mean(r["t"], r["sim"]["P.P1"], SMOOTH)[m] / 1000, color=c, lw=1.8,
                    label=r["label"])
    one_panel(fig, ax, "p (kPa)",
              f"SPHERIC Test 2: the impact on P1 (thin: samples, thick: {1000 * SMOOTH:g} ms running mean)",
              "spheric_p1_impact.png")

    # The lee gauge (x = 0.496 m), close up, with the levels at which its arrival is read.
    fig, ax = plt.subplots(figsize=(8, 4.5))
    m = (tm >= 0.8) & (tm <= min(1.3, t_max))
    ax.plot(tm[m], meas["h_x0.496_m"][m], color="k", lw=1.6, label="measured (MARIN)")
    for k, r in enumerate(runs):
        if "H.x0496" in r["sim"]:
            m = (r["t"] >= 0.8) & (r["t"] <= min(1.3, t_max))
            ax.plot(r["t"][m], r["sim"]["H.x0496"][m], color=colors[k % len(colors)], lw=1, label=r["label"])
    for level in (args.threshold, 0.1, 0.15):
        ax.axhline(level, color="0.5", lw=0.6, ls=":")
    one_panel(fig, ax, "height (m)",
              f"SPHERIC Test 2: the gauge behind the box (x = 0.496 m); dotted: {args.threshold:g}, 0.1, 0.15 m",
              "spheric_lee.png")


if __name__ == "__main__":
    main()
