#!/usr/bin/env python3
"""What the live view costs a run (docs/view.md, docs/performance/view.md).

The dam break of `share/make_scene.py --kind dambreak` (33,750 particles by default) through
scenarios/init_file.lua, timed by the timing table's loop time, in turns:

  plain     no --view
  served    --view 0, nobody watching
  watched   --view 0 and a viewer that takes every frame the server offers as soon as it is
            offered (what the page does, without drawing): the most frames the run sends
  browser   (with --browser) --view 0 and the real page in headless Chromium, drawing

prints each run's loop time, frames and the share of the loop the timing table's "live view"
row took (the run's own work for the view: the gathers), the medians and their ratios to
`plain`.

    python3 share/benchmarks/view_cost.py --binary build/pbfengine [--repeats 5] [--steps 200]
        [--particles 33750] [--threads 2] [--browser]
"""
import argparse
import http.client
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import urllib.parse

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))


def watch(url, stop, frames):
    """Takes every frame the server announces, as the page does, until `stop` is set."""
    parts = urllib.parse.urlsplit(url)
    token = urllib.parse.parse_qs(parts.query)["token"][0]
    events = http.client.HTTPConnection(parts.hostname, parts.port, timeout=30)
    events.request("GET", f"/events?token={token}")
    stream = events.getresponse()
    getter = http.client.HTTPConnection(parts.hostname, parts.port, timeout=30)
    name = None
    while not stop.is_set():
        line = stream.readline()
        if not line:
            return
        line = line.decode().rstrip("\n")
        if line.startswith("event: "):
            name = line[7:]
        elif line.startswith("data: ") and name == "frame":
            getter.request("GET", f"/frame?token={token}")
            body = getter.getresponse().read()
            if body[:4] == b"PBFV":
                frames[0] += 1


def browse(url, stop, frames):
    """The real page in headless Chromium (Debian's chromium and chromium-driver)."""
    from selenium import webdriver
    options = webdriver.ChromeOptions()
    for flag in ("--headless=new", "--no-sandbox", "--enable-unsafe-swiftshader", "--use-angle=swiftshader",
                 "--ignore-gpu-blocklist", "--window-size=1280,800"):
        options.add_argument(flag)
    driver = webdriver.Chrome(options=options)
    try:
        driver.get(url)
        while not stop.is_set():
            time.sleep(0.2)
            try:
                frames[0] = driver.execute_script("return window.pbfView ? window.pbfView.frames : 0") or 0
            except Exception:
                break
    finally:
        driver.quit()


def run(args, scene, out, mode):
    command = [args.binary, "run", os.path.join(ROOT, "scenarios", "init_file.lua"), "--log", "none",
               "-v", f"init={scene}", "-v", f"out={out}", "--threads", str(args.threads)]
    if mode != "plain":
        command += ["--view", "0"]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    stop, frames, viewer, text = threading.Event(), [0], None, []
    for line in process.stdout:
        text.append(line)
        found = re.search(r"view: watch this run at (\S+)", line)
        if found and mode in ("watched", "browser"):
            target = watch if mode == "watched" else browse
            viewer = threading.Thread(target=target, args=(found.group(1), stop, frames), daemon=True)
            viewer.start()
    process.wait()
    stop.set()
    if viewer:
        viewer.join(timeout=30)
    seconds = [float(m.group(1)) for m in (re.search(r"^Timing: .* in ([0-9.]+) s$", l) for l in text) if m]
    if process.returncode != 0 or not seconds:
        sys.exit(f"view_cost: the {mode} run failed:\n{''.join(text[-20:])}")
    # The run's own work for the view after each step (gathers, pictures): its timing row.
    share = [float(m.group(1)) for m in (re.search(r"live view \(frames, pictures\)\s+[0-9.]+\s+([0-9.]+)%", l)
                                         for l in text) if m]
    return seconds[-1], frames[0], share[-1] if share else 0.0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "pbfengine"))
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--particles", type=int, default=33750)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--browser", action="store_true", help="also the real page in headless Chromium")
    args = parser.parse_args()
    modes = ["plain", "served", "watched"] + (["browser"] if args.browser else [])
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "scene.txt")
        t_final = 0.002 * args.steps
        subprocess.run([sys.executable, os.path.join(ROOT, "share", "make_scene.py"), "--kind", "dambreak",
                        "--particles", str(args.particles), "--dt", "0.002", "--interval", str(t_final),
                        "--t-final", str(t_final), "-o", scene], check=True, stderr=subprocess.DEVNULL)
        print(f"# {time.strftime('%Y-%m-%d', time.gmtime())} {os.cpu_count()} cores, {args.particles} particles, "
              f"{args.steps} steps, {args.threads} threads")
        times, shares = {m: [] for m in modes}, {m: [] for m in modes}
        for r in range(args.repeats):
            for mode in modes:  # in turns, so that drift in the machine's speed hits all alike
                seconds, frames, share = run(args, scene, os.path.join(tmp, "frames"), mode)
                times[mode].append(seconds)
                shares[mode].append(share)
                print(f"{mode:8s} {seconds:8.3f} s  {frames:5d} frames  view row {share:5.2f}%", flush=True)
        base = statistics.median(times["plain"])
        for mode in modes:
            m = statistics.median(times[mode])
            print(f"median {mode:8s} {m:8.3f} s  ratio to plain {m / base:.4f}  "
                  f"view row {statistics.median(shares[mode]):.2f}%")


if __name__ == "__main__":
    main()
