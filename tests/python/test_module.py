"""The Python module (docs/python.md): scenes from Python and from Lua give the same bits, the
arrays are the engine's memory, stale arrays refuse use, errors carry the engine's messages,
and a callback that raises stops the run with a restart that continues it exactly.

Run by ctest with PYTHONPATH=build/python and PBF_BINARY=build/pbfengine.
"""
import gc
import os
import subprocess

import numpy as np
import pytest

import pbfengine

BINARY = os.path.abspath(os.environ.get("PBF_BINARY", os.path.join(os.path.dirname(__file__), "..", "..", "build", "pbfengine")))

# A small dam break: a column 0.1 x 0.05 x 0.2 m at spacing 0.01 m (1000 particles), h = 2 s.
SCENE_LUA = """
pbf.domain{lo = {0, 0, 0}, hi = {0.3, 0.05, 0.3}}
pbf.kernel_radius(0.02)
pbf.timestep(0.002)
pbf.lattice{lo = {0, 0, 0}, hi = {0.1, 0.05, 0.2}, spacing = 0.01}
pbf.fix("gravity", "gravity", {acceleration = {0, 0, -9.81}})
pbf.fix("solver", "pbf", {iterations = 4})
pbf.fix("walls", "box", {})
pbf.fix("frames", "dump/text", {every = 10, path = "frames/frame_*.txt"})
"""


def build_scene(sim):
    """SCENE_LUA, from Python."""
    sim.domain(lo=(0, 0, 0), hi=(0.3, 0.05, 0.3))
    sim.kernel_radius(0.02)
    sim.timestep(0.002)
    count = sim.lattice(lo=(0, 0, 0), hi=(0.1, 0.05, 0.2), spacing=0.01)
    sim.fix("gravity", "gravity", acceleration=(0, 0, -9.81))
    sim.fix("solver", "pbf", iterations=4)
    sim.fix("walls", "box")
    sim.fix("frames", "dump/text", every=10, path="frames/frame_*.txt")
    return count


@pytest.fixture
def in_tmp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


def frames(folder):
    return {name: (folder / name).read_bytes() for name in sorted(os.listdir(folder))}


def test_same_frames_from_python_lua_and_the_command_line(in_tmp):
    (in_tmp / "scene.lua").write_text(SCENE_LUA + "pbf.run(40)\n")
    subprocess.run([BINARY, "run", "scene.lua", "--log", "none"], check=True, capture_output=True)
    from_command_line = frames(in_tmp / "frames")
    assert len(from_command_line) == 5
    os.rename("frames", "frames_cli")

    sim = pbfengine.Simulation(log=None)
    assert build_scene(sim) == 1000
    sim.run(40)
    assert frames(in_tmp / "frames") == from_command_line
    os.rename("frames", "frames_py")

    lua = pbfengine.Simulation(log=None)
    lua.run_file("scene.lua")
    assert frames(in_tmp / "frames") == from_command_line


def test_arrays_are_the_engines_memory(in_tmp):
    sim = pbfengine.Simulation(log=None)
    build_scene(sim)
    position = sim.field("position")
    for c, view in enumerate(position):
        assert view.__array_interface__["data"][0] == sim._address("position", c)
        assert view.dtype == np.dtype(pbfengine.real) and view.shape == (1000,)
    # The lattice: sites at (i + 1/2) s.
    assert np.allclose(np.sort(np.unique(position.x)), 0.005 + 0.01 * np.arange(10), atol=1e-6)
    # Read-only unless asked.
    with pytest.raises(ValueError, match="read-only"):
        position.z[0] = 1.0
    # Writable where asked: the engine sees the change.
    sim.field("velocity", writable=True).x[:] = 0.5
    assert np.all(sim.copy("velocity")[:, 0] == np.float32(0.5))
    mass = sim.field("mass")
    assert mass.shape == (1000,) and np.all(mass > 0)
    assert np.array_equal(np.sort(sim.ids()), np.arange(1000))


def test_stale_views_refuse_use_and_never_read_freed_memory(in_tmp):
    sim = pbfengine.Simulation(log=None)
    build_scene(sim)
    z = sim.field("position").z
    kept = z.copy()
    raw = np.asarray(z)  # the check stripped: the memory stays pinned
    sim.run(40)          # re-sorted at step 20 and 40: the arrays moved
    for use in (lambda: z[0], lambda: z.max(), lambda: z + 1, lambda: str(z), lambda: z.copy(),
                lambda: np.mean(z), lambda: list(z)):
        with pytest.raises(pbfengine.StaleViewError, match="taken at step 0"):
            use()
    assert kept.max() == pytest.approx(0.195, abs=1e-6)  # a copy is the caller's
    del z
    gc.collect()
    sim.run(40)
    assert np.isfinite(raw).all()  # pinned memory, whatever it holds now
    assert pbfengine._pbfengine._pinned_blocks() >= 1
    del raw, kept
    gc.collect()
    assert pbfengine._pbfengine._pinned_blocks() == 0  # the last view gone, the pin goes
    # Inside a callback, a view is valid until the callback returns.
    taken = []
    sim.every("take", 10, lambda step, time: taken.append((step, sim.field("position").z)))
    sim.run(20)
    assert [step for step, _ in taken] == [90, 100]
    with pytest.raises(pbfengine.StaleViewError):
        taken[0][1].max()


def test_callbacks_see_the_run_and_their_errors_stop_it_with_a_restart(in_tmp):
    reference = pbfengine.Simulation(log=None)
    build_scene(reference)
    reference.unfix("frames")
    reference.run(60)
    expected = reference.copy("position")[np.argsort(reference.ids())]

    sim = pbfengine.Simulation(log=None)
    build_scene(sim)
    sim.unfix("frames")
    heights = []
    def watch(step, time):
        heights.append(float(sim.field("position").z.max()))
        if step == 30:
            raise ValueError("enough")
    sim.every("watch", 10, watch)
    with pytest.raises(pbfengine.Interrupted, match=r"callback 'watch' raised ValueError: enough after step 30") as stop:
        sim.run(60)
    assert isinstance(stop.value.__cause__, ValueError)
    assert heights[0] < 0.2 and heights == sorted(heights, reverse=True)  # the column slumps
    # The restart continues exactly.
    again = pbfengine.Simulation(log=None)
    again.read_restart(stop.value.restart)
    again.fix("gravity", "gravity", acceleration=(0, 0, -9.81))
    again.fix("solver", "pbf", iterations=4)
    again.fix("walls", "box")
    assert again.step == 30
    again.run(30)
    assert np.array_equal(again.copy("position")[np.argsort(again.ids())], expected)


def test_errors_carry_the_engines_messages(in_tmp):
    sim = pbfengine.Simulation(log=None)
    with pytest.raises(pbfengine.Error, match=r"unknown fix style 'gravty' \(did you mean 'gravity'"):
        sim.fix("g", "gravty")
    with pytest.raises(pbfengine.Error, match=r"fix 'g' \(gravity\): unknown parameter 'acceleraton'"):
        sim.fix("g", "gravity", acceleraton=(0, 0, -9.81))
    with pytest.raises(pbfengine.Error, match=r"'iterations'.*integer|integer.*'iterations'"):
        sim.fix("s", "pbf", iterations="four")
    with pytest.raises(pbfengine.Error, match=r"lattice: .*spacing"):
        sim.lattice(lo=(0, 0, 0), hi=(1, 1, 1))
    with pytest.raises(pbfengine.Error, match=r"parameter 'lo' must be three numbers|'lo'"):
        sim.domain(lo="origin", hi=(1, 1, 1))
    with pytest.raises(TypeError):
        sim.run("ten")
    build_scene(sim)
    with pytest.raises(pbfengine.Error, match=r"no particle field 'densty'"):
        sim.field("densty")
    with pytest.raises(pbfengine.Error, match=r"no compute with id 'nope'"):
        sim.value("nope")
    (in_tmp / "bad.lua").write_text("pbf.timestep(0.001)\npbf.fix('x', 'nosuch', {})\n")
    with pytest.raises(pbfengine.Error, match=r"bad.lua:2: unknown fix style 'nosuch'"):
        sim.run_file("bad.lua")
    with pytest.raises(pbfengine.Error, match=r"lua:1:"):
        sim.lua("pbf.run('x')")
    def meddle(step, time):
        sim.fix("late", "gravity")
    sim.every("meddle", 5, meddle)
    with pytest.raises(pbfengine.Interrupted, match=r"fix cannot be called during a run"):
        sim.run(10)


def test_values_functions_and_lua_statements(in_tmp):
    sim = pbfengine.Simulation(log=None)
    sim.domain(lo=(0, 0, 0), hi=(0.3, 0.05, 0.3))
    sim.kernel_radius(0.02)
    sim.timestep(0.002)
    # A velocity given as a function of place.
    sim.lattice(lo=(0, 0, 0), hi=(0.1, 0.05, 0.1), spacing=0.01, velocity=lambda x, y, z: (z, 0, 0))
    vx, z = sim.field("velocity").x, sim.field("position").z
    assert np.allclose(vx, z)
    sim.compute("ke", "kinetic_energy")
    m = float(sim.field("mass")[0])
    assert sim.value("ke") == pytest.approx(0.5 * m * float(np.sum(np.asarray(z, dtype=float) ** 2)), rel=1e-5)
    sim.lua("pbf.fix('gravity', 'gravity', {}); pbf.fix('solver', 'pbf', {}); pbf.fix('walls', 'box', {})")
    sim.lua("pbf.run(5)")
    assert sim.step == 5 and sim.time == pytest.approx(0.01)
    assert [name for name, _, _ in sim.fields()][:3] == ["position", "velocity", "mass"]
