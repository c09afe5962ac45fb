"""The live view of a run on two MPI ranks (mpirun -n 2 pbfengine run small.lua --view 0): rank 0
serves, every rank sends its particles into the frame, and the viewer's pause, step, resume and
stop reach every rank in the reduction Ctrl-C uses (engine/core/run_view.hpp).

    /usr/bin/python3 -m pytest -q tests/view/test_view_mpi.py
"""
import re
import shutil
import time
from pathlib import Path

import pytest

from view_client import SMALL_DOMAIN, SMALL_PARTICLES, Engine, binary

pytestmark = [pytest.mark.skipif(not binary().exists(), reason=f"no engine binary at {binary()}"),
              pytest.mark.skipif(shutil.which("mpirun") is None, reason="no mpirun")]

LONG = {"steps": 1_000_000}


def cpu_seconds(pids):
    """The CPU time (user + system) the processes used so far."""
    total = 0.0
    for pid in pids:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
        total += (int(fields[11]) + int(fields[12])) / 100  # utime, stime in clock ticks (100 a second)
    return total


def engine_pids(run):
    """The ranks: the pbfengine processes under this run's mpirun."""
    pids = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            text = stat.read_text()
            cmdline = (stat.parent / "cmdline").read_bytes()
        except OSError:
            continue
        session = int(text.rsplit(")", 1)[1].split()[3])
        if session == run.proc.pid and cmdline.startswith(str(binary()).encode()):
            pids.append(int(stat.parent.name))
    return pids


def test_frame_pause_step_resume_on_two_ranks(tmp_path):
    with Engine(tmp_path, variables=LONG, ranks=2) as run, run.events() as ev:
        hello = ev.wait_for("hello", timeout=30)
        assert hello["particles"] == SMALL_PARTICLES
        # The frame gathers both ranks' particles.
        ev.wait_for("frame", timeout=15)
        frame = run.frame()
        event = ev.wait_for("frame", lambda d: d["seq"] == frame.seq)
        assert frame.count == event["count"] == SMALL_PARTICLES and frame.step == event["step"]
        lo, hi = SMALL_DOMAIN
        assert all(lo[k] - 1e-6 <= p[k] <= hi[k] + 1e-6 for p in frame.positions() for k in range(3))

        # Pause: the step stops on both ranks (one that went on would be a step ahead in the next
        # reduction and hang or fail the run), and they wait rather than spin.
        mark = ev.mark()
        assert run.control({"command": "pause"}).status == 200
        held = ev.wait_for("status", lambda d: d["state"] == "paused", after=mark)["step"]
        ranks = engine_pids(run)
        assert len(ranks) == 2, ranks
        cpu0 = cpu_seconds(ranks)
        mark = ev.mark()
        time.sleep(1.2)
        assert {d["step"] for d in ev.of("status", mark)} == {held}
        used = cpu_seconds(ranks) - cpu0
        assert used < 0.5, f"two held ranks used {used:.2f} s of CPU in 1.2 s"  # they wait for commands
        assert run.frame().step == held

        # One step, held again; then the run goes on.
        mark = ev.mark()
        assert run.control({"command": "step"}).status == 200
        ev.wait_for("status", lambda d: d["state"] == "paused" and d["step"] == held + 1, after=mark)
        time.sleep(0.6)
        assert {d["step"] for d in ev.of("status", mark)} <= {held, held + 1}
        mark = ev.mark()
        assert run.control({"command": "resume"}).status == 200
        ev.wait_for("status", lambda d: d["state"] == "running" and d["step"] > held + 10, after=mark, timeout=15)
        frame = run.frame()
        assert frame.count == SMALL_PARTICLES and frame.step > held
        assert run.running()


def test_stop_ends_every_rank_with_a_restart(tmp_path):
    with Engine(tmp_path, variables={"steps": 1000}, ranks=2) as run, run.events() as ev:
        ev.wait_for("hello", timeout=30)
        ev.wait_for("status", lambda d: d["step"] > 20, timeout=15)
        asked = time.monotonic()
        assert run.control({"command": "stop"}).status == 200
        assert run.wait(30) == 130, run.stderr  # mpirun's code: its ranks'
        stopped = ev.wait_for("status", lambda d: d["state"] == "stopped")
    print(f"mpirun ended {run.ended - asked:.1f} s after the stop")
    m = re.search(r"wrote restart '([^']+)'", run.stderr)
    assert m, run.stderr
    assert (tmp_path / m.group(1)).is_file()
    assert f"after step {stopped['step']} " in run.stderr
    # Every rank ended (mpirun waits for all of them).
    assert not engine_pids(run)
    # The restart continues, on two ranks again, to the end.
    cont = Engine(tmp_path, variables={"steps": 1000, "restart": m.group(1)}, view=None, ranks=2)
    assert cont.wait(60) == 0, cont.stderr
    print(f"the continuation took {cont.wall_seconds:.1f} s")
    assert (tmp_path / "out" / "final_00001.txt").is_file()
