"""The live view's protocol against the real engine (pbfengine run small.lua --view 0): what the
server sends, what its commands do to the run, who it refuses, and that it never changes the
physics nor holds the run up. The protocol: docs/view.md (engine/view/view_server.cpp).

    /usr/bin/python3 -m pytest -q tests/view        (PBF_BINARY=... for another binary)

Each test starts its own small run (500 particles, a few hundred steps a second on one core;
starting one costs a fraction of a second), so the tests share no state.
"""
import http.client
import json
import math
import os
import re
import shutil
import socket
import statistics
import subprocess
import time
from pathlib import Path

import pytest

from view_client import (SMALL_DOMAIN, SMALL_PARTICLES, Engine, EventStream, ViewClient, binary, png_size,
                         raw_request, status_of, write_scene)

pytestmark = pytest.mark.skipif(not binary().exists(), reason=f"no engine binary at {binary()}")

LONG = {"steps": 1_000_000}  # a run that outlives its test (killed at the end)


def steps_advance(ev, by=5, timeout=10):
    """Waits until status events show the run `by` steps further than now; returns the step."""
    start = ev.latest_step(timeout)
    return ev.wait_for("status", lambda d: d["step"] >= start + by, timeout=timeout, after=ev.mark())["step"]


def paused_at(run, ev, timeout=10):
    """Posts pause and returns the step the run holds at (the first 'paused' status after it)."""
    mark = ev.mark()
    assert run.control({"command": "pause"}).status == 200
    return ev.wait_for("status", lambda d: d["state"] == "paused", timeout=timeout, after=mark)["step"]


def held_steps(ev, seconds):
    """The steps of the status events over the next `seconds` (a held run still sends them)."""
    mark = ev.mark()
    time.sleep(seconds)
    return {d["step"] for d in ev.of("status", mark)}, {d["state"] for d in ev.of("status", mark)}


def stdout_thermo_steps(run, columns):
    """The steps of the thermo rows the run printed (rows of numbers as wide as the columns)."""
    steps = []
    for line in run.stdout_lines:
        words = line.split()
        if len(words) == columns:
            try:
                values = [float(w) for w in words]
            except ValueError:
                continue
            steps.append(int(values[0]))
    return steps


# --- what a viewer gets ---------------------------------------------------------------------------

def test_hello_frame_thermo_log(tmp_path):
    with Engine(tmp_path, variables=LONG) as run, run.events() as ev:
        hello = ev.wait_for("hello")
        assert hello["particles"] == SMALL_PARTICLES
        assert hello["title"] == "small.lua"
        assert hello["state"] == "running"
        assert hello["plan"]["first_step"] == 0 and hello["plan"]["last_step"] == LONG["steps"]
        assert hello["color"] in hello["fields"] and "density" in hello["fields"]
        assert re.fullmatch(r"[0-9a-f]+", hello["run_id"])
        lo, hi = hello["domain"]["lo"], hello["domain"]["hi"]
        assert (tuple(lo), tuple(hi)) == SMALL_DOMAIN
        names = [c["name"] for c in hello["columns"]]
        assert names == ["step", "time", "ke", "err.avg"]
        assert hello["spacing"] == pytest.approx(0.01, rel=1e-6)

        # A frame and its event: the same count, step and time (the event with the frame's seq).
        ev.wait_for("frame")
        frame = run.frame()
        event = ev.wait_for("frame", lambda d: d["seq"] == frame.seq, timeout=5)
        assert frame.count == event["count"] == SMALL_PARTICLES
        assert frame.step == event["step"] and frame.time == pytest.approx(event["time"], rel=1e-12)
        assert frame.reserved == 0
        assert event["color"] == hello["color"]
        eps = 1e-6  # float32 positions of a domain 0.3 m wide
        for x, y, z in frame.positions():
            assert lo[0] - eps <= x <= hi[0] + eps and lo[1] - eps <= y <= hi[1] + eps and lo[2] - eps <= z <= hi[2] + eps
        assert all(math.isfinite(v) for v in frame.values)
        assert min(frame.values) >= event["min"] - 1e-6 and max(frame.values) <= event["max"] + 1e-6

        # Thermo: rows as wide as hello's columns, steps growing; the same rows the run printed,
        # from its first (step 0) on.
        ev.wait_for("thermo", lambda d: d["step"] >= 100, timeout=10)
        rows = ev.of("thermo")
        assert all(len(r["values"]) == len(names) for r in rows)
        steps = [r["step"] for r in rows]
        assert steps == sorted(set(steps)) and len(steps) >= 5
        assert all(r["values"][0] == r["step"] for r in rows)  # the step column
        printed = stdout_thermo_steps(run, len(names))
        n = min(len(steps), len(printed))  # (stdout comes through a pipe: it may lag, or lead)
        assert n >= 5 and steps[:n] == printed[:n], f"view's thermo steps {steps[:5]}... printed {printed[:5]}..."

        # The log: the lines written, among them thermo's header.
        lines = [line for d in ev.of("log") for line in d["lines"]]
        assert any(all(n in line for n in names) for line in lines) or any("view: watch" in l for l in lines), lines[:10]

        status = ev.wait_for("status")
        assert status["particles"] == SMALL_PARTICLES and status["state"] == "running"


def test_solids_sent_with_their_version(tmp_path):
    with Engine(tmp_path, variables=dict(LONG, obstacle=1)) as run, run.events() as ev:
        ev.wait_for("frame")
        frame = run.frame()
        event = ev.wait_for("frame", lambda d: d["seq"] == frame.seq)
        solids = run.view().solids()
        assert solids["version"] == event["solids_version"]
        (ball,) = solids["solids"]
        assert ball["name"] == "ball" and ball["container"] is False
        v, t = ball["vertices"], ball["triangles"]
        assert len(v) % 3 == 0 and len(t) % 3 == 0 and len(t) > 0
        assert all(0 <= i < len(v) // 3 for i in t)
        for k in range(0, len(v), 3):  # on the sphere (centre, radius 0.02), within the mesh's facets
            r = math.dist(v[k:k + 3], (0.22, 0.025, 0.02))
            assert 0.018 <= r <= 0.0201


def test_second_viewer_at_the_same_time(tmp_path):
    with Engine(tmp_path, variables=LONG) as run, run.events() as a, run.events() as b:
        ha, hb = a.wait_for("hello"), b.wait_for("hello")
        assert ha["run_id"] == hb["run_id"] and hb["particles"] == SMALL_PARTICLES
        # Both see the frames published from now on (neither fetches them: one a second).
        ma, mb = a.mark(), b.mark()
        fa = a.wait_for("frame", after=ma, timeout=5)
        fb = b.wait_for("frame", lambda d: d["seq"] >= fa["seq"], after=mb, timeout=5)
        assert fb["count"] == SMALL_PARTICLES
        assert run.frame().count == SMALL_PARTICLES


# --- commands -------------------------------------------------------------------------------------

def test_pause_step_resume(tmp_path):
    with Engine(tmp_path, variables=LONG) as run, run.events() as ev:
        ev.wait_for("hello")
        steps_advance(ev)
        held = paused_at(run, ev)
        steps, states = held_steps(ev, 1.2)  # a held run still reports, twice a second
        assert steps == {held} and states == {"paused"}
        assert run.frame().step == held

        # step: exactly one more, and held again there.
        mark = ev.mark()
        assert run.control({"command": "step"}).status == 200
        ev.wait_for("status", lambda d: d["state"] == "paused" and d["step"] != held, after=mark)
        steps, states = held_steps(ev, 1.0)
        assert steps == {held + 1} and states == {"paused"}
        assert {d["step"] for d in ev.of("status", mark)} <= {held, held + 1}

        # resume: the steps go on.
        mark = ev.mark()
        assert run.control({"command": "resume"}).status == 200
        ev.wait_for("status", lambda d: d["state"] == "running" and d["step"] > held + 10, after=mark)
        assert run.running()


def test_stop_writes_a_restart_that_continues(tmp_path):
    with Engine(tmp_path, variables={"steps": 2000}) as run, run.events() as ev:
        ev.wait_for("hello")
        steps_advance(ev)
        mark = ev.mark()
        assert run.control({"command": "stop"}).status == 200
        assert run.wait(30) == 130
        ended = ev.wait_for("status", lambda d: d["state"] == "stopped", after=mark, timeout=5)
    m = re.search(r"wrote restart '([^']+)'", run.stderr)
    assert m, run.stderr
    assert "stopped from the live view" in run.stderr
    restart = tmp_path / m.group(1)
    assert restart.is_file()
    assert f"after step {ended['step']} " in run.stderr
    assert m.group(1) in ended.get("message", "")
    # Continued (without the view): to the end.
    cont = Engine(tmp_path, variables={"steps": 2000, "restart": m.group(1)}, view=None)
    assert cont.wait(60) == 0, cont.stderr
    assert f"continuing from {m.group(1)}" in cont.stdout + cont.stderr
    assert (tmp_path / "out" / "final_00001.txt").is_file()


def final_frame(directory):
    return (Path(directory) / "out" / "final_00001.txt").read_bytes()


@pytest.mark.parametrize("extra", ["pauses", "colour_frames_picture"])
def test_view_does_not_change_the_physics(tmp_path, extra):
    """A run watched, held, stepped, resumed and stopped from the view, then continued from its
    restart without the view, ends byte for byte as the same run without the view."""
    steps = 600
    plain = Engine(tmp_path / "plain", variables={"steps": steps}, view=None)
    assert plain.wait(60) == 0, plain.stderr
    viewed_dir = tmp_path / "viewed"
    with Engine(viewed_dir, variables={"steps": steps}) as run, run.events() as ev:
        ev.wait_for("hello")
        paused_at(run, ev)
        if extra == "colour_frames_picture":  # a derived field (neighbours), frames taken, a picture
            assert run.control({"command": "color", "field": "density"}).status == 200
            ev.wait_for("frame", lambda d: d["color"] == "density")
        for cycle in range(3):
            for _ in range(2):
                mark = ev.mark()
                assert run.control({"command": "step"}).status == 200
                ev.wait_for("status", lambda d: d["state"] == "paused", after=mark)
            if extra == "colour_frames_picture" and cycle == 1:  # (while held: the run cannot end meanwhile)
                mark = ev.mark()
                assert run.control({"command": "picture", "camera": {"position": [0.15, -0.4, 0.1],
                                    "target": [0.15, 0.025, 0.1], "up": [0, 0, 1], "fov": 40},
                                    "width": 64, "height": 48}).status == 200
                assert "path" in ev.wait_for("picture", after=mark, timeout=20)
            assert run.control({"command": "resume"}).status == 200
            end = time.monotonic() + 0.1  # some 50 steps
            while time.monotonic() < end:
                if extra == "colour_frames_picture":
                    run.frame()
                time.sleep(0.01)
            paused_at(run, ev)
        held = ev.latest_step()
        assert held < steps - 10, f"the run got to step {held} of {steps} before the stop: too fast for this test"
        assert run.control({"command": "stop"}).status == 200
        assert run.wait(30) == 130, run.stderr
    restart = re.search(r"wrote restart '([^']+)'", run.stderr).group(1)
    cont = Engine(viewed_dir, variables={"steps": steps, "restart": restart}, view=None)
    assert cont.wait(60) == 0, cont.stderr
    assert final_frame(viewed_dir) == final_frame(tmp_path / "plain")


def test_colour_by_density(tmp_path):
    with Engine(tmp_path, variables=LONG) as run, run.events() as ev:
        hello = ev.wait_for("hello")
        mark = ev.mark()
        assert run.control({"command": "color", "field": "density"}).json() == {"ok": True}
        event = ev.wait_for("frame", lambda d: d["color"] == "density", after=mark)
        assert event["unit"] == "kg/m^3"
        # Every frame after the first in density is in density (no other colour asked for).
        frame = run.frame()
        assert ev.wait_for("frame", lambda d: d["seq"] == frame.seq)["color"] == "density"
        # Near the rest density, 1000 kg/m^3 (the engine's default): the bulk within 10%; a
        # particle at the free surface misses part of its neighbourhood and sums less.
        values = list(frame.values)
        assert statistics.median(values) == pytest.approx(1000, rel=0.10)
        near = sum(1 for v in values if abs(v - 1000) <= 100)
        assert near >= 0.75 * len(values), sorted(values)[::50]
        ev.wait_for("frame", after=ev.mark(), timeout=5)
        assert all(d["color"] == "density" for d in ev.of("frame", mark) if d["seq"] > event["seq"])

        r = run.control({"command": "color", "field": "temperature"})
        assert r.status == 400
        error = r.json()["error"]
        assert "temperature" in error and all(f in error for f in hello["fields"]), error


def test_picture_from_a_camera(tmp_path):
    with Engine(tmp_path, variables=LONG) as run, run.events() as ev:
        hello = ev.wait_for("hello")
        lo, hi = hello["domain"]["lo"], hello["domain"]["hi"]
        centre = [(a + b) / 2 for a, b in zip(lo, hi)]
        mark = ev.mark()
        r = run.control({"command": "picture", "width": 320, "height": 200,
                         "camera": {"position": [centre[0], centre[1] - 0.6, centre[2] + 0.1], "target": centre,
                                    "up": [0, 0, 1], "fov": 45}})
        assert r.status == 200, r
        picture = ev.wait_for("picture", after=mark, timeout=30)
        assert "error" not in picture, picture
        path = tmp_path / picture["path"]
        assert path.is_file()
        assert png_size(path) == (320, 200)

        # A camera at its target has no direction: an error event, and the run goes on.
        mark = ev.mark()
        r = run.control({"command": "picture", "width": 64, "height": 64,
                         "camera": {"position": centre, "target": centre, "up": [0, 0, 1], "fov": 45}})
        assert r.status == 200
        failed = ev.wait_for("picture", after=mark, timeout=30)
        assert failed.get("error"), failed
        steps_advance(ev)
        assert run.running()

        # A request the server can check itself is refused at once.
        for bad in ({"width": 320, "height": 200},
                    {"width": 8, "height": 200, "camera": {"position": [0, 0, 1], "target": centre, "up": [0, 0, 1], "fov": 45}},
                    {"width": 320, "height": 200, "camera": {"position": [0, 0, 1], "target": centre, "up": [0, 0, 1], "fov": 0}}):
            r = run.control(dict(bad, command="picture"))
            assert r.status == 400 and "picture" in r.json()["error"], r


# --- who may talk to it ---------------------------------------------------------------------------

DATA = ["/events", "/frame", "/solids", "/", "/index.html"]
PUBLIC = ["/view.js", "/view.css", "/three.min.js", "/OrbitControls.js"]


def test_token_host_and_origin(tmp_path):
    with Engine(tmp_path, variables=LONG) as run, run.events() as ev:
        ev.wait_for("hello")
        ev.wait_for("frame")
        view, port = run.view(), run.port
        wrong = "0" * len(run.token) if run.token != "0" * len(run.token) else "1" * len(run.token)
        for token in (None, wrong, run.token[:-1], run.token + "0", ""):
            for path in DATA:
                r = view.get(path, token=token)
                assert r.status == 403, (path, token, r)
                assert run.token.encode() not in r.body
            r = view.control({"command": "pause"}, token=token)
            assert r.status == 403, (token, r)
        # The right token under another Host (DNS rebinding): refused, also the public files.
        evil = ViewClient(port, run.token, host=f"evil.example:{port}")
        for path in DATA + PUBLIC:
            assert evil.get(path).status == 403, path
        assert evil.control({"command": "pause"}).status == 403
        for host in ("127.0.0.1", "localhost", "127.0.0.1:", f"127.0.0.1.evil.example:{port}",
                     f"127.0.0.1:{port}.evil.example", f"127.0.0.1:{port}@evil.example", f"localhost.:{port}",
                     f"[::1]x:{port}", ""):
            assert ViewClient(port, run.token, host=host).get("/frame").status == 403, host
        # The names the server answers to: the loopback's, with this port or another (an ssh
        # tunnel's local end may be another port of the laptop: docs/view.md).
        for host in (f"127.0.0.1:{port}", f"localhost:{port}", f"[::1]:{port}", "127.0.0.1:8080", "localhost:1"):
            assert ViewClient(port, run.token, host=host).get("/solids").status == 200, host
        # The public files need no token.
        for path in PUBLIC:
            r = view.get(path, token=None)
            assert r.status == 200 and len(r.body) > 100, path
        # Another page's Origin: refused, and the command does nothing.
        for origin in ("http://evil.example", f"http://localhost.evil.example:{port}", "null",
                       f"https://127.0.0.1:{port}", f"http://127.0.0.1:{port + 1}", f"http://localhost:{port}"):
            r = view.control({"command": "pause"}, headers={"Origin": origin})
            assert r.status == 403, (origin, r)
        # Neither does a command as text/plain (what another page may post without asking).
        r = view.control(json.dumps({"command": "pause"}), content_type="text/plain")
        assert r.status == 415, r
        r = view.control(json.dumps({"command": "pause"}), content_type=None)
        assert r.status == 415, r
        time.sleep(0.3)
        steps, states = held_steps(ev, 1.0)
        assert states == {"running"} and len(steps) >= 2, (steps, states)
        # The page's own Origin is welcome.
        r = view.control({"command": "color", "field": "speed"}, headers={"Origin": f"http://127.0.0.1:{port}"})
        assert r.status == 200, r


TRAVERSALS = ["/../../../etc/passwd", "/%2e%2e/%2e%2e/etc/passwd", "/view.js/../../etc/passwd", "//etc/passwd",
              "/..%2f..%2f..%2fetc%2fpasswd", "/view.js%00.html", "/%2e%2e%5c%2e%2e%5cetc%5cpasswd"]


def test_malformed_requests(tmp_path):
    with Engine(tmp_path, variables=LONG) as run, run.events() as ev:
        ev.wait_for("hello")
        port, token = run.port, run.token
        host = f"Host: 127.0.0.1:{port}\r\n".encode()

        def control(body, content_type=b"application/json"):
            return (f"POST /control?token={token} HTTP/1.1\r\n".encode() + host +
                    b"Content-Type: " + content_type + b"\r\n" +
                    f"Content-Length: {len(body)}\r\nConnection: close\r\n\r\n".encode() + body)

        requests = {
            "garbage request line": b"\x16\x03\x01 garbage \xff\xfe\r\n\r\n",
            "no HTTP version": f"GET /?token={token}\r\n\r\n".encode(),
            "unknown method": f"BREW /?token={token} HTTP/1.1\r\n".encode() + host + b"\r\n",
            "100 KB header line": b"GET /view.js HTTP/1.1\r\n" + host + b"X-Long: " + b"a" * 100_000 + b"\r\n\r\n",
            "1 MB body": control(b"{" + b" " * (1 << 20) + b"}"),
            "invalid JSON": control(b'{"command": pause}'),
            "JSON not an object": control(b'["pause"]'),
            "command not a string": control(b'{"command": 1}'),
            "unknown command": control(b'{"command": "format_disk"}'),
            "empty body": control(b""),
            "lying Content-Length": (f"POST /control?token={token} HTTP/1.1\r\n".encode() + host +
                                     b"Content-Type: application/json\r\nContent-Length: 99999999\r\n\r\n{}"),
        }
        for path in TRAVERSALS:
            requests[f"path {path}"] = (f"GET {path}?token={token} HTTP/1.1\r\n".encode() + host +
                                        b"Connection: close\r\n\r\n")
        answers = {}
        for name, data in requests.items():
            # the lying Content-Length waits for its body: the server's read timeout (10 s) is
            # longer than we wait, which counts as closed
            raw = raw_request(port, data, timeout=3)
            answers[name] = status_of(raw)
            assert b"root:" not in raw and b"/bin/" not in raw, name
            code = status_of(raw)
            assert code is None or 400 <= code < 500, (name, raw[:300])
        # Each answered (or closed) without a file; the commands above changed nothing.
        for name in ("invalid JSON", "JSON not an object", "command not a string", "unknown command", "empty body"):
            assert answers[name] == 400, (name, answers[name])
        assert answers["1 MB body"] in (413, None), answers["1 MB body"]
        print(answers)
        # The run goes on, and a normal request still works.
        steps_advance(ev)
        assert run.running()
        assert run.frame().count == SMALL_PARTICLES
        assert run.control({"command": "color", "field": "speed"}).status == 200


# --- a viewer never holds the run up --------------------------------------------------------------

# A run of a few seconds whose event stream is big (a thermo row of 44 columns every step, and
# its log line: about 1.5 KB a step), so that a viewer that never reads fills the socket's
# buffers (about 1 MB here) within it and the server's writes to it block.
BUSY = {"steps": 1500, "thermo": 1, "wide": 40}


@pytest.fixture(scope="module")
def plain_seconds(tmp_path_factory):
    """The wall time of the BUSY run without the view."""
    run = Engine(tmp_path_factory.mktemp("plain"), variables=BUSY, view=None)
    assert run.wait(120) == 0, run.stderr
    return run.wall_seconds


def misbehave(kind, port, token):
    """A viewer that goes wrong in one way; returns what to keep open until the run ends."""
    events = f"GET /events?token={token} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n".encode()
    if kind == "closes mid-stream":
        ev = EventStream(port, token)
        ev.wait_for("thermo")
        time.sleep(0.3)
        ev.close()
        return []
    if kind == "never reads its events":
        s = socket.socket()
        s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 1024)  # tiny: the server's writes back up
        s.connect(("127.0.0.1", port))
        s.sendall(events)
        return [s]
    if kind == "connects and sends nothing":
        return [socket.create_connection(("127.0.0.1", port))]
    if kind == "sends half a request":
        s = socket.create_connection(("127.0.0.1", port))
        s.sendall(events[:20])
        return [s]
    if kind == "idle keep-alive connection":  # what a browser keeps after a fetch
        conn = http.client.HTTPConnection("127.0.0.1", port)
        conn.request("GET", f"/solids?token={token}")
        assert conn.getresponse().read()
        return [conn]
    raise ValueError(kind)


@pytest.mark.parametrize("kind", ["closes mid-stream", "never reads its events", "connects and sends nothing",
                                  "sends half a request", "idle keep-alive connection"])
def test_misbehaving_viewer_does_not_hold_the_run(tmp_path, plain_seconds, kind):
    """The run goes on and its process ends as soon as without the view, whatever a viewer does."""
    with Engine(tmp_path, variables=BUSY) as run:
        with run.events() as watcher:  # a good viewer too, which sees the run go on
            watcher.wait_for("hello")
            if kind not in ("closes mid-stream", "never reads its events"):
                # Idle from near the run's end: a timeout that started early would hide in the run.
                watcher.wait_for("status", lambda d: d["step"] >= BUSY["steps"] // 2, timeout=60)
            kept = misbehave(kind, run.port, run.token)
            code = run.wait(120)
            last = watcher.events[-1]  # (the run's very last events may be lost: test_every_viewer_sees_the_end)
            steps = [d["step"] for d in watcher.of("thermo")]
        for k in kept:
            k.close()
    assert code == 0, run.stderr
    assert steps and steps[-1] >= BUSY["steps"] - 50, steps[-3:]  # the good viewer followed to the end
    assert (tmp_path / "out" / "final_00001.txt").is_file()
    # From the run's end (the last event the good viewer got) to the process's end: the timing
    # table, and the server's end, which waits for each connection's thread at most the server's
    # write timeout (1 s) or read timeout (2 s); 3 s catches an exit held up by a viewer.
    lag = run.ended - last["at"]
    assert lag <= 3, f"{kind}: the process ended {lag:.1f} s after its run"
    # The view costs the run a status event twice a second and a frame a second (gathering
    # frames at most 2% of its time, ViewServer::kFrameBudget); 1.5x + 2 s leaves room for two
    # cores shared with this test and the server's threads and the process's start, and catches a
    # run or an exit held up by a viewer.
    assert run.wall_seconds <= 1.5 * plain_seconds + 2, \
        f"{kind}: {run.wall_seconds:.1f} s with the view, {plain_seconds:.1f} s without"


def test_every_viewer_sees_the_end(tmp_path):
    """Every viewer gets a run's last thermo row and its final status ("finished"): the page shows
    the run as over. Short runs with a big event stream and several viewers, as the loss is a race
    at the server's end (about 1 viewer in 10 misses the end on this machine; see the report)."""
    steps = 600  # about a second: time for eight viewers to connect on a busy machine
    missed = []
    for i in range(6):
        with Engine(tmp_path / str(i), variables={"steps": steps, "thermo": 1, "wide": 40}) as run:
            viewers = [run.events() for _ in range(8)]
            for ev in viewers:
                ev.wait_for("hello")
            assert run.wait(60) == 0
            for k, ev in enumerate(viewers):
                deadline = time.monotonic() + 2
                while not ev.closed and time.monotonic() < deadline:
                    time.sleep(0.02)
                states = [d["state"] for d in ev.of("status")]
                rows = [d["step"] for d in ev.of("thermo")]
                if "finished" not in states or steps not in rows:
                    missed.append(f"run {i} viewer {k}: last status {states[-1]!r}, last thermo row "
                                  f"{rows[-1] if rows else None}")
                ev.close()
    assert not missed, f"{len(missed)} of 48 viewers missed the run's end: {missed[:4]}"


# --- runs one after another -----------------------------------------------------------------------

@pytest.mark.parametrize("how", ["killed", "stopped from the view"])
def test_reconnect_to_a_new_run_on_the_same_port(tmp_path, how):
    """A run on port P (--view 0's choice) ends with a viewer connected; the next run on --view P
    (at once, as a person continuing from the restart would) serves, with a new run_id and the
    same token."""
    first = Engine(tmp_path, variables=LONG)
    with first, first.events() as ev:
        one = ev.wait_for("hello")
        port, old_token = first.port, first.token
        if how == "killed":
            first.kill()
            variables = LONG
        else:
            assert first.control({"command": "stop"}).status == 200
            assert first.wait(30) == 130
            restart = re.search(r"wrote restart '([^']+)'", first.stderr).group(1)
            variables = dict(LONG, restart=restart)
        deadline = time.monotonic() + 5
        while not ev.closed and time.monotonic() < deadline:
            time.sleep(0.05)
        assert ev.closed  # the stream ends with the process
    second = Engine(tmp_path, variables=variables, view=port, wait_url=False)
    with second:
        second.wait_url(30)  # fails when the port is refused ("in use")
        assert second.port == port
        with second.events() as ev:
            two = ev.wait_for("hello")
        assert two["run_id"] != one["run_id"]
        # The token is the user's (~/.config/pbfengine/view-token): the page left open on the
        # first run's address reaches the second.
        assert second.token == old_token
        assert ViewClient(port, old_token).get("/solids").status == 200


# --- the command line -----------------------------------------------------------------------------

@pytest.mark.parametrize("args, words", [
    (["--view", "abc"], ["--view", "abc"]),
    (["--view", "70000"], ["--view", "70000"]),
    (["--view", "-1"], ["--view"]),
    (["--view", "0", "--view-address", "0.0.0.0"], ["0.0.0.0", "ssh tunnel", "--view-allow-remote"]),
    (["--view", "0", "--view-address", "10.255.255.1", "--view-allow-remote"], ["10.255.255.1", "not an address"]),
    (["--view-allow-remote"], ["--view"]),
    (["--view-address", "127.0.0.1"], ["--view"]),
    (["--view", "0", "--view-address", "no-such-host.invalid"], ["no-such-host.invalid"]),
])
def test_command_line_errors(tmp_path, args, words):
    script = write_scene(tmp_path)
    r = subprocess.run([str(binary()), "run", str(script), "--log", "none", "-v", "steps=5"] + args, cwd=tmp_path,
                       capture_output=True, text=True, timeout=30)
    assert r.returncode != 0
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    assert len(lines) == 1, r.stderr
    assert all(w in lines[0] for w in words), lines[0]
    assert "view: watch" not in r.stdout and "Timing:" not in r.stdout  # no run


def test_port_in_use(tmp_path):
    script = write_scene(tmp_path)
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen()
        port = s.getsockname()[1]
        r = subprocess.run([str(binary()), "run", str(script), "--log", "none", "-v", "steps=5", "--view", str(port)],
                           cwd=tmp_path, capture_output=True, text=True, timeout=30)
    assert r.returncode != 0
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    assert len(lines) == 1 and "in use" in lines[0] and str(port) in lines[0], r.stderr
    assert "Timing:" not in r.stdout



@pytest.mark.skipif(os.geteuid() != 0 or not shutil.which("setpriv"),
                    reason="needs root, to run the engine as a user without it (setpriv)")
def test_port_below_1024_without_the_right(tmp_path):
    """A user may not serve on port 80: one message saying why, before the run."""
    script = write_scene(tmp_path)
    os.chmod(tmp_path, 0o777)
    r = subprocess.run(["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups", str(binary()), "run",
                        str(script), "--log", "none", "-v", "steps=5", "--view", "80"],
                       cwd=tmp_path, capture_output=True, text=True, timeout=30, env=dict(os.environ, HOME="/nonexistent"))
    assert r.returncode == 1
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    assert len(lines) == 1 and "80" in lines[0] and "root" in lines[0], r.stderr
    assert "Timing:" not in r.stdout
