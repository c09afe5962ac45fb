#!/usr/bin/env python3
"""pbfengine on a machine it shares: wall times beside other work, as ratios measured in one run.

The scene is the dam break of the performance tables (`share/make_scene.py --kind dambreak
--particles 33750 --dt 0.002`, 75 steps; PBF with 4 iterations, vorticity, XSPH, box walls)
run through `scenarios/init_file.lua` with `--log none`. Each figure is the wall time of the
whole `pbfengine run` process (start to exit, what a user waits for), the median of
`--repeats` rounds; within a round every case runs once, in a fixed order, so that slow spells
of the machine fall on all of them. The cases (the load is CPU-bound `yes > /dev/null`
processes, started before the run and stopped after it):

  alone      the run alone, at the default thread count and at 1 thread
  load1      beside one CPU-bound process, at the default and at 1 thread
  load2      beside two CPU-bound processes, at the default and at 1 thread
  pair       two runs started together, each at the default thread count: the time until
             both have finished, against running the same two one after the other
  pair1      the same pair at 1 thread each

It prints a Markdown table with the medians and the ratios issue 29 sets bounds on:
load1 default / load1 one thread (at most 1.2), load2 the same (at most 1.2), pair / serial
(at most 1.1) and alone 1 thread / alone default (the speed-up). --baseline OLD measures a
second binary in the same rounds (its cases right before the binary's), for a table of both.
--out FILE also writes the table there, with the date, the machine and the binaries, and a
bar chart of the ratios beside it (FILE with .png; matplotlib needed).

    python3 share/benchmarks/shared_machine.py --binary build/pbfengine --baseline OLD/pbfengine \
        --repeats 7 --out docs/performance/shared.md      # about 8 minutes on 2 cores
    python3 share/benchmarks/shared_machine.py --env OMP_WAIT_POLICY=passive --cases load1,pair

--env NAME=VALUE (repeatable) sets a variable for the runs (and only for them), to compare
wait policies; --cases picks a subset; --particles and --steps shrink the scene for a quick
look.
"""
import argparse
import datetime
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))
MAKE_SCENE = os.path.join(REPO, "share", "make_scene.py")
SCENARIO = os.path.join(REPO, "scenarios", "init_file.lua")
DT = 0.002
CASES = ["alone", "load1", "load2", "pair", "pair1"]


def fail(message):
    sys.exit(f"shared_machine.py: error: {message}")


def progress(message):
    print(f"shared_machine.py: {message}", file=sys.stderr, flush=True)


class Runs:
    """Starts pbfengine runs of one scene; each run writes its frames into a folder of its own."""

    def __init__(self, binary, scene, folder, env):
        self.binary, self.scene, self.folder = binary, scene, folder
        self.env = dict(os.environ, **env)
        self.count = 0

    def start(self, threads):
        self.count += 1
        out = os.path.join(self.folder, f"run{self.count}")
        command = [self.binary, "run", SCENARIO, "-v", f"init={self.scene}", "-v", f"out={out}", "--log", "none"]
        if threads:
            command += ["--threads", str(threads)]
        return subprocess.Popen(command, env=self.env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)

    @staticmethod
    def finish(process):
        text, _ = process.communicate()
        if process.returncode != 0:
            fail(f"a run failed (exit {process.returncode}):\n{text[-2000:]}")

    def wall(self, threads, together=1):
        """Seconds until `together` runs started at once have all finished."""
        t0 = time.perf_counter()
        processes = [self.start(threads) for _ in range(together)]
        for p in processes:
            self.finish(p)
        return time.perf_counter() - t0


class Load:
    """`count` CPU-bound processes for the length of a `with` block."""

    def __init__(self, count):
        self.count, self.processes = count, []

    def __enter__(self):
        self.processes = [subprocess.Popen(["yes"], stdout=subprocess.DEVNULL) for _ in range(self.count)]
        time.sleep(0.2)  # running before the measured run starts
        return self

    def __exit__(self, *exc):
        for p in self.processes:
            p.kill()
            p.wait()


def one_round(runs, cases):
    """Every case once: {name: seconds}."""
    t = {}
    if "alone" in cases:
        t["alone default"] = runs.wall(None)
        t["alone 1 thread"] = runs.wall(1)
    for load in (1, 2):
        if f"load{load}" in cases:
            with Load(load):
                t[f"load{load} default"] = runs.wall(None)
                t[f"load{load} 1 thread"] = runs.wall(1)
    if "pair" in cases:
        t["pair together"] = runs.wall(None, together=2)
        t["pair one after the other"] = runs.wall(None) + runs.wall(None)
    if "pair1" in cases:
        t["pair together, 1 thread each"] = runs.wall(1, together=2)
    return t


RATIOS = [
    ("alone: 1 thread / default (the speed-up)", "alone 1 thread", "alone default", None),
    ("beside one CPU-bound process: default / 1 thread", "load1 default", "load1 1 thread", 1.2),
    ("beside two CPU-bound processes: default / 1 thread", "load2 default", "load2 1 thread", 1.2),
    ("two runs together / one after the other", "pair together", "pair one after the other", 1.1),
    ("two runs together at 1 thread each / one after the other at the default", "pair together, 1 thread each",
     "pair one after the other", None),
]


def ratios(medians):
    """(label, value, bound) of each ratio whose cases were measured."""
    return [(label, medians[top] / medians[bottom], bound) for label, top, bottom, bound in RATIOS
            if top in medians and bottom in medians]


def table(results, repeats):
    """results: [(name, {case: [seconds]})], one per binary."""
    medians = [(name, {case: statistics.median(v) for case, v in samples.items()}) for name, samples in results]
    names = [name for name, _ in results]
    lines = ["| case | " + " | ".join(f"{n}: median wall (s)" for n in names) + " | runs (s) |",
             "|---|" + "---|" * len(names) + "---|"]
    for case in results[0][1]:
        runs = "; ".join(" ".join(f"{x:.2f}" for x in samples[case]) for _, samples in results)
        lines.append(f"| {case} | " + " | ".join(f"{m[case]:.2f}" for _, m in medians) + f" | {runs} |")
    lines += ["", f"Ratios of the medians ({repeats} rounds):", "",
              "| ratio | " + " | ".join(names) + " | bound (issue 29) |", "|---|" + "---|" * len(names) + "---|"]
    for k, (label, _, bound) in enumerate(ratios(medians[0][1])):
        values = " | ".join(f"{ratios(m)[k][1]:.2f}" for _, m in medians)
        lines.append(f"| {label} | {values} | {'' if bound is None else bound} |")
    return "\n".join(lines) + "\n", medians


def plot(medians, path):
    """A bar chart of the bounded ratios, one bar per binary, the bounds as marks."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        progress("no matplotlib: no plot (on Debian: apt install python3-matplotlib, run with /usr/bin/python3)")
        return
    bounded = [r for r in ratios(medians[0][1]) if r[2] is not None]
    labels = [label.replace(": ", ":\n") for label, _, _ in bounded]
    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    width = 0.8 / len(medians)
    for k, (name, m) in enumerate(medians):
        values = [v for _, v, b in ratios(m) if b is not None]
        ax.bar([x + k * width for x in range(len(values))], values, width, label=name)
    for x, (_, _, bound) in enumerate(bounded):
        ax.plot([x - width / 2, x + (len(medians) - 0.5) * width], [bound, bound], "k--", lw=1)
    ax.set_xticks([x + (len(medians) - 1) * width / 2 for x in range(len(bounded))])
    ax.set_xticklabels(labels, fontsize=8)
    ax.set_ylabel("ratio of wall times (dashed: the bound)")
    ax.set_title("The dam break on a 2-core machine it shares")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    progress(f"wrote {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=os.path.join(REPO, "build", "pbfengine"))
    parser.add_argument("--baseline", help="a second pbfengine measured in the same rounds (an older build)")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--particles", type=int, default=33750)
    parser.add_argument("--steps", type=int, default=75)
    parser.add_argument("--cases", default=",".join(CASES), help=f"comma-separated, of {', '.join(CASES)}")
    parser.add_argument("--env", action="append", default=[], metavar="NAME=VALUE")
    parser.add_argument("--out", help="also write the table into this Markdown file, and its plot beside it")
    args = parser.parse_args()
    binaries = [b for b in (args.baseline, args.binary) if b]
    for b in binaries:
        if not os.access(b, os.X_OK):
            fail(f"no executable '{b}' (build it with ./setup.sh, or give --binary)")
    if args.repeats < 1 or args.particles < 1 or args.steps < 1:
        fail("--repeats, --particles and --steps must be at least 1")
    cases = [c.strip() for c in args.cases.split(",") if c.strip()]
    for c in cases:
        if c not in CASES:
            fail(f"unknown case '{c}'; the cases are {', '.join(CASES)}")
    env = {}
    for item in args.env:
        name, eq, value = item.partition("=")
        if not eq or not name:
            fail(f"--env expects NAME=VALUE, got '{item}'")
        env[name] = value

    with tempfile.TemporaryDirectory(prefix="pbf-shared-") as folder:
        scene = os.path.join(folder, "scene.txt")
        t_final = args.steps * DT
        subprocess.run([sys.executable, MAKE_SCENE, "--kind", "dambreak", "--particles", str(args.particles), "--dt",
                        str(DT), "--interval", f"{t_final:g}", "--t-final", f"{t_final:g}", "-o", scene],
                       check=True, stderr=subprocess.DEVNULL)
        runs = [Runs(os.path.abspath(b), scene, folder, env) for b in binaries]
        samples = [{} for _ in binaries]
        for r in range(args.repeats):
            progress(f"round {r + 1} of {args.repeats}")
            for k, run in enumerate(runs):
                for name, seconds in one_round(run, cases).items():
                    samples[k].setdefault(name, []).append(seconds)
    names = ["before", "after"] if args.baseline else ["pbfengine"]
    text, medians = table(list(zip(names, samples)), args.repeats)
    cpu = next((line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name")), "?")
    which = (f"before: {args.baseline}; after: {args.binary}" if args.baseline else args.binary)
    head = (f"{datetime.datetime.utcnow():%Y-%m-%d %H:%M} UTC; {os.cpu_count()} hardware threads ({cpu}); "
            f"{which}; the dam break of {args.particles} particles, {args.steps} steps"
            + (f"; environment {' '.join(args.env)}" if args.env else "") + "\n\n")
    print(head + text)
    if args.out:
        with open(args.out, "w") as f:
            f.write(head + text)
        plot(medians, os.path.splitext(args.out)[0] + ".png")


if __name__ == "__main__":
    main()
