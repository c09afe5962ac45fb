#!/usr/bin/env python3
"""What the Python module costs (docs/performance/python.md).

1. Views: taking the position arrays (three zero-copy views) of a million particles, median
   of 1,000 takes, against copying them; and a check that the views' memory is the engine's.
2. Callbacks: the dam break of compare_step.sh (33,750 particles from `share/make_scene.py
   --kind dambreak`, 75 steps through scenarios/init_file.lua) run from Python with and
   without a Python callback every step that reads the positions through views (the front:
   the largest x); the runs alternate, `--repeats` each, and the loop times' medians give
   the ratio; the timing table's row of the callback gives its own share of the loop, which
   the noise of whole runs (a few % here) hides.

    PYTHONPATH=build/python python3 share/benchmarks/python_module.py [--repeats 5]
"""
import argparse
import os
import statistics
import subprocess
import tempfile
import time

import numpy as np

import pbfengine

HERE = os.path.dirname(os.path.abspath(__file__))
INIT_FILE = os.path.join(HERE, "..", "..", "scenarios", "init_file.lua")
MAKE_SCENE = os.path.join(HERE, "..", "make_scene.py")


def views(particles):
    sim = pbfengine.Simulation(log=None, log_level="warn")
    side = round(particles ** (1 / 3))
    sim.domain(lo=(0, 0, 0), hi=(1, 1, 1))
    sim.kernel_radius(2.0 / side)
    sim.lattice(lo=(0, 0, 0), hi=(1, 1, 1), spacing=1.0 / side)
    takes, copies = [], []
    for _ in range(1000):
        t0 = time.perf_counter()
        position = sim.field("position")
        takes.append(time.perf_counter() - t0)
    assert all(v.__array_interface__["data"][0] == sim._address("position", c) for c, v in enumerate(position))
    for _ in range(20):
        t0 = time.perf_counter()
        sim.copy("position")
        copies.append(time.perf_counter() - t0)
    return sim.count, statistics.median(takes), statistics.median(copies)


def dambreak_loop_seconds(scene, with_callback, threads):
    sim = pbfengine.Simulation(log=None, log_level="warn", threads=threads)
    fronts = []
    if with_callback:
        sim.every("front", 1, lambda step, time: fronts.append(float(sim.field("position").x.max())))
    with tempfile.TemporaryDirectory() as out:
        sim.run_file(INIT_FILE, init=scene, out=out)
    timing = sim.timing()
    in_callback = sum(r["seconds"] for r in timing["rows"] if r["label"] == "front (python)")
    if with_callback:
        assert len(fronts) == sim.step
    return timing["wall"], sim.count, sim.step, in_callback


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--dambreak-particles", type=int, default=33750)
    parser.add_argument("--threads", type=int, default=None)
    parser.add_argument("--particles", type=int, default=1_000_000)
    args = parser.parse_args()
    cpu = next((l.split(":")[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
    print(f"# {time.strftime('%Y-%m-%d')} {os.cpu_count()} cores, {cpu}, pbfengine {pbfengine.version} "
          f"({pbfengine.real})")
    count, take, copy = views(args.particles)
    print(f"views: {count} particles: taking the 3 position views {take * 1e6:.1f} us (median of 1000), "
          f"copying them {copy * 1e3:.2f} ms (median of 20)")
    plain, called, inside = [], [], []
    with tempfile.TemporaryDirectory() as folder:
        scene = os.path.join(folder, "scene.txt")  # 75 steps of 2 ms, as compare_step.sh
        subprocess.run(["python3", MAKE_SCENE, "--kind", "dambreak", "--particles", str(args.dambreak_particles),
                        "--dt", "0.002", "--interval", "0.15", "--t-final", "0.15", "-o", scene],
                       check=True, capture_output=True)
        for _ in range(args.repeats):
            seconds, count, steps, _ = dambreak_loop_seconds(scene, False, args.threads)
            plain.append(seconds)
            seconds, _, _, in_callback = dambreak_loop_seconds(scene, True, args.threads)
            called.append(seconds)
            inside.append(in_callback / seconds)
    a, b = statistics.median(plain), statistics.median(called)
    print(f"callbacks: dam break, {count} particles, {steps} steps: without {' '.join(f'{s:.3f}' for s in plain)} s, "
          f"with a callback every step {' '.join(f'{s:.3f}' for s in called)} s; medians {a:.3f} and {b:.3f} s: "
          f"ratio {b / a:.4f} ({(b / a - 1) * 100:+.2f}%); the timing table's callback row: "
          f"{statistics.median(inside) * 100:.3f}% of the loop (median)")


if __name__ == "__main__":
    main()
