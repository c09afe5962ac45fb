#!/usr/bin/env python3
"""Memory of a distributed run's set-up: does a scene funnel through one rank?

One scene, a block of water of --particles particles (default 2,000,000) in a 2 x 1 x 1 m box,
with the PBF pipeline, run for one step, made four ways: a lattice (pbf.lattice), a CSV
and a .vtu particle file (pbf.read_particles; the .vtu is a dump/vtk frame) and a restart
(pbf.read_restart; the files are written first). Each is run as one process and as 2 ranks (mpirun --bind-to none,
1 thread a rank), under /usr/bin/time, and the table gives each process's peak resident
memory (the largest of the ranks'), and the wall time of the whole run. A rank that built or
read the whole scene before keeping its half would peak as high as one process does; a rank
that makes or reads only its share peaks near half of it.

    share/benchmarks/mpi_setup.py --binary build/pbfengine [--particles 2000000]
                                  [--compare OTHER_BINARY] [--out docs/performance]

--compare runs another build (for example one from before the change) the same way, as more
columns. Writes Markdown on stdout, and with --out also DIR/mpi_setup.md.
"""
import argparse
import datetime
import os
import platform
import subprocess
import sys
import tempfile
import time

SCENE = """-- mpi_setup.py's scene: a block of water, made by -v source=lattice|csv|vtu|restart
local source = var.source
local s = {spacing}
if source == "restart" then
  pbf.read_restart(var.file)
else
  pbf.domain{{lo = {{0, 0, 0}}, hi = {{2, 1, 1}}}}
  pbf.kernel_radius(2 * s)
  pbf.timestep(0.001)
  if source == "lattice" then
    pbf.lattice{{lo = {{0, 0, 0}}, hi = {{{length}, 1, {height}}}, spacing = s}}
  else
    pbf.read_particles(var.file)
  end
end
pbf.fix("gravity", "gravity", {{acceleration = {{0, 0, -9.81}}}})
pbf.fix("pbf", "pbf", {{iterations = 4}})
pbf.fix("walls", "box", {{}})
if var.vtk then pbf.fix("vtk", "dump/vtk", {{path = var.vtk, every = 1, fields = {{"velocity"}}}}) end
pbf.run(1)
if var.save then pbf.write_restart(var.save) end
"""


def environment():
    env = dict(os.environ)
    env.update({"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
                "OMPI_MCA_btl_vader_single_copy_mechanism": "none", "OMP_NUM_THREADS": "1"})
    return env


def run(args, binary, ranks, script, variables, work):
    """Peak resident memory (MiB, the largest rank's) and wall seconds of one run."""
    # Each process's peak into its own file (PREFIX.RANK), as the ranks' stderr interleave.
    prefix = os.path.join(work, "maxrss")
    for old in os.listdir(work):
        if old.startswith("maxrss."):
            os.remove(os.path.join(work, old))
    command = ["sh", "-c", 'exec /usr/bin/time -f "%M" -o "$0.${OMPI_COMM_WORLD_RANK:-0}" "$@"', prefix,
               binary, "run", "--log", "none", script]
    for name, value in variables.items():
        command += ["-v", f"{name}={value}"]
    if ranks > 1:
        command = [args.mpirun, "-q", "--bind-to", "none", "--oversubscribe", "-np", str(ranks)] + command
    start = time.monotonic()
    done = subprocess.run(command, capture_output=True, text=True, env=environment(), cwd=work)
    seconds = time.monotonic() - start
    peaks = []
    for name in os.listdir(work):
        if name.startswith("maxrss."):
            with open(os.path.join(work, name)) as f:
                peaks.append(int(f.read().split()[-1]))
    if done.returncode != 0 or len(peaks) != ranks:
        sys.exit(f"mpi_setup.py: {ranks} rank(s) of {binary} failed ({done.returncode}):\n{done.stderr[-2000:]}")
    return max(peaks) / 1024.0, seconds


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", required=True)
    parser.add_argument("--compare", help="another pbfengine to run the same way")
    parser.add_argument("--mpirun", default="mpirun")
    parser.add_argument("--particles", type=int, default=2_000_000)
    parser.add_argument("--out", help="directory for mpi_setup.md")
    args = parser.parse_args()
    binaries = [("this build", os.path.abspath(args.binary))]
    if args.compare:
        binaries.append(("compared build", os.path.abspath(args.compare)))
    # A block 2 x 1 x H m at spacing s holding about the requested count, as deep as it is wide.
    spacing = (1.0 * 1.0 / args.particles) ** (1 / 3)
    length, height = 1.0, 1.0
    with tempfile.TemporaryDirectory() as work:
        script = os.path.join(work, "setup.lua")
        with open(script, "w") as f:
            f.write(SCENE.format(spacing=f"{spacing:.6g}", length=length, height=height))
        restart = os.path.join(work, "scene.restart")
        frames = os.path.join(work, "frames")
        os.makedirs(frames)
        run(args, binaries[0][1], 1, script,
            {"source": "lattice", "save": restart, "vtk": os.path.join(frames, "block_*.vtu")}, work)
        vtu = os.path.join(frames, "block_00000.vtu")
        csv = os.path.join(work, "scene.csv")
        n = int(length / spacing + 1e-9)
        with open(csv, "w") as f:  # the lattice's sites, x fastest
            f.write("x,y,z\n")
            rows = []
            for k in range(int(height / spacing + 1e-9)):
                for j in range(int(1.0 / spacing + 1e-9)):
                    z, y = (k + 0.5) * spacing, (j + 0.5) * spacing
                    rows.extend(f"{(i + 0.5) * spacing:.7g},{y:.7g},{z:.7g}\n" for i in range(n))
                if len(rows) > 100_000:
                    f.writelines(rows)
                    rows = []
            f.writelines(rows)
        particles = sum(1 for _ in open(csv)) - 1
        results = {}
        for source, file in (("lattice", None), ("csv", csv), ("vtu", vtu), ("restart", restart)):
            for label, binary in binaries:
                for ranks in (1, 2):
                    variables = {"source": source}
                    if file:
                        variables["file"] = file
                    results[(source, label, ranks)] = run(args, binary, ranks, script, variables, work)
    stamp = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    lines = [f"Set-up memory of a distributed run: {particles:,} particles, one PBF step "
             f"(share/benchmarks/mpi_setup.py, {stamp}, {platform.node()}, {os.cpu_count()} cores).", "",
             "Peak resident memory of a process (MiB; with 2 ranks the larger rank's) and the run's wall time.", ""]
    header = "| source |"
    rule = "|---|"
    for label, _ in binaries:
        header += f" {label}: 1 process | {label}: 2 ranks, each | 2 ranks / 1 |"
        rule += "---|---|---|"
    lines += [header, rule]
    for source in ("lattice", "csv", "vtu", "restart"):
        row = f"| {source} |"
        for label, _ in binaries:
            one, two = results[(source, label, 1)], results[(source, label, 2)]
            row += f" {one[0]:.0f} MiB, {one[1]:.1f} s | {two[0]:.0f} MiB, {two[1]:.1f} s | {two[0] / one[0]:.2f} |"
        lines.append(row)
    text = "\n".join(lines) + "\n"
    print(text)
    if args.out:
        with open(os.path.join(args.out, "mpi_setup.md"), "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
