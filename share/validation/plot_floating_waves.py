#!/usr/bin/env python3
"""The floating box in regular waves (Ren et al. 2015) against share/validation/floating_waves.lua.

    plot_floating_waves.py [--exp CSV] [--png FILE] [--table FILE] [--nobox DIR:LABEL ...] DIR:LABEL ...

Each DIR:LABEL is a run with the box (DIR/body.csv, time from the paddle's start); each --nobox
DIR:LABEL a run without it (DIR/gauges.csv with the gauge x180 at the box's place). Plots heave,
surge and roll against time, model and measured (surge as its change since t = 1.91 s, the
measured series' first sample, since that series carries an offset), and the incident wave at
the box's place; prints (and with --table writes, as Markdown) over the measured window
t = 1.91 to 8.98 s:
  heave and roll height: the mean crest-to-trough of the cycles between zero up-crossings
  (of the signal less its mean over the window); heave period: the mean interval between those
  up-crossings; mean roll: the time mean over the window; surge drift: x(8.98) - x(1.91), and
  the slope of a straight line fitted over the window; the time from heave's maximum to roll's,
  from both signals' harmonics at the heave period; the heave's rms difference from the measured
  one over four parts of the window;
and the incident wave height at the box's place (and at x = 1.0 m) from the no-box runs: the mean
crest-to-trough of the zero-up-crossing waves from 0.6 s after the wave front (at linear theory's
group velocity 1.12 m/s) to the run's end, against the nominal 0.10 m, and the mean crest less
the mean trough of the whole half waves (between zero crossings) in that window.
"""
import argparse
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
EXP_DEFAULT = os.path.normpath(os.path.join(HERE, "..", "..", "..", "shared", "validation", "ren_2015_floating_box_motion.csv"))
T0, T1 = 1.90995, 8.98
CG = 1.1209
SEGMENTS = [(1.9, 3.3), (3.3, 5.0), (5.0, 7.0), (7.0, 9.0)]


def read_csv(path):
    with open(path) as f:
        lines = [l for l in f if not l.startswith("#")]
    names = lines[0].strip().split(",")
    data = np.array([[float(v) for v in l.strip().split(",")] for l in lines[1:] if l.strip()])
    return {n: data[:, i] for i, n in enumerate(names)}


def upcrossings(t, y):
    """Times of zero up-crossings of y (linear interpolation)."""
    i = np.nonzero((y[:-1] < 0) & (y[1:] >= 0))[0]
    return t[i] - y[i] * (t[i + 1] - t[i]) / (y[i + 1] - y[i])


def cycles(t, y, t0, t1):
    """Mean crest-to-trough and mean up-crossing period of y over [t0, t1], about its time mean there."""
    m = (t >= t0) & (t <= t1)
    tt, yy = t[m], y[m]
    if len(tt) < 3:
        return np.nan, np.nan, 0
    yy = yy - np.trapz(yy, tt) / (tt[-1] - tt[0])
    up = upcrossings(tt, yy)
    heights = [yy[(tt >= a) & (tt < b)].ptp() for a, b in zip(up[:-1], up[1:])]
    if not heights:
        return np.nan, np.nan, 0
    return float(np.mean(heights)), float(np.mean(np.diff(up))), len(heights)


def harmonic(t, y, omega):
    """Complex amplitude Z of y ~ c + Re(Z exp(i omega t)), least squares."""
    A = np.column_stack([np.ones_like(t), np.cos(omega * t), np.sin(omega * t)])
    c = np.linalg.lstsq(A, y, rcond=None)[0]
    return c[1] - 1j * c[2]


def half_waves(t, y, t0, t1):
    """Mean crest minus mean trough over [t0, t1]: the extreme of each whole half wave between zero crossings."""
    m = (t >= t0) & (t <= t1)
    tt, yy = t[m], y[m]
    z = np.nonzero(np.sign(yy[:-1]) != np.sign(yy[1:]))[0]
    crests = [yy[a + 1:b + 1].max() for a, b in zip(z[:-1], z[1:]) if yy[a + 1] > 0]
    troughs = [yy[a + 1:b + 1].min() for a, b in zip(z[:-1], z[1:]) if yy[a + 1] < 0]
    if not crests or not troughs:
        return np.nan, 0, 0
    return float(np.mean(crests) - np.mean(troughs)), len(crests), len(troughs)


def motions(t, surge, heave, roll):
    m = (t >= T0) & (t <= T1)
    tt = t[m]
    H_heave, T_heave, n_heave = cycles(t, heave, T0, T1)
    H_roll, T_roll, n_roll = cycles(t, roll, T0, T1)
    s0, s1 = np.interp(T0, t, surge), np.interp(min(T1, t[-1]), t, surge)
    slope = np.polyfit(tt, surge[m], 1)[0]
    omega = 2 * np.pi / T_heave
    zh, zr = harmonic(tt, heave[m], omega), harmonic(tt, roll[m], omega)
    lag = (np.angle(zh) - np.angle(zr)) / omega          # roll's maximum after heave's
    lag = (lag + T_heave / 2) % T_heave - T_heave / 2
    return {"lag": lag, "heave": H_heave, "T": T_heave, "n": n_heave, "roll": H_roll, "T_roll": T_roll,
            "roll_mean": float(np.trapz(roll[m], tt) / (tt[-1] - tt[0])), "drift": s1 - s0, "drift_speed": slope,
            "heave_mean": float(np.trapz(heave[m], tt) / (tt[-1] - tt[0])), "t_last": float(tt[-1])}


def split(arg):
    d, _, label = arg.partition(":")
    return d, label or os.path.basename(d.rstrip("/"))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="*", help="DIR:LABEL of runs with the box")
    ap.add_argument("--nobox", action="append", default=[], help="DIR:LABEL of a run without the box")
    ap.add_argument("--exp", default=EXP_DEFAULT)
    ap.add_argument("--png", default="floating_waves.png")
    ap.add_argument("--table", default=None)
    a = ap.parse_args()

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    exp = read_csv(a.exp)
    rows = []
    rms_rows = []
    out = []
    e = motions(exp["t_s"], exp["surge_m"], exp["heave_m"], exp["roll_deg"])
    rows.append(("experiment (Ren et al. 2015)", e))

    fig, ax = plt.subplots(4, 1, figsize=(11, 12), sharex=True)
    ax[0].plot(exp["t_s"], exp["heave_m"], "ko", ms=3, label="measured")
    ax[1].plot(exp["t_s"], exp["surge_m"] - exp["surge_m"][0], "ko", ms=3, label="measured")
    ax[2].plot(exp["t_s"], exp["roll_deg"], "ko", ms=3, label="measured")
    for arg in a.runs:
        d, label = split(arg)
        b = read_csv(os.path.join(d, "body.csv"))
        t = b["t_s"]
        r = motions(t, b["surge_m"], b["heave_m"], b["roll_deg"])
        rows.append((label, r))
        model = np.interp(exp["t_s"], t, b["heave_m"])
        rms = []
        for t0, t1 in SEGMENTS:
            k = (exp["t_s"] >= t0) & (exp["t_s"] < t1) & (exp["t_s"] <= t[-1])
            rms.append(1000 * np.sqrt(np.mean((model[k] - exp["heave_m"][k]) ** 2)) if k.any() else np.nan)
        rms_rows.append((label, rms))
        ax[0].plot(t, b["heave_m"], lw=1.3, label=label)
        ax[1].plot(t, b["surge_m"] - np.interp(T0, t, b["surge_m"]), lw=1.3, label=label)
        ax[2].plot(t, b["roll_deg"], lw=1.3, label=label)

    out.append("| | heave height (mm) | heave period (s) | roll height (deg) | mean roll (deg) | mean heave (mm) | roll max after heave max (s) | surge drift (m) | drift speed (m/s) | cycles | window (s) |")
    out.append("|---|---|---|---|---|---|---|---|---|---|---|")
    for label, r in rows:
        out.append("| %s | %.1f | %.3f | %.1f | %.1f | %.1f | %+.2f | %.3f | %.3f | %d | %.2f-%.2f |" % (
            label, 1000 * r["heave"], r["T"], r["roll"], r["roll_mean"], 1000 * r["heave_mean"], r["lag"], r["drift"],
            r["drift_speed"], r["n"], T0, r["t_last"]))
    out.append("")
    out.append("(Over t = 1.91 to 8.98 s after the paddle's start, or the run's end if sooner. Heights: mean crest-to-trough "
               "of the cycles between zero up-crossings; heave period: their mean interval; mean heave: the model's from its "
               "floating level at the paddle's start, the experiment's from its first position; surge drift: x(end) - x(1.91 s); "
               "drift speed: a straight line's slope over the window; roll max after heave max: from the two signals' "
               "harmonics at the heave period, fitted over the window, in (-T/2, T/2]: a wave-following box's roll "
               "(turn about +y) would peak a quarter period before its heave, -T/4.)")
    out.append("")
    out.append("| heave, rms of model - measured (mm) | " + " | ".join("t = %.1f-%.1f s" % seg for seg in SEGMENTS) + " |")
    out.append("|---|" + "---|" * len(SEGMENTS))
    for label, rms in rms_rows:
        out.append("| %s | " % label + " | ".join("%.1f" % v for v in rms) + " |")
    out.append("")
    out.append("(At the measured samples, the model's heave interpolated; the measured heave's amplitude is about 47 mm.)")
    out.append("")

    if a.nobox:
        out.append("| incident wave (no box) | gauge | window (s) | H (mm) | H / 0.10 m | waves | mean crest - mean trough (mm) | crests, troughs |")
        out.append("|---|---|---|---|---|---|---|---|")
    for arg in a.nobox:
        d, label = split(arg)
        gz = read_csv(os.path.join(d, "gauges.csv"))
        t = gz["t_s"]
        for name in sorted(k for k in gz if k.startswith("x")):
            x = int(name[1:]) / 100
            t0 = x / CG + 0.6
            if t[-1] - t0 < 1.8:
                continue
            eta = gz[name] - np.mean(gz[name][t < min(0.5, x / 1.7)])
            H, T, n = cycles(t, eta, t0, t[-1])
            H2, nc, nt = half_waves(t, eta, t0, t[-1])
            out.append("| %s | x = %.2f m | %.2f-%.2f | %.1f | %.2f | %d | %.1f | %d, %d |" % (
                label, x, t0, t[-1], 1000 * H, H / 0.10, n, 1000 * H2, nc, nt))
            if name == "x180":
                ax[3].plot(t, eta, lw=1.2, label=label + ", x = 1.8 m")
    ax[3].axhline(0.05, color="k", ls=":", lw=0.8)
    ax[3].axhline(-0.05, color="k", ls=":", lw=0.8, label="+-H/2 nominal (0.05 m)")

    ax[0].set_ylabel("heave (m)")
    ax[1].set_ylabel("surge change since t = 1.91 s (m)")
    ax[2].set_ylabel("roll (deg)")
    ax[3].set_ylabel("incident wave at the box's x (m)")
    ax[3].set_xlabel("time since the paddle's start (s)")
    for x in ax:
        x.axvspan(T0, T1, color="0.93", zorder=-1)
        x.grid(alpha=0.3)
        x.legend(fontsize=8, loc="upper left")
    ax[0].set_title("Floating box in regular waves (Ren et al. 2015): H = 0.10 m, T = 1.2 s, h = 0.4 m")
    fig.tight_layout()
    fig.savefig(a.png, dpi=110)
    text = "\n".join(out) + "\n"
    sys.stdout.write(text)
    if a.table:
        with open(a.table, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
