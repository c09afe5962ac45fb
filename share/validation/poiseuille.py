#!/usr/bin/env python3
"""Poiseuille flow (issue 32): scenarios/poiseuille.lua against the analytic solution.

Runs the scenario (one OpenMP thread, --log none) at several resolutions, reads its probes
(19 heights z = k H / 20, each the mean of 4 points in x and y) and compares them with

    steady    u(z) = F / (2 nu) z (H - z),   centre line u_max = F H^2 / (8 nu)
    start-up  u(z, t) = u(z) - sum_{n odd} 4 F H^2 / (nu pi^3 n^3) sin(n pi z / H) exp(-n^2 pi^2 nu t / H^2)

with the fluid's nu, and with nu' = kappa nu, the SPH Laplacian's effective viscosity at
long waves on the cubic lattice at the run's h / s:

    kappa = -V sum_j g(r_j) r_j^2 z_j^2 / (r_j^2 + 0.01 h^2),   V = 1 / sum_j W(r_j)

(gradW = g r_vec, Wendland C2; docs/physics.md, sph_viscosity). Prints the errors and, with
--out, writes docs/validation/poiseuille.md (date, machine, commands) and --plot its figure.

    /usr/bin/python3 share/validation/poiseuille.py [--binary build/pbfengine]
        [--runs 20:2,10:2,40:2,20:3,40:3] [--out docs/validation/poiseuille.md]
        [--plot docs/validation/poiseuille.png]

--runs: spacings across H and kernel radius in spacings, comma-separated; the first run is
the one plotted. The default set takes about 30 s of one core (the two at 40 spacings: 25 s).
"""
import argparse
import csv
import datetime
import math
import os
import platform
import shlex
import subprocess
import sys
import tempfile
import time

import numpy as np

from machine import machine  # share/validation/machine.py

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PROG = "poiseuille.py"
H, NU, F = 0.1, 1e-3, 8e-3  # the scenario's defaults
T_END = 8.0
U_MAX = F * H * H / (8 * NU)
T_VISC = H * H / (math.pi ** 2 * NU)
HEIGHTS = np.arange(1, 20) * H / 20
STARTUP_TIMES = (0.25, 0.5, 1.0, 2.0)


def series(z, t, nu):
    z = np.asarray(z, dtype=float)
    u = F / (2 * nu) * z * (H - z)
    for n in range(1, 800, 2):
        u = u - 4 * F * H * H / (nu * math.pi ** 3 * n ** 3) * np.sin(n * math.pi * z / H) * \
            math.exp(-n * n * math.pi ** 2 * nu * t / (H * H))
    return u


def kappa(support, eta=0.1):
    """The Laplacian's long-wave factor on the cubic lattice, kernel radius `support` spacings."""
    h, reach = support, int(math.ceil(support))
    c = 21 / (2 * math.pi * h ** 3)
    i = np.arange(-reach, reach + 1)
    X, Y, Z = np.meshgrid(i, i, i, indexing="ij")
    r2 = (X * X + Y * Y + Z * Z).astype(float)
    q = np.sqrt(r2) / h
    inside = q < 1
    W = np.where(inside, c * (1 - q) ** 4 * (1 + 4 * q), 0.0)
    g = np.where(inside, -20 * c * (1 - q) ** 3 / h ** 2, 0.0)
    V = 1 / W.sum()
    return float(-V * np.sum(g * r2 * Z * Z / (r2 + eta * eta * h * h)))



def run(binary, spacings, support, work, commands):
    out = os.path.join(work, f"n{spacings}_h{support:g}")
    cmd = [binary, "run", os.path.join(ROOT, "scenarios", "poiseuille.lua"), "-v", f"spacing={H / spacings!r}",
           "-v", f"support={support:g}", "-v", f"t_end={T_END:g}", "-v", "interval=0.05", "-v", f"out={out}",
           "--threads", "1", "--log", "none"]
    commands.append(cmd)
    start = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - start
    if p.returncode != 0:
        sys.exit(f"{PROG}: error: {shlex.join(cmd)} failed ({p.returncode}):\n{p.stdout[-2000:]}{p.stderr[-2000:]}")
    particles = next((int(l.split()[1]) for l in p.stdout.splitlines() if l.startswith("poiseuille:")), 0)
    with open(os.path.join(out, "profile.csv")) as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    head, data = rows[0], np.array([[float(x) for x in r] for r in rows[1:]])
    u = np.array([np.mean([data[:, head.index(f"u.z{k:02d}{a}_vx")] for a in "abcd"], axis=0)
                  for k in range(1, 20)]).T
    return dict(spacings=spacings, support=support, t=data[:, 0], u=u, wall=wall, particles=particles,
                kappa=kappa(support))


def at(r, time_):
    i = int(np.argmin(np.abs(r["t"] - time_)))
    return i, r["t"][i]


def scores(r):
    """Errors of a run against nu and against nu' = kappa nu, in fractions of each one's u_max."""
    s = {}
    i, t = at(r, T_END)
    h = r["support"] * H / r["spacings"]
    inner = (HEIGHTS >= h - 1e-9) & (HEIGHTS <= H - h + 1e-9)  # probes whose kernel reaches no plate
    for name, nu in (("nu", NU), ("eff", r["kappa"] * NU)):
        umax = F * H * H / (8 * nu)
        exact = series(HEIGHTS, t, nu)
        s[name + "_centre"] = r["u"][i, 9] / exact[9] - 1
        s[name + "_profile"] = float(np.max(np.abs(r["u"][i] - exact)[inner]) / umax)
        s[name + "_profile_all"] = float(np.max(np.abs(r["u"][i] - exact)) / umax)
        for tt in STARTUP_TIMES:
            j, tj = at(r, tt)
            ex = series(HEIGHTS, tj, nu)
            s[f"{name}_start_{tt:g}"] = r["u"][j, 9] / ex[9] - 1
            s[f"{name}_start_profile_{tt:g}"] = float(np.max(np.abs(r["u"][j] - ex)[inner]) / umax)
    shape = r["u"][i] / r["u"][i, 9] - 4 * HEIGHTS * (H - HEIGHTS) / H ** 2
    s["shape"] = float(np.max(np.abs(shape[inner])))
    s["nu_fit"] = float(F * H * H / (8 * r["u"][i, 9]) / NU)  # the viscosity the centre line implies, over nu
    return s


def plot(r, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.6))
    zz = np.linspace(0, H, 201)
    nu_eff = r["kappa"] * NU
    i, t = at(r, T_END)
    a.plot(series(zz, t, NU) / U_MAX, zz / H, "k-", label="analytic, nu")
    a.plot(series(zz, t, nu_eff) / U_MAX, zz / H, "k--", label=f"analytic, nu' = {r['kappa']:.3f} nu")
    a.plot(r["u"][i] / U_MAX, HEIGHTS / H, "o", color="C0", label="WCSPH probes")
    a.set_xlabel("u / u_max (u_max = F H^2 / (8 nu))")
    a.set_ylabel("z / H")
    a.set_title(f"steady, t = {t:.1f} s ({t / T_VISC:.1f} H^2/(pi^2 nu))")
    a.legend(loc="lower right", fontsize=8)
    for k, tt in enumerate(STARTUP_TIMES + (T_END,)):
        j, tj = at(r, tt)
        color = f"C{k}"
        b.plot(series(zz, tj, NU) / U_MAX, zz / H, "-", color=color, lw=1)
        b.plot(series(zz, tj, nu_eff) / U_MAX, zz / H, "--", color=color, lw=1)
        b.plot(r["u"][j] / U_MAX, HEIGHTS / H, "o", color=color, ms=3.5, label=f"t = {tj:.2f} s")
    b.set_xlabel("u / u_max")
    b.set_title("start-up from rest (solid: nu, dashed: nu')")
    b.legend(loc="lower right", fontsize=8)
    fig.suptitle(f"Poiseuille flow, {r['spacings']} spacings across H, h = {r['support']:g} spacings, "
                 f"Re = {U_MAX * H / NU:g}")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def pct(x):
    return f"{100 * x:+.2f}%"


def report(runs, commands, wall, args):
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    invocation = shlex.join(["/usr/bin/python3", "share/validation/poiseuille.py"] + sys.argv[1:])
    first = runs[0]
    L = []
    L += ["# Poiseuille flow (issue 32)", "",
          f"Measured {now} on {machine()} (shared with other work) by `{invocation}` ({wall:.0f} s wall), "
          "single precision, one thread per run. The numbers below are this script's output.", "",
          "`scenarios/poiseuille.lua`: fluid at rest between no-slip plates at z = 0 and H = 0.1 m (the box with "
          "`no_slip = true`), periodic along x (the flow, 8 spacings) and y (6 spacings), driven from t = 0 by "
          f"F = {F:g} m/s^2 along x (`gravity`). WCSPH: `leapfrog`, `wcsph` (summed density, Tait, c0 = 30 u_max = "
          f"{30 * U_MAX:g} m/s: Mach {1 / 30:.3f}, and {30 * U_MAX / math.sqrt(F * H):.1f} sqrt(F H)), "
          f"`sph_viscosity` with `kind = \"laplacian\"`, nu = {NU:g} m^2/s, `cfl` (the step is its viscous limit "
          "0.125 (h/2)^2 / nu). u_max = F H^2 / (8 nu) = "
          f"{U_MAX:g} m/s, Re = u_max H / nu = {U_MAX * H / NU:g}, viscous time H^2 / (pi^2 nu) = {T_VISC:.2f} s; "
          f"the runs end at t = {T_END:g} s, where the slowest mode has {32 / math.pi ** 3 * math.exp(-T_END / T_VISC):.1e} "
          "of u_max left (the comparisons take the series at the time of the sample anyway).", "",
          "The probes: 19 heights z = k H / 20, each the mean of 4 `probe` points (Shepard-interpolated velocity) at "
          "x = L/4, 3L/4 and y = W/4, 3W/4. \"Profile\" is the largest error over the heights more than a kernel "
          "radius from the plates (a Shepard sum nearer a plate is one-sided), in fractions of u_max; \"centre\" "
          "is u(H/2) against the analytic value at the same time.", "",
          "## Against the analytic solution with nu", "",
          "| spacings across H | h / s | particles | wall time | centre, steady | profile, steady | "
          + " | ".join(f"centre, t = {t:g} s" for t in STARTUP_TIMES) + " |",
          "|---|---|---|---|---|---|" + "---|" * len(STARTUP_TIMES)]
    for r in runs:
        s = r["scores"]
        L.append(f"| {r['spacings']} | {r['support']:g} | {r['particles']} | {r['wall']:.1f} s | {pct(s['nu_centre'])} | "
                 f"{100 * s['nu_profile']:.2f}% | " + " | ".join(pct(s[f'nu_start_{t:g}']) for t in STARTUP_TIMES) + " |")
    s0 = first["scores"]
    L += ["",
          f"**The issue's 3% at the centre line is not met with the engine's h = 2s**: the steady flow runs "
          f"{pct(s0['nu_centre'])} fast at {first['spacings']} spacings, and the error does not shrink with the "
          "resolution. The whole profile is the same factor too fast (u / u_analytic is flat across the channel to "
          "within the probes' near-wall bias), the viscosity the centre line implies is "
          f"{s0['nu_fit']:.3f} nu. The start-up follows the same way: on track at first (the centre accelerates at F "
          "until the plates' diffusion reaches it), then fast by the same factor as the steady flow.", "",
          "## Against nu' = kappa nu, the Laplacian's lattice factor", "",
          "The SPH Laplacian of Morris et al. (1997) applied to a quadratic field on the cubic lattice gives kappa "
          "times the exact one, kappa = -V sum_j g r^2 z^2 / (r^2 + eta^2) (docs/physics.md, `sph_viscosity`, "
          "\"Their effective viscosity\"). It is set by h / s, not by s, so refining at fixed h / s does not remove "
          "it. With nu' = kappa nu the same runs:", "",
          "| spacings across H | h / s | kappa | centre, steady | profile, steady | shape u/u(H/2) | "
          + " | ".join(f"centre, t = {t:g} s" for t in STARTUP_TIMES) + " |",
          "|---|---|---|---|---|---|" + "---|" * len(STARTUP_TIMES)]
    for r in runs:
        s = r["scores"]
        L.append(f"| {r['spacings']} | {r['support']:g} | {r['kappa']:.4f} | {pct(s['eff_centre'])} | "
                 f"{100 * s['eff_profile']:.2f}% | {100 * s['shape']:.2f}% | "
                 + " | ".join(pct(s[f'eff_start_{t:g}']) for t in STARTUP_TIMES) + " |")
    L += ["",
          "At h = 2s the flow is the analytic one of nu' within about 1% everywhere, start-up included: the no-slip "
          "wall term holds the plates (the shape u / u(H/2), which the viscosity's scale drops out of, is the "
          "parabola within a fraction of a percent; a slip of half a spacing at each plate would put it 5% high at "
          "z = 0.2 H at 12 spacings, 3% at 20), the leapfrog and `cfl` integrate the start-up, and the compressibility is negligible. What "
          "remains, about -0.4 to -1%, is the probes' Shepard average of the parabola (4/15 (h/H)^2 of u_max low "
          "at the centre: 0.7% at 12 spacings, 0.3% at 20, 0.07% at 40), the lattice of sliding layers (its kappa, "
          "averaged over the layers' offsets, is 0.924: -0.2%) and the wall layers' force errors "
          "(docs/physics.md, a few tenths of a percent).", "",
          "Of kappa = 0.922 at h = 2s, the regularisation eta^2 = 0.01 h^2 takes 2.8 points (kappa = 0.950 with "
          "eta = 0; the continuum limit with eta is 0.958): Morris's eta^2 = 0.01 h^2 is on the smoothing length, "
          "h/2 here, i.e. 0.0025 h^2 on the kernel's radius (kappa 0.944 at h = 2s). The rest is the lattice sum "
          "at 2 spacings a radius. A larger kernel helps (kappa 0.959 at h = 3s), but not enough: the centre "
          "line runs +2.7% fast at 20 spacings and +3.6% at 40, on its way to 1/kappa = +4.3% as the probes' "
          "Shepard bias (larger with h) shrinks. The remedy would be in "
          "`sph_viscosity`: divide nu by kappa at the run's h / s (the way the walls' delta is calibrated on the "
          "initial lattice), or normalise each particle's Laplacian by its own -1/3 sum_j V_j g r^4 / (r^2 + eta^2). "
          "Either changes the engine's documented nu_eff and the tests built on it (test_viscosity, "
          "test_viscous_walls, test_viscous_wall_flow), so it is left to a decision.", "",
          "## The test", "",
          "`Poiseuille.TheFlowBetweenNoSlipPlatesIsTheParabolaOfTheLaplaciansViscosity` (tests/test_poiseuille.cpp) "
          "runs the scenario at 12 spacings (576 particles, 990 steps, 0.4 s of one core) and checks it against nu' = "
          "kappa nu: the steady centre line within the issue's 3%, the centre line at t = 0.5 and 1 s within "
          "3% (1 - exp(-pi^2 nu' t / H^2)) of u_max, and the shape within 1% of the centre line; the bounds are "
          "derived in its header.", "",
          f"![Poiseuille flow](poiseuille.png)", "",
          "The runs (the CSV files lay in a temporary directory):", "", "```sh"]
    L += [shlex.join(c).replace(ROOT + "/", "") for c in commands]
    L += ["```", ""]
    with open(args.out, "w") as f:
        f.write("\n".join(L))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "pbfengine"))
    ap.add_argument("--runs", default="20:2,10:2,40:2,20:3,40:3", help="spacings:support, comma-separated")
    ap.add_argument("--out", help="write the report (Markdown) to this file")
    ap.add_argument("--plot", help="write the figure (PNG) to this file")
    args = ap.parse_args()
    binary = os.path.abspath(args.binary)
    if not os.access(binary, os.X_OK):
        sys.exit(f"{PROG}: error: --binary {binary}: no such executable (build it, or give --binary)")
    specs = [(int(a), float(b)) for a, b in (x.split(":") for x in args.runs.split(","))]
    commands, runs = [], []
    start = time.time()
    with tempfile.TemporaryDirectory(prefix="pbf_poiseuille_") as work:
        for n, sup in specs:
            print(f"{PROG}: {n} spacings across, h = {sup:g} s", file=sys.stderr)
            r = run(binary, n, sup, work, commands)
            r["scores"] = scores(r)
            runs.append(r)
    wall = time.time() - start
    for r in runs:
        s = r["scores"]
        print(f"{r['spacings']:3d} spacings, h = {r['support']:g} s, {r['particles']} particles, {r['wall']:.1f} s: "
              f"against nu: centre {pct(s['nu_centre'])}, profile {100 * s['nu_profile']:.2f}% of u_max, start-up "
              + " ".join(f"t={t:g}:{pct(s[f'nu_start_{t:g}'])}" for t in STARTUP_TIMES))
        print(f"     against nu' = {r['kappa']:.4f} nu: centre {pct(s['eff_centre'])}, profile "
              f"{100 * s['eff_profile']:.2f}%, shape {100 * s['shape']:.2f}%, start-up "
              + " ".join(f"t={t:g}:{pct(s[f'eff_start_{t:g}'])}" for t in STARTUP_TIMES)
              + f"; the centre line's viscosity {s['nu_fit']:.4f} nu")
    if args.plot:
        plot(runs[0], args.plot)
    if args.out:
        report(runs, commands, wall, args)


if __name__ == "__main__":
    main()
