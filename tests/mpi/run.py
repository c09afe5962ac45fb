#!/usr/bin/env python3
"""Distributed-run tests: pbfengine under mpirun at 2 and 3 ranks against one process.

    run.py --binary build/pbfengine --case NAME [--mpirun mpirun]

Cases:
  identical   tests/mpi/dambreak.lua on 1 process, 2 and 3 ranks: every text frame, the
              probes' CSV and the thermo CSV have the same bytes (the fluid crosses every
              rank boundary), and the VTK frames' pieces hold the rows of the 1-process .vtu.
  identical_flow  tests/mpi/inflow.lua (an emitter and a sink), both solvers, in a closed tank
              and in one periodic across its width: frames, thermo and probes identical at 1 to
              4 ranks (and, periodic, at 2 threads), initial + in - out = present, and a restart
              written on 3 ranks continued on 2 (periodic: and on 1 process at 2 threads) as the
              run that never stopped; and, at 1 to 3 ranks, PBF with the jet's velocity a Lua
              function of time and place, WCSPH with an inlet zone.
  identical_wcsph  scenarios/dambreak.lua with WCSPH (leapfrog, wcsph, sph_viscosity, cfl)
              likewise: frames, dump/image's pictures and the thermo CSV (the front, the
              gauge at the back wall).
  identical_dfsph  scenarios/dambreak.lua with DFSPH (dfsph, sph_viscosity, cfl) likewise, and
              scenarios/spheric_dambreak.lua at 5 cm with DFSPH: probes.csv and thermo.csv.
  identical_solid  scenarios/spheric_dambreak.lua at 5 cm (PBF, the box obstacle across the
              ranks' boundaries, its load in thermo, pressure probes and gauges): probes.csv and
              thermo.csv.
  identical_periodic  tests/mpi/periodic.lua, a dam break in a tank periodic along x and y
              (the column spreads through the faces and meets itself), on 1 process and 2, 3 and
              4 ranks: every text frame, probes.csv (probes and gauges beside the periodic faces)
              and thermo.csv have the same bytes (images cross the faces as ghosts); a restart
              written on 3 ranks at step 150 (particles beyond the faces x = 0, x = 0.8, y = 0 and
              y = 0.2 at that step's end, measured), continued on 2 and on 1,
              writes the later frames of the run that never stopped.
  sources     tests/mpi/sources.lua: particle files (.csv, and a .vtu frame), lattices (two on the same sites, one in a
              sphere), solids that leave particles out before the first run and after it, a
              lattice added between runs: every rank creates a share of each (about 1/ranks of
              the particles) and the frames and thermo CSV are those of one process.
  scene_file  scenarios/init_file.lua on a scene file of share/make_scene.py (each rank reads
              its share of the lines, the mass rule over the whole file): the same frames.
  restart     a restart written on 3 ranks, continued on 2 ranks and on 1 process, and one
              written by one process, continued on 3 (each rank reads its share of the
              records): the later frames are those of the run that never stopped; a damaged
              one is refused once.
  restart_wcsph  the same for WCSPH with the continuity density and cfl (state beyond
              positions and velocities): written on 3 ranks, continued on 2 and on 1.
  script_error  an error every rank meets (an unknown style): one message, exit code 1.
  rank_error  an error only rank 1 meets, while the others wait in a collective call: its
              message, naming the rank, once; exit code 1; no rank left running.
  per_particle  pbf.value of the per-particle density, printed by the script (once: print is
              rank 0's): the same line at 1, 2 and 3 ranks.
  signals     SIGUSR1 and SIGTERM sent to mpirun (2 ranks): a restart and the run goes on; a
              restart and a stop. Each restart continued (on 1 process, on 3 ranks) ends with
              the bits of the run that went on.

Open MPI is run as the CI runs it: as root it needs OMPI_ALLOW_RUN_AS_ROOT(_CONFIRM); in
containers the vader transport's single-copy mechanism is off; --oversubscribe lets 3 ranks
share 2 cores, and idle ranks yield (mpi_yield_when_idle) instead of spinning.
"""
import argparse
import filecmp
import os
import re
import signal
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TIMEOUT = 240


def environment():
    env = dict(os.environ)
    env.update({"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
                "OMPI_MCA_btl_vader_single_copy_mechanism": "none", "OMPI_MCA_mpi_yield_when_idle": "1",
                "OMP_NUM_THREADS": "1"})
    return env


def run(args, ranks, script, variables, cwd, threads=1):
    command = [args.binary, "run", script, "--log", "none"] + (["--threads", str(threads)] if threads > 1 else [])
    for name, value in variables.items():
        command += ["-v", f"{name}={value}"]
    if ranks > 1:
        command = [args.mpirun, "-q", "--oversubscribe", "--bind-to", "none", "-np", str(ranks)] + command
    return subprocess.run(command, cwd=cwd, env=environment(), capture_output=True, text=True, timeout=TIMEOUT)


def fail(message):
    print("FAIL:", message)
    sys.exit(1)


def same_outputs(args, work, script, variables, files, least_frames=5, rank_counts=(1, 2, 3)):
    """Runs at each of rank_counts (1 first); fails unless every file the 1-process run wrote in
    its output directory (text frames, CSVs, pictures; of its subdirectories, the surfaces'
    surface/) has the same bytes in the others', and `files` are among them. Returns the
    1-process output directory and its frames."""
    outputs = {}
    for ranks in rank_counts:
        out = os.path.join(work, f"r{ranks}")
        result = run(args, ranks, script, dict(variables, out=out), work)
        if result.returncode != 0:
            fail(f"{ranks} rank(s): exit {result.returncode}\n{result.stdout}\n{result.stderr}")
        outputs[ranks] = out
        print(f"{ranks} rank(s):", [line.strip() for line in result.stdout.splitlines() if "ranks;" in line])
    frames = sorted(f for f in os.listdir(outputs[1]) if f.endswith(".txt"))
    if len(frames) < least_frames:
        fail(f"expected at least {least_frames} frames, found {frames}")
    written = sorted(f for f in os.listdir(outputs[1]) if os.path.isfile(os.path.join(outputs[1], f)))
    surfaces = os.path.join(outputs[1], "surface")
    if os.path.isdir(surfaces):
        written += sorted(os.path.join("surface", f) for f in os.listdir(surfaces))
    for name in files:
        if name not in written:
            fail(f"the 1-process run wrote no {name}")
    for ranks in rank_counts[1:]:
        for name in written:
            a, b = os.path.join(outputs[1], name), os.path.join(outputs[ranks], name)
            if not os.path.exists(b) or not filecmp.cmp(a, b, shallow=False):
                fail(f"{name} differs between 1 process and {ranks} ranks")
    return outputs[1], frames


def vtk_rows(directory, frame):
    """{id: (velocity, density, position)} of one VTK frame: the .vtu, or the .pvtu's pieces."""
    sys.path.insert(0, os.path.join(HERE, ".."))
    import check_vtu  # the engine-independent reader of tests/check_vtu.py
    import xml.etree.ElementTree as ET
    whole = os.path.join(directory, "vtk", f"frame_{frame:05d}.vtu")
    if os.path.exists(whole):
        files = [whole]
    else:
        parallel = os.path.join(directory, "vtk", f"frame_{frame:05d}.pvtu")
        pieces = ET.parse(parallel).getroot().findall("PUnstructuredGrid/Piece")
        files = [os.path.join(directory, "vtk", p.get("Source")) for p in pieces]
    rows = {}
    for path in files:
        n, arrays = check_vtu.read_vtu(path)
        for i in range(n):
            key = arrays["id"][2][i]
            if key in rows:
                fail(f"{path}: particle {key} in two pieces")
            rows[key] = tuple(tuple(arrays[name][2][i * c:(i + 1) * c])
                              for name, c in (("velocity", 3), ("density", 1), ("Points", 3)))
    return rows


def identical(args, work):
    out, frames = same_outputs(args, work, os.path.join(HERE, "dambreak.lua"), {}, ["thermo.csv", "probes.csv"],
                               rank_counts=(1, 2, 3, 4))
    for frame in range(len(frames)):
        expected = vtk_rows(out, frame)
        for ranks in (2, 3, 4):
            if vtk_rows(os.path.join(work, f"r{ranks}"), frame) != expected:
                fail(f"VTK frame {frame}: the pieces of {ranks} ranks hold other rows than the 1-process file")
    with open(os.path.join(work, "r3", "vtk", "frame.pvd")) as f:
        if "frame_00001.pvtu" not in f.read():
            fail("the collection of 3 ranks does not list the parallel frames")
    # The fluid reached the far wall: past every initial cut (all inside the column, x < 0.3).
    with open(os.path.join(out, frames[-1])) as f:
        rows = [line.split() for line in f if line[0].isdigit() and " " in line]
    farthest = max(float(r[1]) for r in rows)
    if farthest < 0.6:
        fail(f"the fluid reached only x = {farthest}: it did not cross the ranks' boundaries")
    print(f"{len(frames)} frames, probes.csv, thermo.csv and the VTK frames' rows identical at 1, 2, 3 and 4 ranks; "
          f"front at x = "
          f"{farthest:.3f} m")


def identical_periodic(args, work):
    out, frames = same_outputs(args, work, os.path.join(HERE, "periodic.lua"), {}, ["thermo.csv", "probes.csv"],
                               rank_counts=(1, 2, 3, 4))
    # The fluid went through the faces: particles on both sides of x = 0 (the column starts in 0.2 < x < 0.5).
    with open(os.path.join(out, frames[-1])) as f:
        xs = [float(line.split()[1]) for line in f if line[0].isdigit() and " " in line]
    if not (min(xs) < 0.05 and max(xs) > 0.75):
        fail(f"the fluid spans x = {min(xs)} .. {max(xs)}: it did not reach the periodic faces")
    saved = os.path.join(work, "at150.restart")
    script = os.path.join(HERE, "periodic.lua")
    for ranks, variables in ((3, {"out": os.path.join(work, "first"), "steps": 150, "save": saved}),
                             (2, {"out": os.path.join(work, "on2"), "read": saved}),
                             (1, {"out": os.path.join(work, "on1"), "read": saved})):
        result = run(args, ranks, script, variables, work)
        if result.returncode != 0:
            fail(f"{ranks} rank(s) with {variables}: exit {result.returncode}\n{result.stdout}\n{result.stderr}")
    later = [f"f_{k:05d}.txt" for k in (4, 5)]  # steps 160, 200
    for name in later:
        for where in ("on2", "on1"):
            if not filecmp.cmp(os.path.join(out, name), os.path.join(work, where, name), shallow=False):
                fail(f"{name} of the periodic run continued {where} differs from the run that never stopped")
    print(f"periodic x and y: {len(frames)} frames, probes.csv and thermo.csv identical at 1, 2, 3 and 4 ranks; "
          f"a restart written on 3 ranks, continued on 2 and on 1: {', '.join(later)} identical")


def identical_flow(args, work):
    """An emitter and a sink, in a closed tank and in one periodic across its width: the same
    frames, thermo and probes at 1 to 4 ranks, both solvers, and (periodic) at 2 threads; a
    restart written on 3 ranks continued on 2 (and, periodic, on 1 process at 2 threads) as the
    run that never stopped; the same at 1 to 3 ranks for PBF with the jet's velocity a Lua
    function (every rank calls it alike) and for WCSPH with an inlet zone (its particles marked
    in a field that travels with them)."""
    script = os.path.join(HERE, "inflow.lua")
    for solver, periodic, extra in (("pbf", None, None), ("wcsph", None, None), ("pbf", "y", None),
                                    ("wcsph", "y", None), ("pbf", None, "profile"), ("wcsph", None, "buffer")):
        steps = 200 if solver == "pbf" else 800
        name = solver + (f" periodic {periodic}" if periodic else "") + (f" ({extra})" if extra else "")
        base = os.path.join(work, solver + (f"_periodic_{periodic}" if periodic else "") + (f"_{extra}" if extra else ""))
        os.makedirs(base)
        variables = {"solver": solver, "steps": steps}
        if periodic:
            variables["periodic"] = periodic
        if extra:
            variables[extra] = 1
        rank_counts = (1, 2, 3) if extra else (1, 2, 3, 4)
        out, frames = same_outputs(args, base, script, variables, ["thermo.csv", "probes.csv"], rank_counts=rank_counts)
        with open(os.path.join(out, "thermo.csv")) as f:
            rows = [line.strip().split(",") for line in f][2:]
        last = rows[-1]
        if not (float(last[2]) > 0 and float(last[4]) > 0):
            fail(f"{name}: nothing came in or went out ({last})")
        if int(float(last[1])) != int(float(rows[0][1])) + int(float(last[2])) - int(float(last[4])):
            fail(f"{name}: the count is not initial + in - out ({last})")
        continued = [(2, "on2", "2 ranks")]
        if periodic:
            threads2 = os.path.join(base, "t2")
            result = run(args, 1, script, dict(variables, out=threads2), base, threads=2)
            if result.returncode != 0:
                fail(f"{name} at 2 threads: exit {result.returncode}\n{result.stdout}\n{result.stderr}")
            for file in sorted(os.listdir(out)):
                if os.path.isfile(os.path.join(out, file)) and not filecmp.cmp(
                        os.path.join(out, file), os.path.join(threads2, file), shallow=False):
                    fail(f"{name}: {file} differs between 1 and 2 threads")
            continued.append((1, "on1t2", "1 process at 2 threads"))
        saved = os.path.join(base, "half.restart")
        first = dict(variables, out=os.path.join(base, "first"), steps=steps // 2, save=saved)
        result = run(args, 3, script, first, base)
        if result.returncode != 0:
            fail(f"{name} 3 ranks with {first}: exit {result.returncode}\n{result.stdout}\n{result.stderr}")
        later = [f for f in frames if int(f[2:7]) * 50 > steps // 2]
        for ranks, where, label in continued:
            then = dict(variables, out=os.path.join(base, where), read=saved)
            result = run(args, ranks, script, then, base, threads=2 if ranks == 1 else 1)
            if result.returncode != 0:
                fail(f"{name} {ranks} rank(s) with {then}: exit {result.returncode}\n{result.stdout}\n{result.stderr}")
            for frame in later:
                if not filecmp.cmp(os.path.join(out, frame), os.path.join(base, where, frame), shallow=False):
                    fail(f"{name}: {frame} of the run continued ({where}) differs from the run that never stopped")
        print(f"{name}: {len(frames)} frames, thermo.csv and probes.csv identical at 1 to {rank_counts[-1]} ranks"
              f"{' and at 2 threads' if periodic else ''} ({last[2]} in, {last[4]} out); a restart on 3 ranks "
              f"continued on {' and on '.join(label for _, _, label in continued)}: {', '.join(later)} identical")


def identical_wcsph(args, work):
    scenario = os.path.join(HERE, "..", "..", "scenarios", "dambreak.lua")
    variables = {"solver": "wcsph", "particles": 1500, "t_end": 0.15, "interval": 0.03, "restart_interval": 0,
                 "images": 0.05, "surface": 0.05}
    _, frames = same_outputs(args, work, scenario, variables,
                             ["thermo.csv", "image_00003.png", "surface/surface_00003.ply", "surface/surface.pvd"])
    print(f"WCSPH: {len(frames)} frames, the pictures, surfaces and thermo.csv identical at 1, 2 and 3 ranks")
    # Finer, so that each of 3 ranks meshes a slab from a part of the particles (the 1,500's reach
    # covers the whole tank): the joined surfaces are the same bytes.
    slabs = os.path.join(work, "slabs")
    os.makedirs(slabs, exist_ok=True)
    same_outputs(args, slabs, scenario, {"particles": 8000, "t_end": 0.2, "interval": 0.2, "restart_interval": 0,
                                         "surface": 0.1}, ["surface/surface_00002.ply"], least_frames=0,
                 rank_counts=(1, 3))
    print("the dam break of 8,000 particles: its surfaces meshed in 3 slabs identical to 1 process's")


def identical_dfsph(args, work):
    scenarios = os.path.join(HERE, "..", "..", "scenarios")
    variables = {"solver": "dfsph", "particles": 1500, "t_end": 0.15, "interval": 0.03, "restart_interval": 0,
                 "images": 0.05, "surface": 0.05}
    _, frames = same_outputs(args, work, os.path.join(scenarios, "dambreak.lua"), variables,
                             ["thermo.csv", "image_00003.png", "surface/surface_00003.vtp"])
    spheric = os.path.join(work, "spheric")
    os.makedirs(spheric, exist_ok=True)
    same_outputs(args, spheric, os.path.join(scenarios, "spheric_dambreak.lua"),
                 {"solver": "dfsph", "spacing": 0.05, "t_end": 0.6}, ["probes.csv", "thermo.csv"], least_frames=0)
    print(f"DFSPH: the dam break's {len(frames)} frames, pictures, surfaces and thermo.csv, and SPHERIC's pressure probes, "
          "gauges and obstacle load, identical at 1, 2 and 3 ranks")


def identical_solid(args, work):
    scenario = os.path.join(HERE, "..", "..", "scenarios", "spheric_dambreak.lua")
    variables = {"spacing": 0.05, "t_end": 0.6}
    same_outputs(args, work, scenario, variables, ["probes.csv", "thermo.csv"], least_frames=0)
    print("SPHERIC (a box obstacle, its load, pressure probes and gauges): probes.csv and thermo.csv identical at "
          "1, 2 and 3 ranks")


def identical_floating(args, work):
    scenario = os.path.join(HERE, "..", "..", "scenarios", "floating.lua")
    variables = {"particles": 4000, "t_end": 0.6, "images": 0.3, "joints": "true"}
    same_outputs(args, work, scenario, variables, ["thermo.csv", "image_00002.png"], least_frames=0)
    print("floating bodies (four, falling into the tank and meeting the floor, and two on joints): their poses in "
          "thermo.csv and the pictures identical at 1, 2 and 3 ranks")


def sources(args, work):
    """Each rank creates its share of every source, and the run is one process's."""
    path = os.path.join(work, "block.csv")
    with open(path, "w") as f:  # a block of water, x < 0.2, with a velocity along x
        f.write("x,y,z,vx,vy,vz\n")
        for k in range(10):
            for j in range(15):
                for i in range(10):
                    f.write(f"{0.01 + 0.02 * i:.6g},{0.01 + 0.02 * j:.6g},{0.01 + 0.02 * k:.6g},0.5,0,0\n")
    # A block of water as a dump/vtk frame (appended raw arrays), written by one process.
    maker = os.path.join(work, "make_vtu.lua")
    with open(maker, "w") as f:
        f.write('pbf.domain{lo = {0, 0, 0}, hi = {0.8, 0.3, 0.5}}\npbf.kernel_radius(0.04)\npbf.timestep(0.002)\n'
                'pbf.lattice{lo = {0.62, 0, 0}, hi = {0.78, 0.3, 0.1}, spacing = 0.02, velocity = {-0.3, 0, 0}}\n'
                'pbf.fix("vtk", "dump/vtk", {path = "block/block_*.vtu", every = 1, fields = {"velocity"}})\n'
                'pbf.run(0)\n')
    made = run(args, 1, maker, {}, work)
    if made.returncode != 0:
        fail(f"writing the .vtu block: {made.stderr}")
    files = {"file": path, "vtu": os.path.join(work, "block", "block_00000.vtu")}
    script = os.path.join(HERE, "sources.lua")
    same_outputs(args, work, script, files, ["thermo.csv"], least_frames=4)
    for ranks in (2, 3):
        result = run(args, ranks, script, dict(files, out=os.path.join(work, f"shares{ranks}")), work)
        counts = [line.split("created: ")[1].split(" of ") for line in result.stdout.splitlines() if "created: " in line]
        shares = [int(c[0]) for c in counts]
        total = int(counts[0][1]) if counts else 0
        # Each rank holds its share of each source, not the whole set: a block of 1/ranks of the
        # candidates (of the sphere's, the sites of its bounding box, which hold unequal parts of it).
        if len(shares) != ranks or sum(shares) != total or max(shares) > 1.5 * total / ranks:
            fail(f"{ranks} ranks: each should create about {total}/{ranks} particles; they created {shares}")
        print(f"{ranks} ranks created {shares} of {total} particles")
    print("particle files (.csv, .vtu), lattices (coincident sites, a sphere), solids before and after the first "
          "run, a lattice between runs: frames and thermo.csv identical at 1, 2 and 3 ranks")


def scene_file(args, work):
    """A scene file in the original study's format, each rank reading its share of the lines."""
    path = os.path.join(work, "dambreak.scene")
    subprocess.run([sys.executable, os.path.join(HERE, "..", "..", "share", "make_scene.py"), "--kind", "dambreak",
                    "--particles", "1500", "--t-final", "0.2", "--interval", "0.04", path], check=True)
    scenario = os.path.join(HERE, "..", "..", "scenarios", "init_file.lua")
    _, frames = same_outputs(args, work, scenario, {"init": path}, [], least_frames=5)
    print(f"a scene file (scenarios/init_file.lua): {len(frames)} frames identical at 1, 2 and 3 ranks")


def restart(args, work):
    """A restart written on 3 ranks continues on 2, and on 1 process, as the run never stopped."""
    script = os.path.join(HERE, "dambreak.lua")
    saved = os.path.join(work, "at120.restart")
    saved_by_one = os.path.join(work, "at120_one.restart")  # in one process's memory order
    runs = [(1, {"out": os.path.join(work, "straight")}),
            (3, {"out": os.path.join(work, "first"), "steps": 120, "save": saved}),
            (2, {"out": os.path.join(work, "on2"), "read": saved}),
            (1, {"out": os.path.join(work, "on1"), "read": saved}),
            (1, {"out": os.path.join(work, "first_one"), "steps": 120, "save": saved_by_one}),
            (3, {"out": os.path.join(work, "on3_from_one"), "read": saved_by_one})]
    for ranks, variables in runs:
        result = run(args, ranks, script, variables, work)
        if result.returncode != 0:
            fail(f"{ranks} rank(s) with {variables}: exit {result.returncode}\n{result.stdout}\n{result.stderr}")
    later = [f"f_{k:05d}.txt" for k in (3, 4, 5)]  # steps 150, 200, 250
    for name in later:
        for where in ("on2", "on1", "on3_from_one"):
            a, b = os.path.join(work, "straight", name), os.path.join(work, where, name)
            if not os.path.exists(b) or not filecmp.cmp(a, b, shallow=False):
                fail(f"{name} of the run continued {where} differs from the run that never stopped")
    # A damaged payload: every rank checks its block of it, and the combined checksum says so once.
    with open(saved, "r+b") as f:
        f.seek(os.path.getsize(saved) // 2)
        byte = f.read(1)
        f.seek(-1, os.SEEK_CUR)
        f.write(bytes([byte[0] ^ 0xFF]))
    expect_failure(run(args, 3, script, {"out": os.path.join(work, "damaged"), "read": saved}, work),
                   "checksum mismatch", "a damaged restart on 3 ranks")
    print(f"written on 3 ranks at step 120, continued on 2 and on 1, and written by one process, continued on 3: "
          f"{', '.join(later)} identical to the straight run")


def restart_wcsph(args, work):
    """WCSPH's state across a restart and a change of rank count: the leapfrog's accelerations,
    the continuity density and the cfl fix's step, written on 3 ranks, continued on 2 and on 1."""
    scenario = os.path.join(HERE, "..", "..", "scenarios", "dambreak.lua")
    common = {"solver": "wcsph", "particles": 1500, "t_end": 0.15, "interval": 0.03, "density": "continuity",
              "restart_every": 300}
    runs = [(1, "straight", {}), (3, "first", {})]
    for ranks, out, extra in runs:
        result = run(args, ranks, scenario, dict(common, out=os.path.join(work, out), **extra), work)
        if result.returncode != 0:
            fail(f"{out} on {ranks} rank(s): exit {result.returncode}\n{result.stdout}\n{result.stderr}")
    saved = os.path.join(work, "first", "restart.600.restart")
    if not os.path.exists(saved):
        fail(f"the run on 3 ranks wrote no restart of step 600: {sorted(os.listdir(os.path.join(work, 'first')))}")
    compared = []
    for ranks, out in ((2, "on2"), (1, "on1")):
        result = run(args, ranks, scenario, dict(common, out=os.path.join(work, out), restart=saved), work)
        if result.returncode != 0:
            fail(f"{out}: exit {result.returncode}\n{result.stdout}\n{result.stderr}")
        frames = sorted(f for f in os.listdir(os.path.join(work, out)) if f.startswith("frame_"))
        if len(frames) < 2:
            fail(f"the run continued {out} wrote {frames}: expected the frames after step 600")
        for name in frames:
            a, b = os.path.join(work, "straight", name), os.path.join(work, out, name)
            if not filecmp.cmp(a, b, shallow=False):
                fail(f"{name} of the WCSPH run continued {out} differs from the run that never stopped")
        compared = frames
    print(f"WCSPH (continuity density, cfl): written on 3 ranks at step 600, continued on 2 and on 1: "
          f"{', '.join(compared)} identical to the straight run")


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


def per_particle(args, work):
    path = small_scene(work, "values.lua", """pbf.fix("gravity", "gravity", {acceleration = {0, 0, -9.81}})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.compute("rho", "density")
pbf.run(30)
local rho = pbf.value("rho")
print(#rho, string.format("%.17g %.17g %.17g", rho[1], rho[500], rho[#rho]))
""")
    lines = {}
    for ranks in (1, 2, 3):
        result = run(args, ranks, path, {}, work)
        if result.returncode != 0:
            fail(f"{ranks} rank(s): exit {result.returncode}\n{result.stdout}\n{result.stderr}")
        lines[ranks] = [line for line in result.stdout.splitlines() if line and line[0].isdigit()]
    if len(lines[1]) != 1 or lines[2] != lines[1] or lines[3] != lines[1]:
        fail(f"pbf.value of a per-particle compute differs, or printed more than once: {lines}")
    print(f"pbf.value('rho') printed once, the same at 1, 2 and 3 ranks: {lines[1][0]}")

def signals(args, work):
    """mpirun forwards SIGUSR1 and SIGTERM to every rank: SIGUSR1 gives a restart and the run
    goes on; SIGTERM a restart and a clean stop. Both restarts continue as the run never stopped."""
    # From step 5 on, each step takes 60 ms more: mpirun takes up to a second to forward a
    # signal, which then comes before step 60, the run's end. (Not much more: mpirun kills the
    # ranks 1 s after it forwards SIGTERM.)
    path = os.path.join(work, "signals.lua")
    with open(path, "w") as f:
        f.write("""if var.restart then pbf.read_restart(var.restart) else
  pbf.domain{lo = {0, 0, 0}, hi = {1, 1, 1}}
  pbf.kernel_radius(0.1)
  pbf.timestep(0.001)
  pbf.lattice{lo = {0, 0, 0}, hi = {0.5, 0.5, 0.5}, spacing = 0.05}
end
pbf.fix("gravity", "gravity", {acceleration = {0, 0, -9.81}})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("frames", "dump/text", {path = var.out .. "/f_*.txt", every = 60})
pbf.every("slow", 1, function(step)
  if step < 5 or var.restart then return end
  if step == 5 then io.open(var.dir .. "/running", "w"):close() end
  local start = os.clock()
  while os.clock() - start < 0.06 do end
end)
pbf.run(60 - pbf.step())
""")

    def signalled(name, which, ranks):
        where = os.path.join(work, name)
        os.makedirs(where)
        command = [args.mpirun, "-q", "--oversubscribe", "--bind-to", "none", "-np", str(ranks), args.binary, "run",
                   path, "--log", "none", "-v", f"dir={where}", "-v", f"out={where}"]
        launched = subprocess.Popen(command, cwd=where, env=environment(), stdout=subprocess.PIPE,
                                    stderr=subprocess.PIPE, text=True)
        for _ in range(2400):
            if os.path.exists(os.path.join(where, "running")) or launched.poll() is not None:
                break
            time.sleep(0.05)
        launched.send_signal(which)
        out, err = launched.communicate(timeout=TIMEOUT)
        return where, launched.returncode, out + err

    def continued(name, restart, ranks):  # the frame of step 60
        out = os.path.join(work, name)
        result = run(args, ranks, path, {"dir": work, "restart": restart, "out": out}, work)
        if result.returncode != 0:
            fail(f"{name}: exit {result.returncode}\n{result.stdout}\n{result.stderr}")
        return os.path.join(out, "f_00001.txt")

    where, code, log = signalled("usr1", signal.SIGUSR1, 2)
    found = re.search(r"SIGUSR1: wrote restart '([^']+)' after step (\d+)", log)
    if code != 0 or not found or log.count("SIGUSR1: wrote restart") != 1:
        fail(f"SIGUSR1 at 2 ranks: exit {code}, expected one restart and the run to go on:\n{log}")
    straight = os.path.join(where, "f_00001.txt")
    on_one = continued("usr1_on1", os.path.join(where, found.group(1)), 1)
    if not filecmp.cmp(straight, on_one, shallow=False):
        fail("the SIGUSR1 restart continued on 1 process ends with other bits than the run it was written in")

    where, code, log = signalled("term", signal.SIGTERM, 2)
    stopped = re.search(r"interrupted \(Ctrl-C\) after step (\d+) .*wrote restart '([^']+)'", log)
    if code == 0 or not stopped or os.path.exists(os.path.join(where, "f_00001.txt")):
        fail(f"SIGTERM at 2 ranks: exit {code}, expected a restart and a stop before the script's end:\n{log}")
    # The ranks end together, as one process: one message, with the command that continues, no abort.
    if log.count("interrupted (Ctrl-C)") != 1 or "MPI_ABORT" in log or \
            f"continue with: mpirun -np 2 {args.binary} run" not in log:
        fail(f"SIGTERM at 2 ranks: expected one message naming `mpirun -np 2 ... -v restart=...`, no abort:\n{log}")
    on_three = continued("term_on3", os.path.join(where, stopped.group(2)), 3)
    if not filecmp.cmp(straight, on_three, shallow=False):
        fail("the SIGTERM restart continued on 3 ranks ends with other bits than the run that never stopped")
    print(f"SIGUSR1: restart after step {found.group(2)}, the run went on; SIGTERM: restart after step "
          f"{stopped.group(1)}, exit {code}; each continued (on 1 process, on 3 ranks) to the same final state")



def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", required=True)
    parser.add_argument("--mpirun", default="mpirun")
    parser.add_argument("--case", required=True,
                        choices=["identical", "identical_flow", "identical_periodic", "identical_wcsph", "identical_dfsph", "identical_solid", "identical_floating", "sources", "scene_file", "restart", "restart_wcsph",
                                 "script_error",
                                 "rank_error", "per_particle", "signals"])
    args = parser.parse_args()
    args.binary = os.path.abspath(args.binary)
    with tempfile.TemporaryDirectory() as work:
        globals()[args.case](args, work)


if __name__ == "__main__":
    main()
