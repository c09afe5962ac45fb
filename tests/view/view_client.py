"""A small client of pbfengine's live view (docs/view.md, the protocol in engine/view/view_server.cpp),
for the tests in this directory. Standard library only (run with Debian's /usr/bin/python3).

    with Engine(tmp_path, variables={"steps": 100000}) as run:   # pbfengine run small.lua --view 0
        with run.events() as ev:                                   # GET /events, parsed on a thread
            hello = ev.wait_for("hello")
            frame = run.frame()                                    # GET /frame, its header and arrays
            run.control({"command": "pause"})                     # POST /control

The binary is $PBF_BINARY, or build/pbfengine of this repository.
"""
import http.client
import json
import os
import queue
import re
import signal
import socket
import struct
import subprocess
import threading
import time
from array import array
from pathlib import Path
from urllib.parse import urlsplit, parse_qs

REPO = Path(__file__).resolve().parents[2]

# The engine's threads must not spin while it waits (two cores are shared with the test and the
# server's threads); the same settings the Python module and the mutation tests use.
ENGINE_ENV = {"GOMP_SPINCOUNT": "1000", "KMP_BLOCKTIME": "0", "PBF_WAITING": "pbfengine"}
MPI_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
           "OMPI_MCA_rmaps_base_oversubscribe": "1"}

# A small dam break (500 particles at the default spacing, about 400 steps/s on one core) that
# can continue from a restart (-v restart=FILE, pbf.scene as scenarios/dambreak.lua does), and
# writes one text frame at step 0 and one at its last step (out/final_00001.txt), to compare runs.
#   -v steps=N      the run ends at step N (a continued run too)
#   -v spacing=S    the lattice spacing (m): 0.01 gives 500 particles, 0.008 about 1000
#   -v obstacle=1   a solid ball on the floor (an obstacle the view sends as a solid)
#   -v thermo=N     a thermo row every N steps (default 10)
#   -v wide=N       N more thermo columns (kinetic energy again): a viewer gets more bytes a step
SMALL_SCENE = """\
-- small.lua: a small dam break for the live view's tests (tests/view/view_client.py)
local steps = var.steps or 300
local s = var.spacing or 0.01
pbf.scene(function()
  pbf.domain{lo = {0, 0, 0}, hi = {0.3, 0.05, 0.2}}
  pbf.kernel_radius(2 * s)
  pbf.timestep(0.002)
  pbf.lattice{lo = {0, 0, 0}, hi = {0.1, 0.05, 0.1}, spacing = s}
end)
pbf.fix("gravity", "gravity", {acceleration = {0, 0, -9.81}})
pbf.fix("pbf", "pbf", {iterations = 4})
pbf.fix("walls", "box", {})
if var.obstacle then   -- a ball on the floor in the surge's way: the view's /solids
  pbf.fix("ball", "solid", {shape = "sphere", center = {0.22, 0.025, 0.02}, radius = 0.02})
end
pbf.fix("final", "dump/text", {path = "out/final_*.txt", every = steps, fields = {"id", "position", "velocity"}})
pbf.compute("ke", "kinetic_energy")
pbf.compute("err", "density_error")
local columns = {"step", "time", "ke", "err.avg"}
for k = 1, var.wide or 0 do   -- more columns: a bigger event stream
  pbf.compute("ke" .. k, "kinetic_energy")
  columns[#columns + 1] = "ke" .. k
end
pbf.thermo{every = var.thermo or 10, columns = columns}
pbf.run(steps - pbf.step())
"""

SMALL_PARTICLES = 500  # 10 x 5 x 10 at the default spacing
SMALL_DOMAIN = ((0.0, 0.0, 0.0), (0.3, 0.05, 0.2))
URL_LINE = re.compile(r"view: watch this run at (http://\S+)")


def binary():
    path = Path(os.environ.get("PBF_BINARY", "build/pbfengine"))
    return path if path.is_absolute() else REPO / path


def write_scene(directory, name="small.lua", text=SMALL_SCENE):
    path = Path(directory) / name
    path.write_text(text)
    return path


class Engine:
    """pbfengine run SCRIPT in `workdir`, its stdout and stderr kept by reader threads. With
    view=None no --view is given; `ranks` runs it under mpirun."""

    def __init__(self, workdir, script=None, variables=None, view="0", args=(), threads=1, ranks=None,
                 wait_url=True, timeout=30):
        self.workdir = Path(workdir)
        self.workdir.mkdir(parents=True, exist_ok=True)
        script = script or write_scene(self.workdir)
        command = [str(binary()), "run", str(script), "--log", "none"]
        for k, v in (variables or {}).items():
            command += ["-v", f"{k}={v}"]
        if view is not None:
            command += ["--view", str(view)]
        command += list(args)
        env = dict(os.environ, **ENGINE_ENV, OMP_NUM_THREADS=str(threads))
        if ranks:
            command = ["mpirun", "-n", str(ranks)] + command
            env.update(MPI_ENV)
        self.command = command
        self.stdout_lines, self.stderr_lines = [], []
        self._url_seen = threading.Event()
        self.url = self.port = self.token = None
        self.started = time.monotonic()
        self.ended = None
        # A session of its own, so that a kill reaches mpirun's ranks too.
        self.proc = subprocess.Popen(command, cwd=self.workdir, env=env, stdin=subprocess.DEVNULL,
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                     start_new_session=True)
        self._readers = [threading.Thread(target=self._read, args=(self.proc.stdout, self.stdout_lines), daemon=True),
                         threading.Thread(target=self._read, args=(self.proc.stderr, self.stderr_lines), daemon=True)]
        for t in self._readers:
            t.start()
        if view is not None and wait_url:
            self.wait_url(timeout)

    def _read(self, stream, lines):
        for line in stream:
            lines.append(line.rstrip("\n"))
            m = URL_LINE.search(line)
            if m and not self._url_seen.is_set():
                self.url = m.group(1)
                parts = urlsplit(self.url)
                self.port = parts.port
                self.token = parse_qs(parts.query)["token"][0]
                self._url_seen.set()
        if stream is self.proc.stdout:
            self._url_seen.set()  # no URL is coming: the waiter sees url None

    def wait_url(self, timeout=30):
        if not self._url_seen.wait(timeout) or self.url is None:
            try:
                self.proc.wait(2)  # when stdout closed: the exit code of a run that failed
            except subprocess.TimeoutExpired:
                pass
            raise AssertionError(f"no view URL (within {timeout} s, before stdout closed); rc {self.proc.poll()}\nstdout:\n"
                                 f"{self.stdout}\nstderr:\n{self.stderr}")
        return self.url

    @property
    def stdout(self):
        return "\n".join(self.stdout_lines)

    @property
    def stderr(self):
        return "\n".join(self.stderr_lines)

    def running(self):
        return self.proc.poll() is None

    def wait(self, timeout=60):
        """The exit code (after the readers took all of the output)."""
        code = self.proc.wait(timeout)
        for t in self._readers:
            t.join(5)
        if self.ended is None:
            self.ended = time.monotonic()
        return code

    @property
    def wall_seconds(self):
        return (self.ended or time.monotonic()) - self.started

    def kill(self):
        if self.running():
            try:
                os.killpg(self.proc.pid, signal.SIGKILL)  # its own session: this run's processes only
            except ProcessLookupError:
                pass
        try:
            self.wait(10)
        except subprocess.TimeoutExpired:
            pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.kill()

    # --- the view ---
    def view(self, host=None):
        return ViewClient(self.port, self.token, host=host)

    def events(self, **kw):
        return EventStream(self.port, self.token, **kw)

    def frame(self, **kw):
        return self.view().frame(**kw)

    def control(self, command, **kw):
        return self.view().control(command, **kw)


class Response:
    def __init__(self, status, headers, body):
        self.status, self.headers, self.body = status, headers, body

    def json(self):
        return json.loads(self.body)

    def __repr__(self):
        return f"Response({self.status}, {self.body[:200]!r})"


class Frame:
    """GET /frame: the 32-byte header ("PBFV", uint32 count, float64 time, int64 step, uint32 seq,
    uint32 reserved), float32 xyz * count, float32 values * count; little endian."""
    HEADER = struct.Struct("<4sIdqII")

    def __init__(self, data):
        magic, self.count, self.time, self.step, self.seq, self.reserved = self.HEADER.unpack_from(data, 0)
        assert magic == b"PBFV", f"frame magic {magic!r}"
        expected = self.HEADER.size + 16 * self.count
        assert len(data) == expected, f"frame of {len(data)} bytes, its header says {expected}"
        floats = array("f", data[self.HEADER.size:])
        if floats.itemsize != 4:
            raise RuntimeError("float is not 4 bytes here")
        n = self.count
        self.xyz = floats[:3 * n]
        self.values = floats[3 * n:]

    def positions(self):
        return [(self.xyz[3 * i], self.xyz[3 * i + 1], self.xyz[3 * i + 2]) for i in range(self.count)]


class ViewClient:
    """Plain requests to the view on 127.0.0.1:port; `host` replaces the Host header."""

    def __init__(self, port, token, host=None, timeout=10):
        self.port, self.token, self.host, self.timeout = port, token, host, timeout

    def path(self, path, token=True):
        if token is True:
            token = self.token
        if token is None or token is False:
            return path
        return f"{path}{'&' if '?' in path else '?'}token={token}"

    def request(self, method, path, body=None, headers=None, token=True):
        conn = http.client.HTTPConnection("127.0.0.1", self.port, timeout=self.timeout)
        try:
            h = dict(headers or {})
            if self.host is not None:
                h["Host"] = self.host  # http.client then sends this one only
            conn.request(method, self.path(path, token), body=body, headers=h)
            r = conn.getresponse()
            return Response(r.status, dict(r.getheaders()), r.read())
        finally:
            conn.close()

    def get(self, path, **kw):
        return self.request("GET", path, **kw)

    def frame(self, **kw):
        r = self.get("/frame", **kw)
        assert r.status == 200, r
        return Frame(r.body)

    def solids(self, **kw):
        r = self.get("/solids", **kw)
        assert r.status == 200, r
        return r.json()

    def control(self, command, content_type="application/json", headers=None, **kw):
        """POST /control: a dict is sent as JSON, bytes or str as they are."""
        body = json.dumps(command) if isinstance(command, dict) else command
        h = {"Content-Type": content_type} if content_type else {}
        h.update(headers or {})
        return self.request("POST", "/control", body=body, headers=h, **kw)


class EventStream:
    """GET /events on a thread: every event as {"event": NAME, "data": parsed JSON, "at": monotonic
    seconds} in `events` (and in `queue`). wait_for() looks from a position in that list on."""

    def __init__(self, port, token, host=None, timeout=10):
        self.events = []
        self.queue = queue.Queue()
        self.comments = 0
        self.error = None
        self._cond = threading.Condition()
        self._conn = http.client.HTTPConnection("127.0.0.1", port, timeout=timeout)
        headers = {"Accept": "text/event-stream"}
        if host is not None:
            headers["Host"] = host
        self._conn.request("GET", f"/events?token={token}" if token else "/events", headers=headers)
        self.response = self._conn.getresponse()
        self.status = self.response.status
        self.closed = False
        if self.status != 200:
            self.body = self.response.read()
            self._conn.close()
            self.closed = True
            return
        self._conn.sock.settimeout(None)  # a paused run sends only status events
        self._thread = threading.Thread(target=self._read, daemon=True)
        self._thread.start()

    def _read(self):
        name, data = None, []
        try:
            while True:
                raw = self.response.readline()
                if not raw:
                    break
                line = raw.decode("utf-8").rstrip("\r\n")
                if line == "":
                    if name is not None or data:
                        event = {"event": name or "message", "data": json.loads("\n".join(data)),
                                 "at": time.monotonic()}
                        with self._cond:
                            self.events.append(event)
                            self._cond.notify_all()
                        self.queue.put(event)
                    name, data = None, []
                elif line.startswith(":"):
                    self.comments += 1
                elif line.startswith("event:"):
                    name = line[6:].strip()
                elif line.startswith("data:"):
                    data.append(line[5:].lstrip(" "))
        except Exception as e:  # a closed socket ends the stream
            if not self.closed:
                self.error = e
        finally:
            with self._cond:
                self.closed = True
                self._cond.notify_all()

    def mark(self):
        """The position of the next event: wait_for(after=mark()) sees only newer ones."""
        with self._cond:
            return len(self.events)

    def of(self, name, after=0):
        with self._cond:
            return [e["data"] for e in self.events[after:] if e["event"] == name]

    def wait_for(self, name, pred=None, timeout=10, after=0):
        """The data of the first event NAME from position `after` on for which pred(data) holds."""
        deadline = time.monotonic() + timeout
        i = after
        with self._cond:
            while True:
                while i < len(self.events):
                    e = self.events[i]
                    i += 1
                    if e["event"] == name and (pred is None or pred(e["data"])):
                        return e["data"]
                left = deadline - time.monotonic()
                if left <= 0 or self.closed:
                    seen = [(e["event"], e["data"]) for e in self.events[-5:]]
                    raise AssertionError(f"no '{name}' event{' as wished' if pred else ''} within {timeout} s "
                                         f"(stream {'closed' if self.closed else 'open'}; last: {seen})")
                self._cond.wait(left)

    def latest_step(self, timeout=10):
        """The step of a status event newer than now."""
        return self.wait_for("status", after=self.mark(), timeout=timeout)["step"]

    def close(self):
        self.closed = True
        try:
            self._conn.sock and self._conn.sock.shutdown(socket.SHUT_RDWR)
        except OSError:
            pass
        self._conn.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def _complete(out):
    """Whether `out` holds a whole answer: its headers and as many bytes as Content-Length says
    (the server keeps a connection open after a 400 unless asked to close it)."""
    head, sep, body = out.partition(b"\r\n\r\n")
    if not sep:
        return False
    m = re.search(rb"(?im)^content-length:\s*(\d+)\s*$", head)
    return m is not None and len(body) >= int(m.group(1))


def raw_request(port, data, timeout=5, read_limit=1 << 20):
    """Sends bytes over a fresh socket and returns what came back until the server closed it, a
    whole answer came, or `timeout` passed. A reset while sending (the server refused early)
    counts as closed."""
    out = b""
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as s:
        try:
            s.sendall(data)
        except (BrokenPipeError, ConnectionResetError):
            pass
        deadline = time.monotonic() + timeout
        try:
            while len(out) < read_limit and time.monotonic() < deadline:
                chunk = s.recv(65536)
                if not chunk:
                    break
                out += chunk
                if _complete(out):
                    break
        except (socket.timeout, ConnectionResetError):
            pass
    return out


def status_of(raw):
    """The status code of a raw HTTP answer, None when none came."""
    m = re.match(rb"HTTP/1\.[01] (\d{3})", raw)
    return int(m.group(1)) if m else None


def png_size(path):
    """A PNG's width and height from its IHDR chunk."""
    data = Path(path).read_bytes()[:32]
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    assert data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24])


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]
