#!/usr/bin/env python3
"""Distributed-run tests: pbfengine under mpirun at 2 and 3 ranks against one process.

    run.py --binary build/pbfengine --case NAME [--mpirun mpirun]

Cases:
  identical   tests/mpi/dambreak.lua on 1 process, 2 and 3 ranks: every text frame, the
              probes' CSV and the thermo CSV have the same bytes (the fluid crosses every
              rank boundary).
  identical_wcsph  scenarios/dambreak.lua with WCSPH (leapfrog, wcsph, sph_viscosity, cfl)
              likewise: frames and thermo CSV (the front, the gauge at the back wall).
  script_error  an error every rank meets (an unknown style): one message, exit code 1.
  rank_error  an error only rank 1 meets, while the others wait in a collective call: its
              message, naming the rank, once; exit code 1; no rank left running.
  refused     a style not yet written for several ranks (solid): refused by name, exit code 1.

Open MPI is run as the CI runs it: as root it needs OMPI_ALLOW_RUN_AS_ROOT(_CONFIRM); in
containers the vader transport's single-copy mechanism is off; --oversubscribe lets 3 ranks
share 2 cores, and idle ranks yield (mpi_yield_when_idle) instead of spinning.
"""
import argparse
import filecmp
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TIMEOUT = 240


def environment():
    env = dict(os.environ)
    env.update({"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
                "OMPI_MCA_btl_vader_single_copy_mechanism": "none", "OMPI_MCA_mpi_yield_when_idle": "1",
                "OMP_NUM_THREADS": "1"})
    return env


def run(args, ranks, script, variables, cwd):
    command = [args.binary, "run", script, "--log", "none"]
    for name, value in variables.items():
        command += ["-v", f"{name}={value}"]
    if ranks > 1:
        command = [args.mpirun, "-q", "--oversubscribe", "--bind-to", "none", "-np", str(ranks)] + command
    return subprocess.run(command, cwd=cwd, env=environment(), capture_output=True, text=True, timeout=TIMEOUT)


def fail(message):
    print("FAIL:", message)
    sys.exit(1)


def same_outputs(args, work, script, variables, files):
    """Runs at 1, 2 and 3 ranks; fails unless the text frames and `files` are the same bytes.
    Returns the 1-rank output directory and its frames."""
    outputs = {}
    for ranks in (1, 2, 3):
        out = os.path.join(work, f"r{ranks}")
        result = run(args, ranks, script, dict(variables, out=out), work)
        if result.returncode != 0:
            fail(f"{ranks} rank(s): exit {result.returncode}\n{result.stdout}\n{result.stderr}")
        outputs[ranks] = out
        print(f"{ranks} rank(s):", [line.strip() for line in result.stdout.splitlines() if "ranks;" in line])
    frames = sorted(f for f in os.listdir(outputs[1]) if f.endswith(".txt"))
    if len(frames) < 5:
        fail(f"expected at least 5 frames, found {frames}")
    for ranks in (2, 3):
        for name in frames + files:
            a, b = os.path.join(outputs[1], name), os.path.join(outputs[ranks], name)
            if not os.path.exists(b) or not filecmp.cmp(a, b, shallow=False):
                fail(f"{name} differs between 1 process and {ranks} ranks")
    return outputs[1], frames


def identical(args, work):
    out, frames = same_outputs(args, work, os.path.join(HERE, "dambreak.lua"), {}, ["thermo.csv", "probes.csv"])
    # The fluid reached the far wall: past every initial cut (all inside the column, x < 0.3).
    with open(os.path.join(out, frames[-1])) as f:
        rows = [line.split() for line in f if line[0].isdigit() and " " in line]
    farthest = max(float(r[1]) for r in rows)
    if farthest < 0.6:
        fail(f"the fluid reached only x = {farthest}: it did not cross the ranks' boundaries")
    print(f"{len(frames)} frames, probes.csv and thermo.csv identical at 1, 2 and 3 ranks; front at x = "
          f"{farthest:.3f} m")


def identical_wcsph(args, work):
    scenario = os.path.join(HERE, "..", "..", "scenarios", "dambreak.lua")
    variables = {"solver": "wcsph", "particles": 1500, "t_end": 0.15, "interval": 0.03, "restart_interval": 0}
    _, frames = same_outputs(args, work, scenario, variables, ["thermo.csv"])
    print(f"WCSPH: {len(frames)} frames and thermo.csv identical at 1, 2 and 3 ranks")


def expect_failure(result, needle, name):
    if result.returncode == 0:
        fail(f"{name}: exit code 0\n{result.stdout}\n{result.stderr}")
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    ours = [line for line in lines if needle in line]
    if len(ours) != 1:
        fail(f"{name}: expected one message with '{needle}', stderr was:\n{result.stderr}")
    print(f"{name}: exit {result.returncode}: {ours[0]}")


def script_error(args, work):
    path = os.path.join(work, "bad.lua")
    with open(path, "w") as f:
        f.write('pbf.domain{lo = {0, 0, 0}, hi = {1, 1, 1}}\npbf.fix("x", "no_such_style", {})\n')
    expect_failure(run(args, 3, path, {}, work), "unknown fix style 'no_such_style'", "script_error")


# A block of water in a unit box, then a pipeline and what the script does with it.
def small_scene(work, name, rest):
    path = os.path.join(work, name)
    with open(path, "w") as f:
        f.write("""pbf.domain{lo = {0, 0, 0}, hi = {1, 1, 1}}
pbf.kernel_radius(0.1)
pbf.timestep(0.001)
pbf.lattice{lo = {0, 0, 0}, hi = {0.5, 0.5, 0.5}, spacing = 0.05}
""" + rest)
    return path


def rank_error(args, work):
    path = small_scene(work, "rank.lua", """pbf.fix("gravity", "gravity", {acceleration = {0, 0, -9.81}})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.run(10)
if pbf.rank() == 1 then error("rank one gives up") end
pbf.run(1000000)
""")
    result = run(args, 3, path, {}, work)
    expect_failure(result, "rank one gives up", "rank_error")
    if "rank 1:" not in result.stderr:
        fail("rank_error: the message does not name rank 1")


def refused(args, work):
    path = small_scene(work, "solid.lua", """pbf.fix("pbf", "pbf", {})
pbf.fix("ball", "solid", {shape = "sphere", center = {0.8, 0.8, 0.8}, radius = 0.1})
pbf.run(1)
""")
    expect_failure(run(args, 2, path, {}, work), "fix 'ball' (solid) does not run on several MPI ranks yet",
                   "refused")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", required=True)
    parser.add_argument("--mpirun", default="mpirun")
    parser.add_argument("--case", required=True,
                        choices=["identical", "identical_wcsph", "script_error", "rank_error", "refused"])
    args = parser.parse_args()
    args.binary = os.path.abspath(args.binary)
    with tempfile.TemporaryDirectory() as work:
        globals()[args.case](args, work)


if __name__ == "__main__":
    main()
