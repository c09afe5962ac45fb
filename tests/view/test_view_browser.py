"""The live view's page in headless Chromium, driven as a person would, against a running dam
break (scenarios/dambreak.lua, small, with the hinged gate so that a solid is drawn): the page
shows the run's particle count and step, its plots grow, pause holds the step, Step adds one,
Resume goes on, the colour field changes, a picture is written, a second browser watches the
same run, and Stop ends the run with a restart whose continuation on the same port the same
(not reloaded) page reconnects to. A screenshot is kept for a person: $PBF_ARTIFACTS
(default build/artifacts)/view_dambreak.png. The protocol alone: test_view_protocol.py.

    /usr/bin/python3 -m pytest -x -q tests/view/test_view_browser.py   (PBF_BINARY=... for another binary)

The tests run in order against one run (starting Chromium and the run is what costs), so the
later ones need the earlier ones: run them with -x.
"""
import json
import os
import re
import subprocess
import threading
import time
import urllib.request
from pathlib import Path
from urllib.parse import parse_qs, urlsplit

import pytest

REPO = Path(__file__).resolve().parents[2]
CHROMIUM, CHROMEDRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"
SCENARIO = REPO / "scenarios" / "dambreak.lua"
# About 2700 particles and the gate (a solid the page draws); t_end far away: the run is
# stopped from the page long before. Text frames seldom: they are not what is tested.
VARIABLES = {"particles": 3000, "flap": 800, "t_end": 100, "interval": 0.5}
ENGINE_ENV = {"GOMP_SPINCOUNT": "1000", "KMP_BLOCKTIME": "0", "PBF_WAITING": "pbfengine"}
URL_LINE = re.compile(r"view: watch this run at (http://\S+)")

webdriver = pytest.importorskip("selenium.webdriver", reason="python3-selenium is not installed")
from selenium.webdriver.chrome.service import Service  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402
from selenium.webdriver.support.ui import Select  # noqa: E402

for _path in (CHROMIUM, CHROMEDRIVER):
    if not os.access(_path, os.X_OK):
        pytest.skip(f"{_path} is missing (Debian's chromium and chromium-driver)", allow_module_level=True)


def binary():
    path = Path(os.environ.get("PBF_BINARY", "build/pbfengine"))
    return path if path.is_absolute() else REPO / path


if not binary().exists():
    pytest.skip(f"no engine binary at {binary()}", allow_module_level=True)


def wait_for(probe, what, timeout=20, period=0.1):
    """Polls probe() until it returns something true and returns that; fails naming `what` and
    the last value seen (deadlines rather than fixed sleeps: CI machines differ in pace)."""
    end = time.monotonic() + timeout
    while True:
        value = probe()
        if value:
            return value
        if time.monotonic() > end:
            raise AssertionError(f"timed out after {timeout} s waiting for {what}; last seen: {value!r}")
        time.sleep(period)


class Run:
    """pbfengine run dambreak.lua in `workdir` with a view, on one thread (the browser needs the
    other core); stdout and stderr kept by reader threads (thermo fills a pipe otherwise)."""

    def __init__(self, workdir, view="0", **variables):
        self.workdir = Path(workdir)
        command = [str(binary()), "run", str(SCENARIO), "--threads", "1", "--log", "none", "--view", str(view)]
        for k, v in {**VARIABLES, **variables}.items():
            command += ["-v", f"{k}={v}"]
        # The view's token is kept per user under XDG_CONFIG_HOME: a config of the test's own, which
        # both runs share, so that the continuation serves at the very same address.
        env = dict(os.environ, **ENGINE_ENV, XDG_CONFIG_HOME=str(self.workdir / "config"))
        self.proc = subprocess.Popen(command, cwd=self.workdir, env=env, stdin=subprocess.DEVNULL,
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.stdout, self.stderr = [], []
        self.url_seen = threading.Event()
        self.url = None
        self.readers = [threading.Thread(target=self._read, args=(stream, lines), daemon=True)
                        for stream, lines in ((self.proc.stdout, self.stdout), (self.proc.stderr, self.stderr))]
        for reader in self.readers:
            reader.start()
        if not (self.url_seen.wait(30) and self.url):
            self.kill()
            raise AssertionError(f"no view address printed:\n{self.output()}")
        parts = urlsplit(self.url)
        self.port, self.token = parts.port, parse_qs(parts.query)["token"][0]
        self.base = f"http://127.0.0.1:{self.port}"

    def _read(self, stream, lines):
        for line in stream:
            lines.append(line.rstrip("\n"))
            m = URL_LINE.search(line)
            if m and not self.url_seen.is_set():
                self.url = m.group(1)
                self.url_seen.set()
        if stream is self.proc.stdout:
            self.url_seen.set()  # the process ended: no address is coming

    def output(self):
        if self.proc.poll() is not None:
            for reader in self.readers:
                reader.join(5)  # all that the ended process wrote
        return "\n".join(self.stdout[-20:] + self.stderr[-20:])

    def particles(self):
        """The count the scenario prints ('dam break (pbf): N particles, ...')."""
        for line in self.stdout:
            if m := re.match(r"dam break \(\w+\): (\d+) particles", line):
                return int(m.group(1))
        raise AssertionError(f"no particle count printed: {self.output()}")

    def status(self):
        """The engine's newest status, straight from its event stream (a new connection replays
        hello, the thermo rows, the log and then the newest status)."""
        with urllib.request.urlopen(f"{self.base}/events?token={self.token}", timeout=10) as stream:
            name = None
            for raw in stream:
                line = raw.decode().rstrip("\n")
                if line.startswith("event: "):
                    name = line[7:]
                elif line.startswith("data: ") and name == "status":
                    return json.loads(line[6:])
        raise AssertionError("the event stream ended without a status")

    def control(self, command):
        request = urllib.request.Request(f"{self.base}/control?token={self.token}", data=json.dumps(command).encode(),
                                         headers={"Content-Type": "application/json"})
        with urllib.request.urlopen(request, timeout=10) as answer:
            return json.loads(answer.read())

    def wait(self, timeout):
        try:
            return self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            raise AssertionError(f"the run did not end within {timeout} s: {self.output()}")

    def kill(self):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()


# One call for all that the tests read off the page: cheaper than an element lookup each.
PAGE_STATE = """
const t = (id) => document.getElementById(id).textContent, v = window.pbfView;
return {step: t('step'), state: t('state'), connection: t('connection'), particles: t('particles'),
        banner: document.getElementById('banner').hidden ? '' : t('banner'), colorbar: t('colorbar-name'),
        notice: t('notice'), frames: v.frames, rows: v.rows, lastFrame: v.lastFrame, pictures: v.pictures,
        webgl: v.webgl, log: document.querySelectorAll('#log div').length,
        plots: Array.from(document.querySelectorAll('#plots canvas'), (c) => [c.dataset.column, +c.dataset.points])};
"""


class Page:
    def __init__(self, url=None):
        options = webdriver.ChromeOptions()
        options.binary_location = CHROMIUM
        for flag in ("--headless=new", "--no-sandbox", "--enable-unsafe-swiftshader", "--use-angle=swiftshader",
                     "--ignore-gpu-blocklist", "--window-size=1400,900"):
            options.add_argument(flag)
        options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
        self.driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
        self.console = []  # every console entry so far (get_log empties the browser's buffer)
        if url:
            self.driver.get(url)

    def state(self):
        return self.driver.execute_script(PAGE_STATE)

    def wait(self, predicate, what, timeout=20):
        """Polls the page's state until predicate(state) holds; returns that state."""
        last = {}

        def probe():
            last["state"] = s = self.state()
            return s if predicate(s) else None

        try:
            return wait_for(probe, what, timeout, period=0.15)
        except AssertionError as e:
            raise AssertionError(f"{e}\npage: {last.get('state')}") from None

    def click(self, element_id):
        self.driver.find_element(By.ID, element_id).click()

    def read_console(self):
        self.console += self.driver.get_log("browser")
        return self.console

    def quit(self):
        self.driver.quit()


def severe(entries):
    """The console's errors."""
    return [e for e in entries if e["level"] == "SEVERE"]


@pytest.fixture(scope="module")
def session(tmp_path_factory):
    """The run, and the page open on it (the first browser)."""
    workdir = tmp_path_factory.mktemp("view_browser")
    page, runs = Page(), []
    try:
        # Chromium first: it takes seconds to start, and the run should not be far ahead of the page.
        runs.append(Run(workdir))
        page.driver.get(runs[0].url)
        yield {"workdir": workdir, "runs": runs, "page": page}
    finally:
        page.quit()
        for run in runs:
            run.kill()


def step_of(state):
    return int(state["step"]) if state["step"].isdigit() else -1


def test_page_shows_the_run(session):
    run, page = session["runs"][0], session["page"]
    count = run.particles()
    s = page.wait(lambda s: s["connection"] == "connected" and s["frames"] >= 3 and s["rows"] >= 3,
                  "the page connected, with frames and thermo rows")
    assert s["webgl"] is True, "no WebGL: the 3D view is off (swiftshader missing?)"
    assert int(s["particles"]) == count and s["lastFrame"]["count"] == count
    assert s["state"] == "running" and s["banner"] == ""
    assert s["log"] > 0, "the log panel is empty"
    columns = [c for c, _ in s["plots"]]
    assert "front" in columns and "gate.ry" in columns, columns
    # Every plot has a point per thermo row, and the rows keep coming.
    assert {n for _, n in s["plots"]} == {s["rows"]}, s["plots"]
    page.wait(lambda t: min(n for _, n in t["plots"]) > s["rows"] and t["frames"] > s["frames"]
              and step_of(t) > step_of(s), "the plots, the frames and the step growing")
    # The gate (a solid) was fetched and drawn with the frames.
    assert page.driver.execute_script(
        "return performance.getEntriesByType('resource').some((e) => new URL(e.name).pathname === '/solids')")
    # A screenshot of the running dam break for a person to look at, after a few frames.
    page.wait(lambda t: t["frames"] >= 5, "five frames")
    artifacts = Path(os.environ.get("PBF_ARTIFACTS", "build/artifacts"))
    artifacts = artifacts if artifacts.is_absolute() else REPO / artifacts
    artifacts.mkdir(parents=True, exist_ok=True)
    assert page.driver.save_screenshot(str(artifacts / "view_dambreak.png"))
    assert not severe(page.read_console()), page.console


def test_pause_step_resume(session):
    run, page = session["runs"][0], session["page"]
    page.click("pause")
    held = step_of(page.wait(lambda s: s["state"] == "paused", "the paused state"))
    # Held: the step stays put (status events still come, twice a second) and is the engine's.
    end = time.monotonic() + 1.5
    while time.monotonic() < end:
        s = page.state()
        assert (s["state"], step_of(s)) == ("paused", held)
        time.sleep(0.2)
    engine = run.status()
    assert (engine["state"], engine["step"]) == ("paused", held)
    # Step: exactly one more, then held again.
    page.click("step-once")
    page.wait(lambda s: step_of(s) == held + 1 and s["state"] == "paused", f"step {held + 1}, paused")
    time.sleep(1.0)
    s = page.state()
    assert (s["state"], step_of(s)) == ("paused", held + 1)
    assert run.status()["step"] == held + 1
    page.click("resume")
    page.wait(lambda s: s["state"] == "running" and step_of(s) > held + 5, "the run going on")


def test_colour_field(session):
    page = session["page"]
    frames = page.state()["frames"]
    Select(page.driver.find_element(By.ID, "color")).select_by_value("density")
    # The colour bar names the field of the frame drawn, which the frame's event brings.
    s = page.wait(lambda s: s["colorbar"].startswith("density") and s["frames"] > frames, "frames coloured by density")
    assert page.driver.find_element(By.ID, "color").get_attribute("value") == "density"
    page.wait(lambda t: t["frames"] > s["frames"] + 2 and t["colorbar"].startswith("density"),
              "more frames, still by density")


def test_picture(session):
    page, workdir = session["page"], session["workdir"]
    page.click("picture")
    s = page.wait(lambda s: s["pictures"] or "picture failed" in s["notice"], "the picture's path", timeout=30)
    assert len(s["pictures"]) == 1, s["notice"]
    picture = workdir / s["pictures"][0]  # relative to the run's directory: out/view_STEP.png
    assert picture.is_file(), f"{picture} missing"
    assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_second_browser(session):
    run, page = session["runs"][0], session["page"]
    second = Page(run.url)
    try:
        s = second.wait(lambda s: s["connection"] == "connected" and s["frames"] >= 3, "frames in the second browser",
                        timeout=30)
        assert int(s["particles"]) == run.particles()
        # Both keep taking frames: one viewer never starves the other.
        first = page.state()["frames"]
        second.wait(lambda t: t["frames"] > s["frames"] + 3, "more frames in the second browser")
        page.wait(lambda t: t["frames"] > first + 3, "more frames in the first browser")
        assert not severe(second.read_console()), second.console
    finally:
        second.quit()


def test_stop_and_continue_on_the_same_port(session):
    runs, page, workdir = session["runs"], session["page"], session["workdir"]
    run = runs[0]
    assert not severe(page.read_console()), page.console
    rows = page.state()["rows"]
    # The Stop button asks first; the mark tells that the page is never reloaded.
    page.driver.execute_script("window.confirm = () => true; window.notReloaded = true")
    page.click("stop")
    assert run.wait(60) == 130, run.output()
    message = "\n".join(run.stderr)
    m = re.search(r"after step (\d+) \(t = ([0-9.e+-]+) s\): wrote restart '([^']+)'", message)
    assert m and "continue with:" in message, message
    stopped, t_stopped, restart = int(m.group(1)), float(m.group(2)), m.group(3)
    assert (workdir / restart).is_file()
    # The page says the run ended, then that it lost the engine and is trying again.
    page.wait(lambda s: s["state"] == "stopped" and step_of(s) == stopped, "the stopped state at the stop's step")
    page.wait(lambda s: s["connection"] == "disconnected" and "connection lost" in s["banner"], "the lost banner")
    assert page.driver.find_element(By.ID, "pause").get_attribute("disabled") is not None

    # The continuation, on the same port, to 0.5 s of simulated time past the restart.
    # At once, as a person would: the port must be free again as soon as the stopped run exited.
    again = Run(workdir, view=run.port, restart=restart, t_end=round(t_stopped + 0.5, 6))
    runs.append(again)
    assert again.url == run.url, "the continuation serves at another address"
    # Held at once (by the protocol, not the page) so that it cannot end before the page's
    # next try (every 2 s): the page then shows the new run and resumes it itself.
    again.control({"command": "pause"})
    page.wait(lambda s: s["connection"] == "connected" and "new run" in s["banner"], "the page back, on a new run",
              timeout=30)
    page.wait(lambda s: s["state"] == "paused" and step_of(s) > stopped and s["lastFrame"]["step"] > stopped,
              "the continuation's step and frame")
    page.click("resume")
    assert again.wait(120) == 0, again.output()
    # The plots started afresh with the continuation's rows; the page was never reloaded.
    s = page.state()
    assert 0 < s["rows"] < rows and {n for _, n in s["plots"]} == {s["rows"]}, (rows, s)
    assert page.driver.execute_script("return window.notReloaded === true")
    # While the engine was away the page's requests failed (the event stream cut, its retries and
    # the /solids probe refused): those errors, and no others.
    down = re.compile(rf"{re.escape(run.base)}/(events|solids|frame)\?\S* - Failed to load resource: net::ERR_"
                      r"(CONNECTION_REFUSED|CONNECTION_RESET|EMPTY_RESPONSE|INCOMPLETE_CHUNKED_ENCODING)$")
    assert not [e for e in severe(page.read_console()) if not down.match(e["message"])], page.console
