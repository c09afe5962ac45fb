"""pbfengine.readers against files the engine writes: a small dam of a few hundred particles
run for 20 steps with every dump the readers read, then copies of those files broken in
each way a reader must refuse.

    PBF_BINARY          the engine (default: build/pbfengine in this repository)
"""
import os
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from pbfengine import readers

REPO = Path(__file__).resolve().parents[2]
BINARY = Path(os.environ.get("PBF_BINARY", REPO / "build" / "pbfengine")).absolute()

# The lattice fills [0.02, 0.10]^2 x [0.02, 0.06] at lo + (i + 1/2) s: 8 x 8 x 4 sites.
L, S, DT = 0.12, 0.01, 0.002
SITES = [0.025 + S * np.arange(8), 0.025 + S * np.arange(8), 0.025 + S * np.arange(4)]
COUNT = 8 * 8 * 4
SCENE = f"""
pbf.domain{{lo = {{0, 0, 0}}, hi = {{{L}, {L}, {L}}}}}
pbf.kernel_radius(0.02)
pbf.timestep({DT})
print("lattice", pbf.lattice{{lo = {{0.02, 0.02, 0.02}}, hi = {{0.10, 0.10, 0.06}}, spacing = {S}}})
pbf.fix("gravity", "gravity", {{}})
pbf.fix("pbf", "pbf", {{iterations = 3}})
pbf.fix("walls", "box", {{}})
pbf.fix("seed", "dump/text", {{path = "out/seed_*.txt", every = 5}})
pbf.fix("text", "dump/text", {{path = "out/text_*.txt", every = 5,
                               fields = {{"id", "position", "velocity", "density"}}}})
pbf.fix("vtk", "dump/vtk", {{path = "out/vtk/frame_*.vtu", every = 5, fields = {{"id", "velocity", "density"}}}})
pbf.compute("err", "density_error")
pbf.compute("n", "count")
pbf.compute("ke", "kinetic_energy")
pbf.thermo{{every = 4, columns = {{"step", "time", "particles", "err.max", "n"}}, csv = "out/thermo.csv"}}
pbf.run(12)
-- other columns into the same CSV: a second units line and header row
pbf.thermo{{every = 4, columns = {{"step", "time", "particles", "ke"}}, csv = "out/thermo.csv"}}
pbf.run(8)
"""
FRAME_STEPS = [0, 5, 10, 15, 20]
THERMO_STEPS = [0, 4, 8, 12, 16, 20]


def run_engine(directory, launcher=(), env=None):
    if not BINARY.is_file():
        pytest.fail(f"no engine at {BINARY}: build it, or set PBF_BINARY")
    directory.mkdir(parents=True, exist_ok=True)
    (directory / "scene.lua").write_text(SCENE)
    done = subprocess.run([*launcher, str(BINARY), "run", "scene.lua", "--log", "none", "--threads", "1"],
                          cwd=directory, env={**os.environ, **(env or {})}, capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr
    return directory / "out", done.stdout


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    return run_engine(tmp_path_factory.mktemp("run"))


@pytest.fixture(scope="module")
def out(run):
    return run[0]


def test_the_lattice_count_is_every_frames_length(run):
    out, stdout = run
    assert re.search(rf"^lattice\s+{COUNT}$", stdout, re.M), stdout
    frames = [readers.read_frame(p) for p in readers.frame_paths(out / "seed_*.txt")]
    frames += [readers.read_frame(p) for p in readers.frame_paths(out / "text_*.txt")]
    frames += [readers.read_vtu(p) for p in readers.frame_paths(out / "vtk" / "frame_*.vtu")]
    assert len(frames) == 3 * len(FRAME_STEPS)
    for frame in frames:
        assert len(frame) == COUNT
        assert all(len(values) == COUNT for _, values in frame.items())
        assert frame["position"].shape == (COUNT, 3)


def test_frames_hold_the_fields_asked_for(out):
    seed = readers.read_frame(out / "seed_00000.txt")
    assert seed.names() == ["position", "velocity"]
    text = readers.read_frame(out / "text_00000.txt")
    assert text.names() == ["id", "position", "velocity", "density"]
    assert text["id"].dtype == np.int64 and text["density"].shape == (COUNT,)
    vtu = readers.read_vtu(out / "vtk" / "frame_00000.vtu")
    assert vtu.names() == ["position", "id", "velocity", "density"]
    assert vtu["id"].dtype == np.int64 and vtu["position"].dtype in (np.float32, np.float64)
    assert np.array_equal(text["id"], np.arange(COUNT)) and np.array_equal(vtu["id"], np.arange(COUNT))
    assert vtu.time is None and vtu.step is None  # neither frame format records them


def test_the_first_frame_is_the_lattice_at_rest(out):
    frame = readers.read_frame(out / "seed_00000.txt")
    position = frame["position"]
    for axis in range(3):
        assert np.allclose(np.unique(position[:, axis]), SITES[axis], rtol=0, atol=1e-7)
    grid = np.stack(np.meshgrid(*SITES, indexing="ij"), axis=-1).reshape(-1, 3)
    assert np.allclose(np.unique(position, axis=0), np.unique(grid, axis=0), rtol=0, atol=1e-7)
    assert np.all(frame["velocity"] == 0)


def test_positions_stay_inside_the_domain_and_the_water_falls(out):
    first = readers.read_frame(out / "seed_00000.txt")["position"]
    for path in readers.frame_paths(out / "seed_*.txt"):
        position = readers.read_frame(path)["position"]
        assert np.all((position >= 0) & (position <= L)), path
    last = readers.read_frame(out / "seed_00004.txt")
    assert last["position"][:, 2].mean() < first[:, 2].mean()
    assert last["velocity"][:, 2].mean() < 0


def test_vtu_and_text_frames_of_a_step_agree_to_the_files_precision(out):
    # Text holds each value in the shortest form that reads back to it: rounded to the
    # .vtu's type, it is the same bits.
    for k in range(len(FRAME_STEPS)):
        text = readers.read_frame(out / f"text_{k:05d}.txt")
        seed = readers.read_frame(out / f"seed_{k:05d}.txt")
        vtu = readers.read_vtu(out / "vtk" / f"frame_{k:05d}.vtu")
        assert np.array_equal(text["id"], vtu["id"])
        for name in ("position", "velocity", "density"):
            assert np.array_equal(text[name].astype(vtu[name].dtype), vtu[name]), (k, name)
        for name in ("position", "velocity"):
            assert np.array_equal(seed[name], text[name])


def test_the_collection_lists_every_frame_with_its_time(out):
    frames = readers.read_pvd(out / "vtk" / "frame.pvd")
    assert [Path(p) for _, p in frames] == [Path(p) for p in readers.frame_paths(out / "vtk" / "frame_*.vtu")]
    assert np.allclose([t for t, _ in frames], np.array(FRAME_STEPS) * DT, rtol=1e-12, atol=0)
    assert readers.read_pvd(out / "vtk" / "frame.pvd", part=1) == []  # no solids


def test_frame_paths_are_in_frame_order(out, tmp_path):
    for k in (100000, 99999, 7):  # the number outgrows five digits after frame 99999
        (tmp_path / f"f_{k:05d}.txt").write_text("")
    (tmp_path / "f_00001_0.txt").write_text("")  # not a frame of the pattern
    assert [Path(p).name for p in readers.frame_paths(tmp_path / "f_*.txt")] == \
        ["f_00007.txt", "f_99999.txt", "f_100000.txt"]
    with pytest.raises(ValueError, match="one '\\*'"):
        readers.frame_paths(tmp_path / "f.txt")


def test_thermo_has_the_steps_asked_for(out):
    thermo = readers.read_thermo(out / "thermo.csv")
    assert thermo.columns == ["step", "time", "particles", "err.max", "n", "ke"]
    assert thermo["step"].dtype == np.int64 and thermo["particles"].dtype == np.int64
    assert thermo["step"].tolist() == THERMO_STEPS and len(thermo) == len(THERMO_STEPS)
    assert np.allclose(thermo["time"], thermo["step"] * DT, rtol=1e-12, atol=0)
    assert np.all(thermo["particles"] == COUNT)
    # The first run's columns, then the second's: NaN where a row's run did not have them.
    before = np.array(THERMO_STEPS) <= 12
    assert np.all(thermo["n"][before] == COUNT) and np.all(np.isnan(thermo["n"][~before]))
    assert np.all(np.isfinite(thermo["err.max"][before])) and np.all(np.isnan(thermo["err.max"][~before]))
    assert np.all(np.isnan(thermo["ke"][before])) and np.all(thermo["ke"][~before] > 0)
    assert thermo.units == {"step": "-", "time": "s", "particles": "-", "err.max": "-", "n": "-", "ke": "J"}


@pytest.mark.skipif(shutil.which("mpirun") is None, reason="no mpirun")
def test_a_distributed_frame_reads_as_one_processs(out, tmp_path):
    # As tests/mpi/run.py runs Open MPI: as root, in a container.
    env = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
           "OMPI_MCA_btl_vader_single_copy_mechanism": "none"}
    mpi, _ = run_engine(tmp_path, ["mpirun", "-q", "--oversubscribe", "--bind-to", "none", "-np", "2"], env)
    frames = readers.read_pvd(mpi / "vtk" / "frame.pvd")
    if not frames or not frames[0][1].endswith(".pvtu"):
        pytest.skip(f"{BINARY} is not built with MPI: it wrote no .pvtu")
    assert len(frames) == len(FRAME_STEPS)
    for k, (_, path) in enumerate(frames):
        distributed, whole = readers.read_vtu(path), readers.read_vtu(out / "vtk" / f"frame_{k:05d}.vtu")
        assert distributed.names() == whole.names() and len(distributed) == COUNT
        for name in whole:
            assert np.array_equal(distributed[name], whole[name]), (k, name)  # the same bits


# Malformed input: every reader refuses it, naming the file (and the line where there is one).

def broken(tmp_path, source, edit):
    """A copy of `source` in tmp_path, edited."""
    path = tmp_path / Path(source).name
    path.write_bytes(edit(Path(source).read_bytes()))
    return path


def refuses(reader, path, message):
    with pytest.raises(ValueError) as error:
        reader(path)
    assert str(path) in str(error.value)
    assert re.search(message, str(error.value)), str(error.value)


def replace_line(number, text):
    def edit(data):
        lines = data.split(b"\n")
        lines[number - 1] = text(lines[number - 1])
        return b"\n".join(lines)
    return edit


def replace_value(number, column, value, sep=b" "):
    def text(line):
        values = line.split(sep)
        values[column - 1] = value
        return sep.join(values)
    return replace_line(number, text)


@pytest.mark.parametrize("reader", [readers.read_frame, readers.read_vtu, readers.read_pvd, readers.read_thermo])
def test_a_missing_file_is_named(reader, tmp_path):
    with pytest.raises(FileNotFoundError, match=re.escape(str(tmp_path / "none"))):
        reader(tmp_path / "none")


@pytest.mark.parametrize("case, edit, message", [
    ("empty", lambda d: b"", "empty file"),
    ("count", replace_line(1, lambda l: b"many"), r":1: expected the particle count"),
    ("columns", replace_line(5, lambda l: l.rsplit(b" ", 1)[0]), r":5: 5 columns, expected 6"),
    ("number", replace_value(7, 2, b"x"), r":7: column 2: 'x' is not a number"),
    ("short", lambda d: b"\n".join(d.split(b"\n")[:-11]) + b"\n",
     r"truncated file: line 1 says 256 particles, but 246 lines"),
    ("long", lambda d: d + b"1 2 3 4 5 6\n", r": line 1 says 256 particles, but 257 lines"),
    ("cut", lambda d: d[:-3], r":257: truncated file"),
])
def test_read_frame_refuses(out, tmp_path, case, edit, message):
    refuses(readers.read_frame, broken(tmp_path, out / "seed_00001.txt", edit), message)


@pytest.mark.parametrize("case, edit, message", [
    ("header", replace_line(1, lambda l: l.replace(b" density", b"")), r":3: 8 columns, expected 7"),
    ("id", replace_line(4, lambda l: b"1.5" + l[1:]), r":4: column 1: '1.5' is not an integer"),
    ("twice", replace_line(1, lambda l: l + b" id"), r":1: a field is named twice"),
])
def test_read_frame_refuses_a_bad_header(out, tmp_path, case, edit, message):
    refuses(readers.read_frame, broken(tmp_path, out / "text_00001.txt", edit), message)


def ascii_vtu(data):
    head = data[:data.index(b"<AppendedData")].replace(b'format="appended"', b'format="ascii"')
    return head + b"</VTKFile>\n"


@pytest.mark.parametrize("case, edit, message", [
    ("cut", lambda d: d[:len(d) // 2], r"truncated file"),
    ("cut_head", lambda d: d[:300], r"no <AppendedData> element"),
    ("cut_block", lambda d: d[:-40] + d[-32:], r"truncated file"),  # 8 bytes of the last array gone
    ("count", lambda d: d.replace(b'NumberOfPoints="256"', b'NumberOfPoints="255"'),
     r"holds \d+ bytes, but NumberOfPoints = 255 needs"),
    ("points", lambda d: d.replace(b"Points>", b"Pointz>"), r"no <Points>"),
    ("piece", lambda d: d.replace(b"Piece", b"Peace"), r"0 <Piece> elements"),
    ("header_type", lambda d: d.replace(b'"UInt64"', b'"UInt32"'), r"header_type='UInt32'"),
    ("type", lambda d: d.replace(b'type="Float', b'type="Real'), r"unknown type 'Real"),
    ("ascii", ascii_vtu, r"no <AppendedData>"),
    ("format", lambda d: d.replace(b'format="appended" offset="0"', b'format="binary"'),
     r"format='binary'"),
    ("xml", lambda d: d.replace(b"<Piece", b"<Piece <"), r":4: not valid XML"),
    ("kind", lambda d: d.replace(b'type="UnstructuredGrid"', b'type="PolyData"'), r"not a VTK UnstructuredGrid"),
])
def test_read_vtu_refuses(out, tmp_path, case, edit, message):
    refuses(readers.read_vtu, broken(tmp_path, out / "vtk" / "frame_00001.vtu", edit), message)


@pytest.mark.parametrize("case, edit, message", [
    ("time", lambda d: d.replace(b'timestep="0.01"', b'timestep="soon"'), r"<DataSet> 2 needs timestep"),
    ("file", lambda d: d.replace(b' file="frame_00002.vtu"', b""), r"<DataSet> 3 needs"),
    ("cut", lambda d: d[:-30], r":\d+: not valid XML"),
    ("kind", lambda d: d.replace(b"Collection", b"Gathering"), r"not a VTK Collection"),
])
def test_read_pvd_refuses(out, tmp_path, case, edit, message):
    refuses(readers.read_pvd, broken(tmp_path, out / "vtk" / "frame.pvd", edit), message)


@pytest.mark.parametrize("case, edit, message", [
    ("empty", lambda d: b"", "empty file"),
    ("values", replace_line(4, lambda l: l + b",1"), r":4: 6 values, expected 5"),
    ("number", replace_value(5, 2, b"zero", b","), r":5: column 2: 'zero' is not a number"),
    ("cut", lambda d: d[:-3], r":\d+: truncated file"),
    ("headless", lambda d: b"\n".join(d.split(b"\n")[2:]), r":1: a row before the header"),
    ("names", replace_line(2, lambda l: l.replace(b"time", b"step")), r":2: a column is empty or named twice"),
])
def test_read_thermo_refuses(out, tmp_path, case, edit, message):
    refuses(readers.read_thermo, broken(tmp_path, out / "thermo.csv", edit), message)
