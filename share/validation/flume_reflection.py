#!/usr/bin/env python3
"""The wave flume's reflected wave, with a vertical far wall, without and with a damping zone.

    /usr/bin/python3 share/validation/flume_reflection.py [--binary build/pbfengine] [--work DIR]
        [--cases wall,damping,beach] [--spacing 0.03] [--report docs/validation/flume_reflection.md]
    /usr/bin/python3 share/validation/flume_reflection.py --analyse-only --work DIR   (re-analyse DIR's runs)

Runs scenarios/wave_flume.lua (one run at a time) in these cases, T = 1.0 s, S = 0.04 m, d = 0.3 m:

  wall     a flume 5 m long ending in a vertical wall (-v length=5 -v beach=false)
  damping  the same with a damping zone over its last 1.5 m, x = 3.5 to 5 m (-v damping=1.5)
  beach    the scenario's default: 6 m, the 1:4 beach from x = 4.5 m

with four gauges at x = 2.70, 2.84, 3.04 and 3.30 m (gauge spacings L/10 and L/4 and more, for
L = 1.37 m: Mansard & Funke's advice), and separates the incident and the reflected wave at the
paddle's frequency by least squares over the gauges (Mansard & Funke 1980, at one frequency;
two gauges would be Goda & Suzuki 1976):

    eta_j(t) = Re[(a_I exp(-i kappa x_j) + a_R exp(+i kappa x_j)) exp(i omega t)],

where each gauge's complex amplitude comes from a least-squares fit of a constant, cos(omega t)
and sin(omega t) over a window. kappa = k - i beta holds the wave number k and the rate beta at
which the fluid's damping takes the wave's amplitude per metre (the incident wave decays along
+x, the reflected one along -x); it is fitted too (the (k, beta) that leave the smallest
residual), and the result is given also with linear theory's k and beta = 0. The reflection
coefficient is K_r = |a_R| / |a_I| at the array's centre, H = 2 |a|.

The window: once the reflected wave's train has grown at every gauge (its front, travelling at
linear theory's group velocity c_g, reached the nearest gauge 2.5 periods before: two periods of
the paddle's ramp and a half to settle), until the wave the paddle re-reflects reaches the nearest
gauge (the piston absorbs nothing). The incident wave alone is measured in the window before any
reflection reaches the farthest gauge, from when its train has grown there.

Writes the report (markdown, with the date and machine) and a PNG next to it. Needs numpy and
matplotlib (/usr/bin/python3 has them).
"""
import argparse
import csv
import datetime
import math
import os
import platform
import subprocess
import sys
import time

from machine import machine  # share/validation/machine.py

G = 9.81
PERIOD, STROKE, DEPTH, START = 1.0, 0.04, 0.3, 1.0
GAUGES = [2.70, 2.84, 3.04, 3.30]
CASES = {
    # name: (flume length, scenario variables, label)
    "wall": (5.0, ["-v", "length=5", "-v", "beach=false"], "vertical wall at x = 5 m"),
    "damping": (5.0, ["-v", "length=5", "-v", "beach=false", "-v", "damping=1.5"],
                "vertical wall at x = 5 m, damping zone x = 3.5 to 5 m (rate 10/s)"),
    "beach": (6.0, [], "the default: 1:4 beach from x = 4.5 m (still shoreline x = 5.7 m), wall at 6 m"),
}
# Where reflections come from, for the windows' timing: the nearest point (the incident window
# closes when a reflection from it could reach the farthest gauge) and the farthest (the window
# of the reflected wave opens once the reflection from it has grown at every gauge). The damping
# zone may reflect from where it starts, x = 3.5 m, to the wall behind it; the beach from its toe
# to its still shoreline.
NEAR = {"wall": 5.0, "damping": 3.5, "beach": 4.5}
FAR = {"wall": 5.0, "damping": 5.0, "beach": 5.7}


def wavenumber(period, depth):
    omega = 2 * math.pi / period
    k = omega * omega / G / math.sqrt(math.tanh(omega * omega * depth / G))
    for _ in range(50):
        f = G * k * math.tanh(k * depth) - omega * omega
        df = G * math.tanh(k * depth) + G * k * depth / math.cosh(k * depth) ** 2
        k -= f / df
    return k


def group_velocity(period, k, depth):
    c = 2 * math.pi / period / k
    return 0.5 * c * (1 + 2 * k * depth / math.sinh(2 * k * depth))


def t_end_for(case):
    """Time the re-reflected wave reaches the nearest gauge (the end of the window)."""
    k = wavenumber(PERIOD, DEPTH)
    cg = group_velocity(PERIOD, k, DEPTH)
    return START + (2 * FAR[case] + GAUGES[0]) / cg


def read_gauges(path):
    import numpy as np

    with open(path) as f:
        rows = list(csv.reader(f))
    header = rows[0]
    data = np.array([[float(v) for v in r] for r in rows[1:]])
    xs = [int(name.split(".x")[-1]) / 100 for name in header[1:]]
    return data[:, 0], data[:, 1:], xs


def amplitudes(t, eta, t0, t1, omega):
    """Complex amplitude A_j per gauge, eta_j ~ c_j + Re(A_j exp(i omega t)), least squares over [t0, t1]."""
    import numpy as np

    keep = (t >= t0) & (t <= t1)
    tt = t[keep]
    M = np.column_stack([np.ones_like(tt), np.cos(omega * tt), np.sin(omega * tt)])
    coef, *_ = np.linalg.lstsq(M, eta[keep], rcond=None)
    # Re(A e^{iwt}) = Re(A) cos - Im(A) sin
    return coef[1] - 1j * coef[2], coef[0]


def separate(A, xs, kappa, x_ref):
    """Least squares for (a_I, a_R) at x_ref; returns a_I, a_R and the residual's norm."""
    import numpy as np

    x = np.asarray(xs) - x_ref
    M = np.column_stack([np.exp(-1j * kappa * x), np.exp(1j * kappa * x)])
    sol, *_ = np.linalg.lstsq(M, A, rcond=None)
    return sol[0], sol[1], float(np.linalg.norm(M @ sol - A))


def fit_kappa(A, xs, x_ref, k0):
    """The (k, beta) whose separation leaves the smallest residual: a grid, then a finer one."""
    import numpy as np

    best = None
    for ks, bs in ((np.linspace(0.7 * k0, 1.3 * k0, 121), np.linspace(0, 0.6, 31)),):
        for k in ks:
            for b in bs:
                r = separate(A, xs, k - 1j * b, x_ref)[2]
                if best is None or r < best[0]:
                    best = (r, k, b)
    _, k1, b1 = best
    for k in np.linspace(k1 - 0.01 * k0, k1 + 0.01 * k0, 41):
        for b in np.linspace(max(0, b1 - 0.03), b1 + 0.03, 31):
            r = separate(A, xs, k - 1j * b, x_ref)[2]
            if r < best[0]:
                best = (r, k, b)
    return best[1], best[2]


def zero_down_heights(t, eta):
    """(time of the wave's start, height) of each zero-down-crossing wave of eta - its running mean."""
    import numpy as np

    n = max(1, int(round(PERIOD / (t[1] - t[0]))))
    mean = np.convolve(eta, np.ones(n) / n, mode="same")
    e = eta - mean
    down = np.where((e[:-1] > 0) & (e[1:] <= 0))[0]
    return [(t[a], float(e[a:b + 1].max() - e[a:b + 1].min())) for a, b in zip(down[:-1], down[1:])]


def analyse(case, path):
    import numpy as np

    t, eta, xs = read_gauges(path)
    omega = 2 * math.pi / PERIOD
    level = float(eta[(t > START - 0.5) & (t <= START)].mean())  # still water before the paddle starts
    k0 = wavenumber(PERIOD, level)
    cg = group_velocity(PERIOD, k0, level)
    x_ref = 0.5 * (xs[0] + xs[-1])
    inc = (START + xs[-1] / cg + 2.5 * PERIOD, START + (2 * NEAR[case] - xs[-1]) / cg)
    win = (START + (2 * FAR[case] - xs[0]) / cg + 2.5 * PERIOD, min(t[-1], START + (2 * FAR[case] + xs[0]) / cg))
    out = {"case": case, "level": level, "k0": k0, "cg": cg, "x_ref": x_ref, "inc": inc, "win": win,
           "t": t, "eta": eta, "xs": xs}
    if win[1] - win[0] < PERIOD:
        out["error"] = f"window {win[0]:.2f}-{win[1]:.2f} s shorter than a period (record ends at {t[-1]:.2f} s)"
        return out
    A, _ = amplitudes(t, eta, *win, omega)
    aI, aR, _ = separate(A, xs, k0, x_ref)
    out["theory"] = (2 * abs(aI), 2 * abs(aR), abs(aR) / abs(aI))
    k, beta = fit_kappa(A, xs, x_ref, k0)
    aI, aR, res = separate(A, xs, k - 1j * beta, x_ref)
    out["fitted"] = (2 * abs(aI), 2 * abs(aR), abs(aR) / abs(aI), k, beta, res / np.linalg.norm(A))
    out["gauge_H"] = [2 * abs(a) for a in A]
    if inc[1] - inc[0] >= 0.5 * PERIOD:
        Ai, _ = amplitudes(t, eta, *inc, omega)
        ki, bi = fit_kappa(Ai, xs, x_ref, k0)
        aIi, aRi, _ = separate(Ai, xs, ki - 1j * bi, x_ref)
        out["incident_only"] = (2 * abs(aIi), 2 * abs(aRi), ki, bi)
    return out


def run_case(case, binary, scenario, work, spacing):
    length, extra, _ = CASES[case]
    out = os.path.join(work, case)
    t_end = math.ceil(t_end_for(case) * 10) / 10
    cmd = [binary, "run", scenario, "-v", f"spacing={spacing}", "-v", f"period={PERIOD}", "-v", f"stroke={STROKE}",
           "-v", "gauges=" + ",".join(f"{x:g}" for x in GAUGES), "-v", f"t_end={t_end}", "-v", f"out={out}"] + extra
    print(" ".join(cmd), flush=True)
    t0 = time.time()
    with open(os.path.join(work, case + ".log"), "w") as log:
        subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, check=True, cwd=work)
    wall = time.time() - t0
    with open(os.path.join(work, case + ".time"), "w") as f:
        f.write(f"{wall:.0f}\n")
    return wall



def plot(results, png):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    fig, axes = plt.subplots(len(results) + 1, 1, figsize=(9, 2.3 * (len(results) + 1)), sharex=True)
    colors = {"wall": "C3", "damping": "C0", "beach": "C2"}
    for ax, r in zip(axes, results):
        t = r["t"]
        for j in (0, len(r["xs"]) - 1):
            ax.plot(t, (r["eta"][:, j] - r["level"]) * 1000, lw=0.7, label=f"x = {r['xs'][j]:.2f} m")
        if r["inc"][1] > r["inc"][0]:
            ax.axvspan(*r["inc"], color="0.9", lw=0)
        ax.axvspan(*r["win"], color=colors[r["case"]], alpha=0.15, lw=0)
        txt = CASES[r["case"]][2]
        if "fitted" in r:
            txt += f": K_r = {r['fitted'][2]:.2f}"
        ax.set_title(txt, fontsize=9)
        ax.set_ylabel("eta (mm)")
        ax.legend(loc="upper left", fontsize=7)
    ax = axes[-1]
    for r in results:
        hs = zero_down_heights(r["t"], r["eta"][:, 0])
        ax.plot([a for a, _ in hs], [h * 1000 for _, h in hs], "o-", ms=3, color=colors[r["case"]],
                label=f"{r['case']} (gauge x = {r['xs'][0]:.2f} m)")
    ax.set_ylabel("wave height (mm)")
    ax.set_xlabel("t (s)")
    ax.legend(fontsize=7, loc="upper left")
    fig.suptitle("wave flume, T = 1.0 s, S = 40 mm, d = 0.3 m: gauge records (grey: incident window; "
                 "coloured: the window K_r is measured in)\nbottom: zero-down-crossing wave heights at the "
                 "nearest gauge", fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=100)


def report(results, times, args, path):
    now = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
    rows = []
    for r in results:
        name = r["case"]
        if "error" in r:
            rows.append(f"| {name} | {CASES[name][2]} | {r['error']} | | | | |")
            continue
        HI, HR, Kr, k, beta, res = r["fitted"]
        at_end = Kr * math.exp(2 * beta * (NEAR[name] - r["x_ref"]))
        rows.append(f"| {name} | {CASES[name][2]} | {r['win'][0]:.1f}-{r['win'][1]:.1f} | {HI * 1000:.1f} | "
                    f"{HR * 1000:.1f} | **{Kr:.2f}** | {r['theory'][2]:.2f} | {k:.2f} / {beta:.2f} | {res:.3f} | "
                    f"{at_end:.2f} at x = {NEAR[name]:g} m | {times.get(name, '?')} |")
    inc_rows = []
    for r in results:
        if "incident_only" in r:
            HI, HR, ki, bi = r["incident_only"]
            inc_rows.append(f"| {r['case']} | {r['inc'][0]:.1f}-{r['inc'][1]:.1f} | {HI * 1000:.1f} | "
                            f"{HR * 1000:.1f} | {ki:.2f} / {bi:.2f} |")
    k0 = results[0]["k0"]
    cg = results[0]["cg"]
    said = []
    by = {r["case"]: r for r in results if "fitted" in r}
    if "wall" in by:
        r = by["wall"]
        HI, HR, Kr, k, beta, _ = r["fitted"]
        perfect = math.exp(-2 * beta * (5.0 - r["x_ref"]))
        kd2 = 2 * r["k0"] * r["level"]
        H_paddle = STROKE * 2 * (math.cosh(kd2) - 1) / (math.sinh(kd2) + kd2)
        head = ("The wall reflects the whole wave; the fluid's damping takes the rest on the way"
                if Kr / perfect > 0.9 else "The wall")
        said.append(f"- *{head}.* K_r = {Kr:.2f} at the "
                    f"array, where a wall that reflects everything, seen through the fluid's measured damping "
                    f"(beta = {beta:.2f} 1/m over the {2 * (5.0 - r['x_ref']):.0f} m there and back), would give "
                    f"exp(-2 beta (5 - x_c)) = {perfect:.2f}. The same damping is why the incident wave is "
                    f"{HI * 1000:.0f} mm high at x_c against linear wavemaker theory's {H_paddle * 1000:.0f} mm at the paddle "
                    f"(at this spacing, coarser than the validation's 0.02 m; [wave_flume.md](wave_flume.md)).")
    if "damping" in by:
        r = by["damping"]
        HI, HR, Kr, k, beta, _ = r["fitted"]
        Kt = r["theory"][2]
        said.append(f"- *The damping zone takes the reflection out.* K_r = {Kr:.3f} ({Kt:.3f} with theory's k and no "
                    f"beta), a reflected wave of {HR * 1000:.1f} mm ({max(Kr, Kt) * HI * 1000:.1f} mm at most) on an "
                    f"incident one of {HI * 1000:.1f} mm. The two fits differ by {abs(Kr - Kt):.3f}, which is about "
                    f"what the method resolves here: the zone leaves a reflection of at most {max(Kr, Kt):.2f}"
                    + (f", against the bare wall's {by['wall']['fitted'][2]:.2f} at the same array." if "wall" in by else "."))
        said.append(f"  The gauges' heights fall steadily along the array "
                    f"({', '.join(f'{h * 1000:.1f}' for h in r['gauge_H'])} mm), a progressive wave's, where "
                    f"the wall's run shows the partial standing wave "
                    f"({', '.join(f'{h * 1000:.1f}' for h in by['wall']['gauge_H'])} mm)." if "wall" in by else "")
    if "beach" in by:
        r = by["beach"]
        HI, HR, Kr, k, beta, _ = r["fitted"]
        said.append(f"- *The beach* (the scenario's default) reflects K_r = {Kr:.2f} ({r['theory'][2]:.2f} with theory's k) "
                    f"at the array, {Kr * math.exp(2 * beta * (4.5 - r['x_ref'])):.2f} referred to its toe"
                    + (": it absorbs about as well as the damping zone, so the scenario keeps the beach and no zone by "
                       "default (and [wave_flume.md](wave_flume.md)'s numbers stand); `-v damping=LENGTH` adds a zone "
                       "to a flume that ends in a wall (`-v beach=false`)." if Kr < 0.1 else "."))
    said.append(f"- Only one zone was measured: {CASES['damping'][1][-1].split('=')[1]} m long (about "
                f"{1.5 * k0 / (2 * math.pi):.1f} wavelengths) at the `damping` fix's default rate of 10 1/s, at one "
                f"period. How short a zone, or how low a rate, still absorbs is not measured here.")
    said = "\n".join(x for x in said if x)
    cases = ",".join(r["case"] for r in results)
    text = f"""# The wave flume's reflected wave, with and without a damping zone

Measured {now} on {machine()}, shared with other work; one run at a time, 2 threads. Made by

```sh
/usr/bin/python3 share/validation/flume_reflection.py --cases {cases} --spacing {args.spacing}
```

which runs `scenarios/wave_flume.lua` (WCSPH, the scenario's defaults but the spacing,
{args.spacing} m) at T = {PERIOD} s, S = {STROKE * 1000:.0f} mm, d = {DEPTH} m (linear theory: k =
{k0:.2f} 1/m, L = {2 * math.pi / k0:.2f} m, c_g = {cg:.2f} m/s) with four gauges at x =
{", ".join(f"{x:.2f}" for x in GAUGES)} m (`-v gauges=...`), in a flume 5 m long ending in a
vertical wall (`-v length=5 -v beach=false`), the same with a damping zone over its last 1.5 m
(`-v damping=1.5`: x = 3.5 to 5 m, about 1.1 wavelengths, the `damping` fix's default rate of
10 1/s), and the scenario's default 6 m flume with its beach.

**Method.** At the paddle's frequency, each gauge's record over a window is fitted by least
squares with a constant, cos(omega t) and sin(omega t), giving a complex amplitude A_j; the four
A_j are then fitted with an incident and a reflected wave,

    A_j = a_I exp(-i kappa (x_j - x_c)) + a_R exp(+i kappa (x_j - x_c)),   kappa = k - i beta,

(Mansard & Funke 1980, at one frequency; with two gauges and beta = 0 it is Goda & Suzuki 1976),
x_c = {results[0]['x_ref']:.2f} m the array's centre. beta is the fluid's numerical damping of
amplitude per metre (each wave decays along its own direction); k and beta are fitted too, as the
pair that leaves the smallest residual. **K_r = |a_R| / |a_I|** at x_c, H = 2|a|. The window
opens when the reflected train has grown at every gauge (its front, at linear theory's c_g from
the reflector, reached the nearest gauge 2.5 periods before: the paddle's two-period ramp and a
half) and closes when the wave re-reflected by the paddle (which absorbs nothing) reaches the
nearest gauge. For the beach the reflector is taken at its still shoreline, x = 5.7 m.

| case | far end | window (s) | H_I (mm) | H_R (mm) | K_r | K_r, theory's k, beta = 0 | fitted k (1/m) / beta (1/m) | residual / norm | K_r exp(2 beta (x_r - x_c)) | run (s) |
|---|---|---|---|---|---|---|---|---|---|---|
{chr(10).join(rows)}

(H_I and H_R at the array's centre; "residual / norm": how much of the four gauges' amplitudes
the two waves leave unexplained; the last column but one refers K_r to where the far end
starts, x_r (the wall; the zone's start; the beach's toe), taking out the fluid's own damping
beta over the way there and back: what the far end itself reflects. "run": the run's wall-clock
seconds.)

What they say:

{said}

Before the reflection's front (at c_g) reaches the farthest gauge, the incident wave alone (the
same fit over the earlier, grey window; what it calls H_R there is the fit's error together with
the reflection's forerunners, which travel faster than c_g; k and beta there come from the
incident wave's phase and decay along the array):

| case | window (s) | H_I (mm) | H_R (mm) | fitted k / beta (1/m) |
|---|---|---|---|---|
{chr(10).join(inc_rows)}

![gauge records and wave heights](flume_reflection.png)
"""
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)
    return text


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.normpath(os.path.join(here, "..", ".."))
    ap.add_argument("--binary", default=os.path.join(root, "build", "pbfengine"))
    ap.add_argument("--scenario", default=os.path.join(root, "scenarios", "wave_flume.lua"))
    ap.add_argument("--work", default="flume_reflection_runs", help="directory for the runs (default ./flume_reflection_runs)")
    ap.add_argument("--cases", default="wall,damping,beach")
    ap.add_argument("--spacing", type=float, default=0.03)
    ap.add_argument("--analyse-only", action="store_true", help="do not run; analyse the runs already in --work")
    ap.add_argument("--report", default=os.path.join(root, "docs", "validation", "flume_reflection.md"))
    args = ap.parse_args()
    work = os.path.abspath(args.work)
    os.makedirs(work, exist_ok=True)
    cases = [c for c in args.cases.split(",") if c]
    times = {}
    for c in cases:
        if not args.analyse_only:
            times[c] = f"{run_case(c, args.binary, args.scenario, work, args.spacing):.0f}"
        elif os.path.exists(os.path.join(work, c + ".time")):
            times[c] = open(os.path.join(work, c + ".time")).read().strip()
    results = [analyse(c, os.path.join(work, c, "gauges.csv")) for c in cases]
    for r in results:
        if "fitted" in r:
            HI, HR, Kr, k, beta, res = r["fitted"]
            print(f"{r['case']}: window {r['win'][0]:.2f}-{r['win'][1]:.2f} s, H_I {HI * 1000:.1f} mm, H_R {HR * 1000:.1f} mm, "
                  f"K_r {Kr:.3f} (theory's k: {r['theory'][2]:.3f}), k {k:.3f}, beta {beta:.3f}, residual {res:.3f}; "
                  f"gauge heights {', '.join(f'{h * 1000:.1f}' for h in r['gauge_H'])} mm")
        else:
            print(f"{r['case']}: {r.get('error')}")
        if "incident_only" in r:
            print(f"   incident only {r['inc'][0]:.2f}-{r['inc'][1]:.2f} s: H_I {r['incident_only'][0] * 1000:.1f} mm, "
                  f"H_R {r['incident_only'][1] * 1000:.1f} mm, k {r['incident_only'][2]:.3f}, beta {r['incident_only'][3]:.3f}")
    report(results, times, args, args.report)
    plot(results, os.path.splitext(args.report)[0] + ".png")
    print("wrote", args.report)
    return 0


if __name__ == "__main__":
    sys.exit(main())
