#!/usr/bin/env python3
"""Compare share/validation/heave_decay.lua runs with Kramer et al. (2021)'s heave decay of a
floating sphere: the first trough and crest of z(t)/z(0) against t/Te0 (Te0 = 0.7561 s),
simulated vs the measured mean, and a plot of all the runs with the measured mean and its 95%
confidence band.

    plot_heave_decay.py --png PNG --table MD RUN_DIR:LABEL [RUN_DIR:LABEL ...]

Each RUN_DIR holds body.csv and meta.txt (written by heave_decay.lua). The measured file is
chosen by the run's H0/D (meta.txt h0_ratio): ../shared/validation beside the checkout (or $KRAMER_DIR)
kramer_2021_sphere_heave_decay_{01D,03D,05D}.csv. z is the sphere centre's height above the
equilibrium the run computed (z_eq), divided by the measured initial offset H0m; t is from the
release. Extrema: the samples' minimum in t/Te0 in [0.25, 0.8] (trough) and maximum in
[0.75, 1.4] (crest), refined by a parabola through the extreme sample and its two neighbours.
Pass: |height error| <= 10% and |time error| <= 5% of the measured value, for both.

A linear oscillator fit, for the diagnosis: (M + A) z'' + B z' + K z = 0 with K the quarter
sphere's hydrostatic stiffness rho0 g pi R^2 / 4 = 173.2 N/m taken as known, M + A and B by
least squares over 0 < t/Te0 < 1.3 (z'' and z' by finite differences of z, the same way for the
simulated and the measured curve; the equation is homogeneous, so the normalisation does not
matter). A is then an apparent added mass (in units of the quarter body's mass M = 1.764 kg)
and zeta = B / (2 sqrt(K (M + A))) a damping ratio; the large offsets are nonlinear, so these
are an equivalent linear system, not the radiation coefficients.
"""
import argparse
import csv
import os

TE0 = 0.7561
KRAMER = os.environ.get(
    "KRAMER_DIR", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "shared", "validation"))


def meta(run):
    m = {}
    for line in open(os.path.join(run, "meta.txt")):
        k, v = line.split(" = ", 1)
        v = v.strip()
        try:
            m[k] = float(v)
        except ValueError:
            m[k] = v
    return m


def simulated(run):
    m = meta(run)
    t, z = [], []
    for r in csv.DictReader(open(os.path.join(run, "body.csv"))):
        tt = float(r["time"]) - m["t_release"]
        if tt < -0.05:
            continue
        t.append(tt / TE0)
        z.append((float(r["body.z"]) - m["z_eq"]) / m["H0m"])
    return m, t, z


def measured(ratio):
    name = {0.1: "01D", 0.3: "03D", 0.5: "05D"}[round(ratio, 1)]
    path = os.path.join(KRAMER, f"kramer_2021_sphere_heave_decay_{name}.csv")
    rows = [r for r in csv.reader(l for l in open(path) if not l.startswith("#"))][1:]
    cols = list(zip(*[[float(x) for x in r] for r in rows]))
    return name, cols[0], cols[1], cols[2], cols[3]


def extremum(t, z, lo, hi, sign):
    """The extreme (sign -1: min, +1: max) of z over t in [lo, hi], refined by a parabola."""
    idx = [i for i in range(len(t)) if lo <= t[i] <= hi]
    k = max(idx, key=lambda i: sign * z[i])
    if 0 < k < len(t) - 1:
        (t0, t1, t2), (z0, z1, z2) = t[k - 1:k + 2], z[k - 1:k + 2]
        den = (t0 - t1) * (t0 - t2) * (t1 - t2)
        a = (t2 * (z1 - z0) + t1 * (z0 - z2) + t0 * (z2 - z1)) / den
        b = (t2 * t2 * (z0 - z1) + t1 * t1 * (z2 - z0) + t0 * t0 * (z1 - z2)) / den
        c = z1 - a * t1 * t1 - b * t1
        if a != 0:
            tv = -b / (2 * a)
            if t0 <= tv <= t2:
                return tv, a * tv * tv + b * tv + c
    return t[k], z[k]


K_QUARTER = 998.2 * 9.82 * 3.141592653589793 * 0.15 ** 2 / 4
M_QUARTER = 7.056 / 4


def oscillator(t, z):
    """(A / M, zeta) of the linear fit over 0 < t/Te0 < 1.3 (t in Te0, z in H0)."""
    import numpy as np
    t = np.asarray(t) * TE0
    z = np.asarray(z)
    v = np.gradient(z, t)
    a = np.gradient(v, t)
    sel = (t > 0.01) & (t < 1.3 * TE0)
    X = np.column_stack([a[sel], v[sel]])
    (mt, b), *_ = np.linalg.lstsq(X, -K_QUARTER * z[sel], rcond=None)
    return (mt - M_QUARTER) / M_QUARTER, b / (2 * (K_QUARTER * mt) ** 0.5)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--png", required=True)
    ap.add_argument("--table", required=True)
    ap.add_argument("runs", nargs="+")
    args = ap.parse_args()
    lines = []
    series = []
    for spec in args.runs:
        run, label = spec.split(":", 1)
        m, t, z = simulated(run)
        name, mt, mz, mlo, mhi = measured(m["h0_ratio"])
        series.append((label, m, t, z, name, mt, mz, mlo, mhi))
        lines.append(f"### {label}")
        lines.append("")
        if m["solver"] == "wcsph":
            how = (f"WCSPH (continuity density with delta-SPH 0.1, artificial viscosity alpha 0.02 unless the command "
                   f"says otherwise; the step chosen by cfl, at most {m['dt']:.4g} s)")
        else:
            how = f"PBF, dt {m['dt']:.4g} s, {int(m['iterations'])} iterations, XSPH c {m['xsph']:g}"
        lines.append(f"{int(m['particles'])} particles, spacing {m['spacing']:g} m, h {m['support']:g} spacings, "
                     f"{how}; "
                     f"H0m = {m['H0m']:.5f} m (nominal {m['h0_ratio'] * 0.3:.3f} m); still level {m['level0']:.4f} m "
                     f"settled, {m['level_hold']:.4f} m with the held sphere; equilibrium z_eq {m['z_eq']:.4f} m; "
                     f"fluid force on the held sphere {m['F_hold']:.3f} N against {m['F_hold_theory']:.3f} N "
                     f"(rho0 g times the quarter cap's volume below the measured level).")
        lines.append("")
        lines.append("| extremum | simulated z/H0m | at t/Te0 | measured (Kramer " + name + ") | at t/Te0 | "
                     "height error | time error | within 10% / 5% |")
        lines.append("|---|---|---|---|---|---|---|---|")
        for what, lo, hi, sign in (("first trough", 0.25, 0.8, -1), ("first crest", 0.75, 1.4, 1)):
            ts, zs = extremum(t, z, lo, hi, sign)
            tm, zm = extremum(mt, mz, lo, hi, sign)
            eh = 100 * (abs(zs) - abs(zm)) / abs(zm)
            et = 100 * (ts - tm) / tm
            ok = abs(eh) <= 10 and abs(et) <= 5
            lines.append(f"| {what} | {zs:+.3f} | {ts:.3f} | {zm:+.3f} | {tm:.3f} | {eh:+.1f}% | {et:+.1f}% | "
                         f"{'pass' if ok else 'FAIL'} |")
        am_s, zeta_s = oscillator(t, z)
        am_m, zeta_m = oscillator(mt, mz)
        lines.append("")
        lines.append(f"Linear oscillator fit over 0 < t/Te0 < 1.3: apparent added mass {am_s:.2f} M (measured {am_m:.2f} M), "
                     f"damping ratio {zeta_s:.3f} (measured {zeta_m:.3f}).")
        tail = [zz for tt, zz in zip(t, z) if tt >= 1.6]
        if tail:
            lines.append("")
            lines.append(f"Mean of z/H0m over t/Te0 >= 1.6 (to the end, {t[-1]:.2f}): {sum(tail) / len(tail):+.3f} "
                         "(0 if the computed equilibrium is the model's).")
        lines.append("")
    open(args.table, "w").write("\n".join(lines) + "\n")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    names = sorted({s[4] for s in series})
    fig, axes = plt.subplots(len(names), 1, figsize=(9, 3.6 * len(names)), squeeze=False)
    for ax, name in zip(axes[:, 0], names):
        done = False
        for label, m, t, z, nm, mt, mz, mlo, mhi in series:
            if nm != name:
                continue
            if not done:
                ax.fill_between(mt, mlo, mhi, color="0.75", label="measured 95% band")
                ax.plot(mt, mz, "k-", lw=1.6, label=f"measured mean (Kramer et al. 2021, H0 = 0.{name[1]} D)")
                done = True
            ax.plot(t, z, lw=1.2, label=label)
        ax.axhline(0, color="0.5", lw=0.5)
        ax.set_xlim(-0.05, 2.6)
        ax.set_ylabel("z / H0")
        ax.set_title(f"sphere heave decay, H0 = 0.{name[1]} D")
        ax.legend(fontsize=7, loc="upper right")
    axes[-1, 0].set_xlabel("t / Te0 (Te0 = 0.7561 s)")
    fig.tight_layout()
    fig.savefig(args.png, dpi=110)


if __name__ == "__main__":
    main()
