#!/usr/bin/env python3
"""The largest stable time step of each solver, found by bisection.

Runs the dam break of scenarios/dambreak.lua at a small size (1000 particles: a = 0.1 m,
spacing 0.01 m, h = 0.02 m) at a fixed time step dt, to t = 0.5 s: past the surge's impact on
the far wall (T = 7), with a thermo line after every step and two more columns, the potential
energy and the fastest speed (a wrapper adds them to the scene's pbf.thermo). A run is stable
at dt when

    it ends       it reaches t = 0.5 s: the engine did not stop it (a NaN, clumps, a particle
                  out of the box, WCSPH's density limit, PBF's step length)
    packed        no particle is ever at twice the rest density: err.max < 1 after every step
                  (particles on top of one another, not a fluid)
    compressed    the mean compression err.compression stays below 20% (a bound, not an
                  accuracy target: PBF at 4 iterations passes 10% at 2.3 times its step)
    energy        the mechanical energy (kinetic plus potential) never exceeds its start by
                  more than 0.1%: neither solver may create energy (PBF's constraint stores
                  none; WCSPH's elastic energy, which the sum leaves out, is below 1e-4 of it)

The bisection halves log(dt) between a stable and an unstable step until they are within 2%:

    PBF      -v dt=DT (4 iterations, the scene's vorticity and XSPH), from the scene's step
             0.4 h / sqrt(2 g 2a) = 4.04 ms to 8 times it
    WCSPH    -v solver=wcsph -v fixed_dt=true -v dt=DT: no cfl, the step as given, from cfl's
             bound 0.15 h / c0 = 0.151 ms (c0 = 10 sqrt(2 g 2a) = 19.81 m/s) to 16 times it

It prints every run (dt, verdict, why), a Markdown table of the results, and what the engine
says at the smallest unstable step found (or that it ran on).

    /usr/bin/python3 share/validation/stable_step.py [--binary build/pbfengine] [--solver pbf wcsph]
        [--particles 1000] [--t-end 0.5] [-v NAME=VALUE ...]

-v passes a variable to the scenario for every run (a variant: -v iterations=8).
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
G = 9.81
A = 0.1             # m, the scene's column width (its default)
TOLERANCE = 1.02    # the bisection stops when unstable / stable is below this
MOST_PACKED = 1.0   # err.max: twice the rest density
MOST_COMPRESSION = 0.20
MOST_GAIN = 1e-3    # of the mechanical energy at the start


# The scene as it is, with the potential energy and the fastest speed in its thermo lines.
WRAPPER = """local thermo = pbf.thermo
pbf.thermo = function(settings)
  pbf.compute("stable_pe", "potential_energy")
  pbf.compute("stable_v", "speed")
  table.insert(settings.columns, "stable_pe")
  table.insert(settings.columns, "stable_v.max")
  return thermo(settings)
end
dofile(var.scene)
"""


def run(binary, solver, dt, args, work):
    """One run at dt; returns (verdict, why, wall seconds, the engine's message)."""
    csv_path = os.path.join(work, "thermo.csv")
    if os.path.exists(csv_path):
        os.remove(csv_path)
    wrapper = os.path.join(work, "wrapper.lua")
    with open(wrapper, "w") as f:
        f.write(WRAPPER)
    cmd = [binary, "run", wrapper, "--log", "none", "--threads", "1",
           "-v", f"scene={os.path.join(ROOT, 'scenarios', 'dambreak.lua')}",
           "-v", f"particles={args.particles}", "-v", f"t_end={args.t_end}", "-v", "out=",
           "-v", f"csv={csv_path}", "-v", "thermo=1e-9", "-v", f"solver={solver}", "-v", f"dt={dt!r}"]
    if solver == "wcsph":
        cmd += ["-v", "fixed_dt=true"]
    for v in args.vars:
        cmd += ["-v", v]
    start = time.time()
    done = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - start
    rows = []
    if os.path.exists(csv_path):
        with open(csv_path) as f:
            rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    if done.returncode != 0:
        message = next((line for line in done.stderr.splitlines() if "step" in line), done.stderr.strip())
        if not rows:
            sys.exit(f"stable_step.py: {' '.join(cmd)} failed before it started:\n{done.stderr[-2000:]}")
        return "unstable", "the engine stopped it", wall, message
    packed = max(float(r["err.max"]) for r in rows)
    compression = max(float(r["err.compression"]) for r in rows)
    energy = [float(r["ke"]) + float(r["stable_pe"]) for r in rows]
    gain = max(energy) / energy[0] - 1
    fastest = max(float(r["stable_v.max"]) for r in rows)
    if packed >= MOST_PACKED:
        return "unstable", f"a particle at rho/rho0 - 1 = {packed:.2f}", wall, ""
    if compression >= MOST_COMPRESSION:
        return "unstable", f"mean compression {100 * compression:.1f}%", wall, ""
    if gain > MOST_GAIN:
        return "unstable", f"mechanical energy {100 * gain:.1f}% above its start, fastest {fastest:.1f} m/s", wall, ""
    return "stable", (f"largest rho/rho0 - 1 {packed:.2f}, mean compression up to {100 * compression:.1f}%, "
                      f"energy gain {100 * gain:.3f}%, fastest {fastest:.1f} m/s"), wall, ""


def bisect(binary, solver, stable, unstable, args, work):
    """The largest stable dt within TOLERANCE, from a stable and an unstable step; and the
    engine's message at the smallest unstable step it found (if the engine stopped there)."""
    message = ""
    for dt in (stable, unstable):
        verdict, why, wall, said = run(binary, solver, dt, args, work)
        print(f"  {solver} dt = {dt:.4g} s: {verdict} ({why}; {wall:.1f} s)", flush=True)
        if (verdict == "stable") != (dt == stable):
            sys.exit(f"stable_step.py: the bracket [{stable}, {unstable}] s does not hold for {solver}")
        message = said or message
    while unstable / stable > TOLERANCE:
        dt = math.sqrt(stable * unstable)
        verdict, why, wall, said = run(binary, solver, dt, args, work)
        print(f"  {solver} dt = {dt:.4g} s: {verdict} ({why}; {wall:.1f} s)", flush=True)
        if verdict == "stable":
            stable = dt
        else:
            unstable, message = dt, said
    return stable, unstable, message


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "pbfengine"))
    ap.add_argument("--solver", nargs="+", default=["pbf", "wcsph"], choices=["pbf", "wcsph"])
    ap.add_argument("--particles", type=int, default=1000)
    ap.add_argument("--t-end", type=float, default=0.5)
    ap.add_argument("-v", dest="vars", action="append", default=[], help="NAME=VALUE for every run")
    args = ap.parse_args()
    if args.particles < 8:
        ap.error(f"--particles must be at least 8 (a column two particles across), got {args.particles}")
    if not (math.isfinite(args.t_end) and args.t_end > 0):
        ap.error(f"--t-end must be a positive number of seconds, got {args.t_end}")
    if not os.access(args.binary, os.X_OK):
        sys.exit(f"stable_step.py: {args.binary}: no such executable (build it, or give --binary)")
    layers = max(4, round(args.particles ** (1 / 3)))
    h = 2 * A / layers
    c0 = 10 * math.sqrt(2 * G * 2 * A)
    scene_dt = 0.4 * h / math.sqrt(2 * G * 2 * A)
    cfl_dt = 0.15 * h / c0
    # Brackets: the scene's step is stable and 8 times it is not (PBF); for WCSPH from cfl's
    # bound to 16 times it.
    brackets = {"pbf": (scene_dt, 8 * scene_dt), "wcsph": (cfl_dt, 16 * cfl_dt)}
    results = []
    with tempfile.TemporaryDirectory() as work:
        for solver in args.solver:
            stable, unstable, message = bisect(args.binary, solver, *brackets[solver], args, work)
            results.append((solver, stable, unstable, message))
    print(f"\n{args.particles} particles (h = {h:.4g} m), to t = {args.t_end} s; "
          f"scene step 0.4 h / sqrt(2 g 2a) = {scene_dt:.4g} s, cfl bound 0.15 h / c0 = {cfl_dt:.4g} s\n")
    print("| solver | largest stable dt | smallest unstable dt | in h / sqrt(2 g 2a) | in h / c0 |")
    print("|---|---|---|---|---|")
    for solver, stable, unstable, _ in results:
        print(f"| {solver} | {stable:.4g} s | {unstable:.4g} s | {stable / h * math.sqrt(2 * G * 2 * A):.3g} "
              f"| {stable * c0 / h:.3g} |")
    for solver, _, unstable, message in results:
        print(f"\n{solver} at {unstable:.4g} s: {message or '(the engine ran on: no stop)'}")


if __name__ == "__main__":
    main()
