#!/usr/bin/env python3
"""Speed of pbfengine: the original study's performance tables, measured on this machine.

Every figure comes from the timing table that `pbfengine run` prints after a run of the
dam break of `share/make_scene.py --kind dambreak --particles N --dt 0.002` run through
`scenarios/init_file.lua` (PBF with 4 iterations, vorticity, XSPH, box walls, one text
frame at the start and one at the end), with `--threads K --log none`. Times per step come
from the table's `particle-steps per second`; each figure is the median of `--repeats`
runs, and the runs being compared alternate, so that slow spells of a shared machine fall
on both sides. Sub-commands:

  compare  old against new: builds a git commit (default the tag perf-baseline, else
           b2e9ae9) in a temporary directory, or takes --old-binary, and runs old and new
           alternately on the 33,750-particle dam break (75 steps, 2 threads): each run's
           particle-steps per second, the medians and the new / old speed ratio.
  strong   strong scaling at the count nearest 32,768 (33,750), 1 .. nproc threads: time
           per step, speed-up over 1 thread, parallel efficiency; and the same beside one
           CPU-bound process (a machine the run shares), speed-up over 1 thread beside it.
  weak     weak scaling at about 2,197 particles per thread: time per step, efficiency
           t(1) / t(p), and the same corrected for the counts the lattice allows.
  profile  the original study's seven phases at about 16,000 particles (17,280), at 1
           thread and at all: seconds per step and share. forces = external_forces;
           candidates = binning + reorder rows of the neighbour stage; neighbours = the rest
           of that stage (the neighbour lists); iterations = constraints (and dfsph's
           divergence stage); vorticity and viscosity = the vorticity and xsph (or
           sph_viscosity) rows; update = predict + velocity_update; other = everything else
           (frames, thermo, checks, loop and setup).
  strong and profile take --solver wcsph|dfsph (init_file.lua's -v solver=...; the files
  then NAME_SOLVER.md and .png).
  size     throughput against N, from 8,000 to --max-particles (1,000,000) roughly
           doubling, fewer steps at large N: time per particle-step, the log-log slope of
           time per step against N, the ratio of time per particle-step at the largest N
           to that at 33,750, and peak resident memory per particle: the run's peak minus
           that of a nearly empty run (1,250 particles, 1 step), over the extra particles.
           Each run's peak is its ru_maxrss, read by a fresh Python process that starts
           only that run. --double-binary adds a double build's bytes per particle.
  mesh     the same dam break in a container read from a box mesh (init_file.lua's
           walls=mesh: the solid map) against the analytic box, alternately: time per step
           without the setup (the map's build), and the mesh / box ratio of the medians.
  all      all of the above into one directory (default docs/performance/), with a
           header giving the date, nproc, the CPU, the binary's version and the commit.

Each writes a Markdown table to stdout; with --out [DIR] (DIR default docs/performance/)
also NAME.md and NAME.png into DIR (matplotlib is needed only for the plots). Progress
goes to stderr. Scenes and frames live in a temporary directory removed at exit.

    python3 share/benchmarks/scaling.py all --out docs/performance   # ~6 min of runs on 2 cores,
                                                                    # plus building the old commit
    python3 share/benchmarks/scaling.py compare --old-binary OLD/pbfengine --repeats 7
    python3 share/benchmarks/scaling.py strong --particles-override 4000 --repeats 1
    python3 share/benchmarks/scaling.py size --quick --out /tmp/perf   # a smoke test

--quick shrinks every particle count, step count and repeat count (a smoke test in
seconds); explicit options still win over it. On Debian, run it with /usr/bin/python3 when
a pyenv or venv python3 lacks matplotlib.
"""
import argparse
import contextlib
import datetime
import math
import os
import re
import shutil
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
BASELINE_TAG, BASELINE_COMMIT = "perf-baseline", "b2e9ae9"
REFERENCE_N = 33750  # the size benchmark's reference count (the compare scene)
EMPTY_N = 1000       # the scene of the "empty" run whose peak memory is subtracted
PHASES = ["forces", "candidates", "neighbours", "iterations", "vorticity", "viscosity",
          "update", "other"]

# Per sub-command defaults, and the smaller ones of --quick. particles: compare, strong and
# profile: the count asked of make_scene.py; weak: per thread; size: the smallest count.
DEFAULTS = {
    "compare": dict(particles=33750, steps=75, repeats=5, threads=2),
    "strong": dict(particles=32768, steps=75, repeats=5),
    "weak": dict(particles=2197, steps=100, repeats=5),
    "profile": dict(particles=16000, steps=75, repeats=5),
    "size": dict(particles=8000, steps=20, repeats=3, max_particles=1_000_000),
    "mesh": dict(particles=33750, steps=75, repeats=7, threads=2),
}
QUICK = {
    "compare": dict(particles=3430, steps=10, repeats=1, threads=2),
    "strong": dict(particles=3430, steps=10, repeats=1),
    "weak": dict(particles=500, steps=10, repeats=1),
    "profile": dict(particles=2000, steps=10, repeats=1),
    "size": dict(particles=2000, steps=5, repeats=1, max_particles=8000),
    "mesh": dict(particles=3430, steps=10, repeats=1, threads=2),
}


def fail(msg):
    sys.exit(f"scaling.py: error: {msg}")


def warn(msg):
    print(f"scaling.py: warning: {msg}", file=sys.stderr)


def progress(msg):
    print(f"scaling.py: {msg}", file=sys.stderr, flush=True)


def nproc():
    return len(os.sched_getaffinity(0))


def setting(args, command, name):
    """An option's value: given on the command line, else --quick's, else the default."""
    value = getattr(args, name, None)
    if value is not None:
        return value
    if name == "threads" and command == "size":
        return nproc()
    return (QUICK if args.quick else DEFAULTS)[command][name]


# ---------------------------------------------------------------- the timing table

TIMING_HEAD = re.compile(r"^Timing: (\d+) steps? of (\d+) particles? in (-?[0-9.]+) s$")
TABLE_ROW = re.compile(r"^( {2,})(\S.*?)\s+(-?[0-9.]+)\s+(-?[0-9.]+)%$")
RATE = re.compile(r"particle-steps per second:\s*([0-9.eE+-]+)")
NEIGHBOURS = re.compile(r"neighbours per particle: mean ([0-9.]+), max (\d+)")


def parse_timing(text, what):
    """The last timing table in a run's output: steps, particles, wall, rate, stages."""
    lines = [line.rstrip() for line in text.splitlines()]
    heads = [i for i, line in enumerate(lines) if TIMING_HEAD.match(line.strip())]
    if not heads:
        fail(f"no timing table ('Timing: N steps of M particles in T s') in the output of {what}")
    steps, particles, wall = TIMING_HEAD.match(lines[heads[-1]].strip()).groups()
    table = {"steps": int(steps), "particles": int(particles), "wall": float(wall),
             "rate": None, "neighbours": None, "stages": []}
    for line in lines[heads[-1] + 1:]:
        if not line.startswith("  "):
            break
        parse_table_line(line, table)
    if not table["stages"]:
        fail(f"the timing table in the output of {what} has no stage rows")
    if table["rate"] is None or table["rate"] <= 0:  # an older table: rate from the wall time
        table["rate"] = table["steps"] * table["particles"] / max(table["wall"], 1e-9)
    # The rate has 4 significant digits, the wall time 3 decimals: take the finer one.
    table["wall"] = table["steps"] * table["particles"] / table["rate"]
    return table


def parse_table_line(line, table):
    """One line below 'Timing:': a stage (2 spaces), a row in it (4+), or a summary."""
    rate, neighbours, row = RATE.search(line), NEIGHBOURS.search(line), TABLE_ROW.match(line)
    if rate:
        table["rate"] = float(rate.group(1))
    elif neighbours:
        table["neighbours"] = (float(neighbours.group(1)), int(neighbours.group(2)))
    elif row:
        entry = {"name": row.group(2), "seconds": float(row.group(3)),
                 "share": float(row.group(4)), "rows": []}
        if len(row.group(1)) <= 2 or not table["stages"]:  # a stage: 2 spaces; its rows: 4
            table["stages"].append(entry)
        else:
            table["stages"][-1]["rows"].append(entry)


def seconds(entry, table):
    """A line's seconds: the printed value (3 decimals), or, for runs under a second, its
    share of the wall time, which is finer (0.1% of the wall)."""
    return entry["share"] / 100 * table["wall"] if table["wall"] < 1 else entry["seconds"]


def total(entries, table):
    return sum(seconds(e, table) for e in entries)


def has(name, keywords):
    return any(k in name.lower() for k in keywords)


def stages_with(table, keywords):
    return [s for s in table["stages"] if has(s["name"], keywords)]


def neighbour_split(stage, table):
    """(candidates, neighbours) seconds of the neighbour stage: candidates are the binning
    and reorder rows, neighbours the rest (the neighbour lists, and any other row)."""
    candidates = sum(seconds(r, table) for r in stage["rows"]
                     if has(r["name"], ("binning", "candidate", "reorder")))
    for row in stage["rows"]:
        if not has(row["name"], ("binning", "candidate", "reorder", "list")):
            warn(f"neighbour-stage row '{row['name']}' counted as 'neighbours'")
    return candidates, seconds(stage, table) - candidates


def phases(table, what):
    """The original study's phases, seconds summed over the run; 'other' is the rest. The
    iterations are the solver's repeated stages (pbf's constraints; dfsph's divergence and
    constraints); a viscosity counts as viscosity in whichever stage it runs (dfsph's in
    forces), the rest of the force stages as forces."""
    neighbour = stages_with(table, ("neighbo",))
    constraints = stages_with(table, ("constraint", "divergence"))
    if not neighbour or not constraints:
        names = ", ".join(s["name"] for s in table["stages"])
        fail(f"the timing table of {what} has no neighbour or constraints stage "
             f"(stages: {names})")
    force_stages = stages_with(table, ("external", "force"))
    update = stages_with(table, ("predict", "update"))
    taken = neighbour + constraints + update
    rows = [r for s in table["stages"] if s not in taken for r in s["rows"]]
    viscosity = [r for r in rows if has(r["name"], ("xsph", "viscosity"))]
    forces = [r for s in force_stages for r in s["rows"] if r not in viscosity]
    out = {"forces": total(forces, table), "iterations": total(constraints, table),
           "update": total(update, table),
           "vorticity": total([r for r in rows if has(r["name"], ("vorticity",))], table),
           "viscosity": total(viscosity, table)}
    out["candidates"], out["neighbours"] = neighbour_split(neighbour[0], table)
    out["other"] = table["wall"] - sum(out.values())
    return out


# ---------------------------------------------------------------- scenes and runs

def check_binary(path):
    if not (os.path.isfile(path) and os.access(path, os.X_OK)):
        fail(f"no pbfengine binary at {path} (build it with ./setup.sh, or give --binary PATH)")
    return os.path.abspath(path)


def make_scene(target, steps, work):
    """Write the dam break of about `target` particles for `steps` steps; (path, count)."""
    t_final = f"{steps * DT:.10g}"
    path = os.path.join(work, f"dambreak-{target}-{steps}.txt")
    if not os.path.exists(path):
        cmd = [sys.executable, MAKE_SCENE, "--kind", "dambreak", "--particles", str(target),
               "--dt", repr(DT), "--interval", t_final, "--t-final", t_final, "-o", path]
        done = subprocess.run(cmd, capture_output=True, text=True)
        if done.returncode != 0:
            fail(f"make_scene.py failed: {last_line(done.stderr)}")
    with open(path) as f:
        f.readline()
        return path, int(f.readline())


def last_line(text):
    lines = [line for line in text.splitlines() if line.strip()]
    return lines[-1].strip() if lines else "(no output)"


LOG_OPTION = {}


def log_option(binary):
    """['--log', 'none'] where the binary has the option (older ones have no log file)."""
    if binary not in LOG_OPTION:
        done = subprocess.run([binary, "run", "--help"], capture_output=True, text=True)
        LOG_OPTION[binary] = ["--log", "none"] if "--log " in done.stdout + done.stderr else []
    return LOG_OPTION[binary]


# Runs each pbfengine from a fresh, small Python process, whose RUSAGE_CHILDREN peak is then
# that run's alone. (The peak a child inherits includes its parent's at fork and exec, so
# this script's own, tens of MB once matplotlib is loaded, would hide small runs.)
RSS_HELPER = """import resource, subprocess, sys
rc = subprocess.call(sys.argv[2:])
with open(sys.argv[1], "w") as f:
    f.write(f"{rc} {resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss}")
"""


SOLVER = []  # -v solver=NAME for init_file.lua, from --solver (strong, profile)


def run_engine(binary, scene, threads, work, extra=()):
    """Run one scene (extra: more arguments, such as -v NAME=VALUE); its timing table, with
    'peak_bytes' (the run's peak RSS) added."""
    cmd = [binary, "run", *log_option(binary), SCENARIO, "-v", f"init={scene}",
           "-v", f"out={os.path.join(work, 'frames')}", "--threads", str(threads), *SOLVER, *extra]
    what = f"{binary} on {os.path.basename(scene)} with {plural(threads, 'thread')}"
    stats = os.path.join(work, "rusage.txt")
    with tempfile.TemporaryFile("w+", dir=work) as log:
        subprocess.run([sys.executable, "-S", "-c", RSS_HELPER, stats, *cmd],
                       stdout=log, stderr=subprocess.STDOUT, cwd=work)
        log.seek(0)
        text = log.read()
    try:
        with open(stats) as f:
            rc, peak = (int(v) for v in f.read().split())
        os.remove(stats)
    except (OSError, ValueError):
        fail(f"could not run {what}: {last_line(text)}")
    if rc != 0:
        fail(f"{what} exited with status {rc}: {last_line(text)}")
    table = parse_timing(text, what)
    table["peak_bytes"] = peak * 1024  # kilobytes on Linux
    return table


def plural(count, noun):
    return f"{count} {noun}{'' if count == 1 else 's'}"


def step_ms(table):
    return 1000 * table["wall"] / table["steps"]


def median(values):
    return statistics.median(values)


# ---------------------------------------------------------------- output

def md_table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def header_line(binary):
    """Date, nproc, CPU model, the binary's version and the commit, in one line."""
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    cpu = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            models = [line.split(":", 1)[1].strip() for line in f
                      if line.startswith("model name")]
        cpu = models[0] if models else cpu
    except OSError:
        pass
    version = subprocess.run([binary, "--version"], capture_output=True, text=True)
    commit = git("rev-parse", "--short", "HEAD", check=False) or "unknown commit"
    if git("status", "--porcelain", "--untracked-files=no", check=False):
        commit += " (work tree modified)"
    return (f"{date}; nproc {nproc()}; {cpu}; {last_line(version.stdout)} "
            f"({binary}); commit {commit}")


def pyplot():
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        fail("the plots need matplotlib (on Debian: apt install python3-matplotlib, "
             "and run this script with /usr/bin/python3)")
    return plt


def emit(args, name, text, plot):
    """Print a section; with --out also write DIR/NAME.md and DIR/NAME.png."""
    print(text + "\n", flush=True)
    if args.out:
        os.makedirs(args.out, exist_ok=True)
        name += "" if getattr(args, "solver", "pbf") == "pbf" else "_" + args.solver
        with open(os.path.join(args.out, name + ".md"), "w") as f:
            f.write(f"{args.header}\n\n{text}\n")
        plt = pyplot()
        fig, ax = plt.subplots(figsize=(6.4, 4.4))
        plot(ax)
        fig.tight_layout()
        fig.savefig(os.path.join(args.out, name + ".png"), dpi=120)
        plt.close(fig)
        progress(f"wrote {os.path.join(args.out, name)}.md and .png")


def threads_list(args):
    return list(range(1, (args.max_threads or nproc()) + 1))


# ---------------------------------------------------------------- compare

def git(*argv, check=True):
    done = subprocess.run(["git", "-C", REPO, *argv], capture_output=True, text=True)
    if done.returncode != 0 and check:
        fail(f"git {' '.join(argv)} failed: {last_line(done.stderr)}")
    return done.stdout.strip() if done.returncode == 0 else ""


def baseline_commit(commit):
    """The commit to build: the one given, else the tag perf-baseline, else b2e9ae9."""
    for name in ([commit] if commit else [BASELINE_TAG, BASELINE_COMMIT]):
        full = git("rev-parse", "--verify", "--quiet", name + "^{commit}", check=False)
        if full:
            return name, full
    fail(f"no commit {commit or BASELINE_COMMIT} in {REPO}")


def build_commit(commit, jobs):
    """Extract a commit into a temporary directory and build it; (binary, directory)."""
    name, full = baseline_commit(commit)
    tmp = tempfile.mkdtemp(prefix="pbf-scaling-build.")
    progress(f"building {name} ({full[:9]}) in {tmp}; this takes minutes")
    build, log_path = os.path.join(tmp, "build"), os.path.join(tmp, "build.log")
    archive = f"git -C '{REPO}' archive {full} | tar -x -C '{tmp}'"
    steps = [["bash", "-o", "pipefail", "-c", archive],
             ["cmake", "-S", tmp, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
              "-DPBF_BUILD_TESTS=OFF"],
             ["cmake", "--build", build, f"-j{jobs}"]]
    with open(log_path, "w") as log:
        for cmd in steps:
            try:
                done = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT)
            except KeyboardInterrupt:
                shutil.rmtree(tmp, ignore_errors=True)
                raise
            if done.returncode != 0:
                fail(f"building {name} failed at '{' '.join(cmd[:2])}': see {log_path} "
                     f"(and remove {tmp} afterwards)")
    binary = os.path.join(build, "pbfengine")
    if not os.access(binary, os.X_OK):
        fail(f"building {name} gave no {binary}: see {log_path} (and remove {tmp} afterwards)")
    return binary, tmp


def cmd_compare(args, work):
    new = check_binary(args.binary)
    tmp = None
    if args.old_binary:
        old, old_name = check_binary(args.old_binary), args.old_binary
    else:
        old, tmp = build_commit(args.commit, args.jobs or nproc())
        old_name = f"commit {baseline_commit(args.commit)[0]}"
    try:
        return compare_runs(args, work, old, new, old_name)
    finally:
        if tmp and args.keep:
            progress(f"kept the old build in {tmp}")
        elif tmp:
            shutil.rmtree(tmp, ignore_errors=True)


def compare_runs(args, work, old, new, old_name):
    repeats, threads = setting(args, "compare", "repeats"), setting(args, "compare", "threads")
    scene, n = make_scene(setting(args, "compare", "particles"),
                          setting(args, "compare", "steps"), work)
    rates = {"old": [], "new": []}
    for r in range(repeats):
        for label, binary in (("old", old), ("new", new)):
            table = run_engine(binary, scene, threads, work)
            rates[label].append(table["rate"])
            progress(f"compare: run {r + 1}/{repeats}, {label}: "
                     f"{table['rate']:.4g} particle-steps/s")
    pairs = zip(rates["old"], rates["new"])
    rows = [[i + 1, f"{o:,.0f}", f"{w:,.0f}"] for i, (o, w) in enumerate(pairs)]
    old_m, new_m = median(rates["old"]), median(rates["new"])
    rows.append(["**median**", f"**{old_m:,.0f}**", f"**{new_m:,.0f}**"])
    text = (f"## New against old\n\nParticle-steps per second on the dam break of {n} "
            f"particles, {table['steps']} steps, {plural(threads, 'thread')}; old and new "
            f"alternate. Old: {old_name}; new: {new}.\n\n"
            + md_table(["run", "old", "new"], rows)
            + f"\n\nNew / old speed, the ratio of the medians: **{new_m / old_m:.3f}** "
            f"({repeats} runs each).")

    def plot(ax):
        for label, marker in (("old", "o"), ("new", "s")):
            ax.plot(range(1, repeats + 1), rates[label], marker, label=label)
            ax.axhline(median(rates[label]), lw=0.8, color="C0" if label == "old" else "C1")
        ratio = new_m / old_m
        ax.set(xlabel="run", ylabel="particle-steps per second", ylim=(0, None),
               title=f"{n} particles, {plural(threads, 'thread')}: new / old = {ratio:.3f}")
        ax.set_xticks(range(1, repeats + 1))
        ax.legend()
    return "compare", text, plot


# ---------------------------------------------------------------- strong and weak

@contextlib.contextmanager
def cpu_load(count):
    """`count` CPU-bound processes (yes > /dev/null) for the length of the block."""
    processes = [subprocess.Popen(["yes"], stdout=subprocess.DEVNULL) for _ in range(count)]
    try:
        if processes:
            time.sleep(0.2)  # running before the measured run starts
        yield
    finally:
        for p in processes:
            p.kill()
            p.wait()


def scaling_runs(args, command, scenes, threads, binary, work, load=0):
    """Median ms per step for each thread count; the thread counts alternate per repeat.
    load: CPU-bound processes beside each run (a machine the run shares)."""
    repeats = setting(args, command, "repeats")
    times = {p: [] for p in threads}
    beside = f", beside {plural(load, 'CPU-bound process')}" if load else ""
    for r in range(repeats):
        for p in threads:
            with cpu_load(load):
                table = run_engine(binary, scenes[p][0], p, work)
            times[p].append(step_ms(table))
            progress(f"{command}: run {r + 1}/{repeats}, {plural(p, 'thread')}{beside}, "
                     f"{scenes[p][1]} particles: {times[p][-1]:.3f} ms per step")
    return {p: median(t) for p, t in times.items()}


def cmd_strong(args, work):
    binary, threads = check_binary(args.binary), threads_list(args)
    steps = setting(args, "strong", "steps")
    scene = make_scene(setting(args, "strong", "particles"), steps, work)
    t = scaling_runs(args, "strong", {p: scene for p in threads}, threads, binary, work)
    speedup = {p: t[1] / t[p] for p in threads}
    rows = [[p, f"{t[p]:.3f}", f"{speedup[p]:.2f}", f"{speedup[p] / p:.0%}"] for p in threads]
    # The same on a machine the run shares: one CPU-bound process beside each run. The
    # speed-up is over 1 thread under the same load; at most 1 is what the run can expect
    # when its threads outnumber the free cores (docs/performance/shared.md).
    loaded = scaling_runs(args, "strong", {p: scene for p in threads}, threads, binary, work, load=1)
    rows += [[f"{p}, beside a CPU-bound process", f"{loaded[p]:.3f}", f"{loaded[1] / loaded[p]:.2f}", ""]
             for p in threads]
    text = (f"## Strong scaling\n\nThe dam break of {scene[1]} particles, {steps} steps; "
            f"medians of {setting(args, 'strong', 'repeats')} runs, alone on the machine and beside "
            "one CPU-bound process (`yes > /dev/null`), whose speed-up is over 1 thread beside "
            "it.\n\n"
            + md_table(["threads", "ms per step", "speed-up", "efficiency"], rows))

    def plot(ax):
        ax.plot(threads, [speedup[p] for p in threads], "o-", label="measured")
        ax.plot(threads, [loaded[1] / loaded[p] for p in threads], "s:",
                label="beside a CPU-bound process")
        ax.plot(threads, threads, "k--", lw=0.8, label="ideal")
        ax.set(xlabel="threads", ylabel="speed-up over 1 thread",
               title=f"Strong scaling, {scene[1]} particles")
        ax.set_xticks(threads)
        ax.legend()
    return "strong", text, plot


def cmd_weak(args, work):
    binary, threads = check_binary(args.binary), threads_list(args)
    steps, per_thread = setting(args, "weak", "steps"), setting(args, "weak", "particles")
    scenes = {p: make_scene(per_thread * p, steps, work) for p in threads}
    t = scaling_runs(args, "weak", scenes, threads, binary, work)
    n = {p: scenes[p][1] for p in threads}
    eff = {p: t[1] / t[p] for p in threads}
    # The lattice allows only some counts: also compare time per particle per thread.
    eff_pp = {p: (t[1] / n[1]) / (t[p] / (n[p] / p)) for p in threads}
    rows = [[p, n[p], f"{n[p] / p:.0f}", f"{t[p]:.3f}", f"{eff[p]:.0%}", f"{eff_pp[p]:.0%}"]
            for p in threads]
    text = (f"## Weak scaling\n\nThe dam break at about {per_thread} particles per thread "
            f"(the nearest counts the lattice allows), {steps} steps; medians of "
            f"{setting(args, 'weak', 'repeats')} runs. Efficiency is t(1) / t(p) per step; "
            "the last column corrects it for the particles per thread actually used.\n\n"
            + md_table(["threads", "particles", "per thread", "ms per step", "efficiency",
                        "efficiency per particle"], rows))

    def plot(ax):
        ax.plot(threads, [eff[p] for p in threads], "o-", label="t(1) / t(p)")
        ax.plot(threads, [eff_pp[p] for p in threads], "s:", label="per particle")
        ax.axhline(1, color="k", ls="--", lw=0.8, label="ideal")
        top = max(1.2, 1.1 * max(eff.values()), 1.1 * max(eff_pp.values()))
        ax.set(xlabel="threads", ylabel="efficiency", ylim=(0, top),
               title=f"Weak scaling, about {per_thread} particles per thread")
        ax.set_xticks(threads)
        ax.legend()
    return "weak", text, plot


# ---------------------------------------------------------------- profile

def profile_runs(args, binary, scene, counts, work):
    """{threads: {phase: median seconds per step}}; the thread counts alternate."""
    repeats = setting(args, "profile", "repeats")
    runs = {p: [] for p in counts}
    for r in range(repeats):
        for p in counts:
            table = run_engine(binary, scene, p, work)
            split = phases(table, f"{binary} on {scene}")
            runs[p].append({k: v / table["steps"] for k, v in split.items()})
            progress(f"profile: run {r + 1}/{repeats}, {plural(p, 'thread')}: "
                     f"{step_ms(table):.3f} ms per step")
    return {p: {k: median([run[k] for run in runs[p]]) for k in PHASES} for p in counts}


def cmd_profile(args, work):
    binary, top = check_binary(args.binary), threads_list(args)[-1]
    steps = setting(args, "profile", "steps")
    scene, n = make_scene(setting(args, "profile", "particles"), steps, work)
    counts = [1] if top == 1 else [1, top]
    prof = profile_runs(args, binary, scene, counts, work)
    header, rows = ["phase"], []
    for p in counts:
        header += [f"{plural(p, 'thread')}: s per step", "share"]
    for k in PHASES + ["total"]:
        row = [k if k != "total" else "**total**"]
        for p in counts:
            whole = sum(prof[p].values())
            value = whole if k == "total" else prof[p][k]
            row += [f"{value:.6f}", f"{value / whole:.1%}"]
        rows.append(row)
    text = (f"## Profile\n\nThe original study's phases on the dam break of {n} particles, "
            f"{steps} steps; medians of {setting(args, 'profile', 'repeats')} runs. "
            "candidates: binning and reordering; other: frames, thermo, checks, loop.\n\n"
            + md_table(header, rows))
    return "profile", text, lambda ax: plot_profile(ax, prof, counts, n)


def plot_profile(ax, prof, counts, n):
    labels = [plural(p, "thread") for p in counts]
    bottom = [0.0] * len(counts)
    for k in PHASES:
        heights = [1000 * prof[p][k] for p in counts]
        ax.bar(labels, heights, bottom=bottom, label=k, width=0.5)
        bottom = [b + h for b, h in zip(bottom, heights)]
    ax.set(ylabel="ms per step", title=f"Where a step goes, {n} particles")
    ax.legend(fontsize="small", loc="center left", bbox_to_anchor=(1, 0.5))


# ---------------------------------------------------------------- size

def size_targets(smallest, largest):
    """Counts from smallest to largest, roughly doubling, and 33,750 when in range."""
    if largest < smallest:
        fail(f"--max-particles ({largest}) is below the smallest count ({smallest})")
    k = max(1, round(math.log2(largest / smallest)))
    targets = [round(smallest * (largest / smallest) ** (i / k)) for i in range(k + 1)]
    if smallest <= REFERENCE_N <= largest:
        targets.append(REFERENCE_N)
    return sorted(set(targets))


def steps_for(n, steps):
    """Fewer steps at large N: all of them up to 100,000 particles, then in proportion,
    never fewer than 10 (or than --steps, when it asks for fewer)."""
    return max(min(10, steps), round(steps * min(1.0, 100_000 / n)))


def size_scenes(args, work):
    """[(path, count, steps)] for the size benchmark, one per distinct count."""
    steps = setting(args, "size", "steps")
    scenes, seen = [], set()
    for target in size_targets(setting(args, "size", "particles"),
                               setting(args, "size", "max_particles")):
        s = steps_for(target, steps)
        path, n = make_scene(target, s, work)
        if n not in seen:
            seen.add(n)
            scenes.append((path, n, s))
    return sorted(scenes, key=lambda scene: scene[1])


def empty_peak(binary, threads, work):
    """(peak RSS, particles) of an almost empty run: a tiny scene, one step."""
    scene, n0 = make_scene(EMPTY_N, 1, work)
    return run_engine(binary, scene, threads, work)["peak_bytes"], n0


def per_particle(peak, n, empty):
    """Bytes of peak memory per particle beyond the empty run's."""
    base, n0 = empty
    return (peak - base) / (n - n0) if n > n0 else float("nan")


def other_memory(binary, scenes, threads, work):
    """{n: bytes per particle} of another build (one run per count)."""
    empty = empty_peak(binary, threads, work)
    return {n: per_particle(run_engine(binary, path, threads, work)["peak_bytes"], n, empty)
            for path, n, _ in scenes}


def size_runs(args, binary, scenes, work):
    """{n: (us per particle-step, ms per step, bytes per particle)}, medians of repeats."""
    threads, repeats = setting(args, "size", "threads"), setting(args, "size", "repeats")
    empty = empty_peak(binary, threads, work)
    runs = {n: [] for _, n, _ in scenes}
    for r in range(repeats):
        for path, n, _ in scenes:
            table = run_engine(binary, path, threads, work)
            runs[n].append((1e6 / table["rate"], step_ms(table), table["peak_bytes"]))
            progress(f"size: run {r + 1}/{repeats}, {n} particles: {runs[n][-1][0]:.4f} us "
                     "per particle-step")
    out = {}
    for n, values in runs.items():
        out[n] = (median([v[0] for v in values]), median([v[1] for v in values]),
                  per_particle(median([v[2] for v in values]), n, empty))
    return out, empty[1]


def loglog_slope(xs, ys):
    """Least-squares slope of log y against log x."""
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    sxx = sum((x - mx) ** 2 for x in lx)
    return sum((x - mx) * (y - my) for x, y in zip(lx, ly)) / sxx if sxx > 0 else float("nan")


def cmd_size(args, work):
    binary = check_binary(args.binary)
    scenes = size_scenes(args, work)
    res, empty_n = size_runs(args, binary, scenes, work)
    others = {}
    if args.double_binary:
        progress("size: peak memory of the double build")
        others = other_memory(check_binary(args.double_binary), scenes,
                              setting(args, "size", "threads"), work)
    text = size_text(args, scenes, res, others, empty_n)
    return "size", text, lambda ax: plot_size(ax, res)


def size_text(args, scenes, res, others, empty_n):
    ns = sorted(res)
    ref = min(ns, key=lambda n: abs(n - REFERENCE_N))
    header = ["particles", "steps", "ms per step", "us per particle-step", "bytes per particle"]
    header += ["bytes per particle (double)"] if others else []
    rows = []
    for _, n, s in scenes:
        row = [f"{n:,}", s, f"{res[n][1]:.3f}", f"{res[n][0]:.4f}", f"{res[n][2]:.0f}"]
        rows.append(row + ([f"{others[n]:.0f}"] if others else []))
    slope = loglog_slope(ns, [res[n][1] for n in ns]) if len(ns) > 1 else float("nan")
    ratio = (f"Time per particle-step at {ns[-1]:,} over that at {ref:,}: "
             f"**{res[ns[-1]][0] / res[ref][0]:.3f}**." if ref != ns[-1] else
             f"(No ratio to {REFERENCE_N:,} particles: no larger count was measured.)")
    threads, repeats = setting(args, "size", "threads"), setting(args, "size", "repeats")
    return (f"## Throughput against size\n\nThe dam break at {plural(threads, 'thread')}; "
            f"medians of {repeats} runs. Bytes per particle: the run's peak resident memory "
            f"minus that of a {empty_n:,}-particle, 1-step run, over the extra particles.\n\n"
            + md_table(header, rows)
            + f"\n\nLog-log slope of time per step against N (least squares): **{slope:.3f}**. "
            + ratio)


def plot_size(ax, res):
    ns = sorted(res)
    ax.semilogx(ns, [res[n][0] for n in ns], "o-")
    ax.set(xlabel="particles", ylabel="us per particle-step", ylim=(0, None),
           title="Time per particle-step against size")


# ---------------------------------------------------------------- mesh container

def cmd_mesh(args, work):
    binary = check_binary(args.binary)
    repeats, threads = setting(args, "mesh", "repeats"), setting(args, "mesh", "threads")
    scene, n = make_scene(setting(args, "mesh", "particles"), setting(args, "mesh", "steps"), work)
    times = {"box": [], "mesh": []}
    for r in range(repeats):
        for walls in times:
            table = run_engine(binary, scene, threads, work, ["-v", f"walls={walls}"])
            setup = total([e for e in table["stages"] if e["name"].startswith("other")], table)
            times[walls].append(1000 * (table["wall"] - setup) / table["steps"])
            progress(f"mesh: run {r + 1}/{repeats}, {walls}: {times[walls][-1]:.2f} ms per step")
    box_m, mesh_m = median(times["box"]), median(times["mesh"])
    rows = [[i + 1, f"{b:.2f}", f"{m:.2f}", f"{m / b:.3f}"]
            for i, (b, m) in enumerate(zip(times["box"], times["mesh"]))]
    rows.append(["**median**", f"**{box_m:.2f}**", f"**{mesh_m:.2f}**", f"**{mesh_m / box_m:.3f}**"])
    text = (f"## Mesh container against the box\n\nMilliseconds per step, without the setup (the "
            f"solid map's build), on the dam break of {n} particles, {table['steps']} steps, "
            f"{plural(threads, 'thread')}, in the analytic `box` and in a container read from a "
            f"box mesh (`init_file.lua -v walls=mesh`); the two alternate.\n\n"
            + md_table(["run", "box", "mesh", "mesh / box"], rows)
            + f"\n\nMesh / box, the ratio of the medians: **{mesh_m / box_m:.3f}** ({repeats} runs each).")

    def plot(ax):
        for label in times:
            ax.plot(range(1, repeats + 1), times[label], "o" if label == "box" else "s", label=label)
        ax.set(xlabel="run", ylabel="ms per step", ylim=(0, None),
               title=f"{n} particles: mesh / box = {mesh_m / box_m:.3f}")
        ax.legend()
    return "mesh", text, plot


# ---------------------------------------------------------------- all, arguments, main

COMMANDS = {"compare": cmd_compare, "strong": cmd_strong, "weak": cmd_weak,
            "profile": cmd_profile, "size": cmd_size, "mesh": cmd_mesh}


def cmd_all(args, work):
    args.out = args.out or os.path.join(REPO, "docs", "performance")
    header = f"# pbfengine performance\n\n{args.header}"
    sections = []
    for name, command in COMMANDS.items():
        section = command(args, work)
        emit(args, *section)
        sections.append(section[1])
    with open(os.path.join(args.out, "scaling.md"), "w") as f:
        f.write("\n\n".join([header] + sections) + "\n")
    progress(f"wrote {os.path.join(args.out, 'scaling.md')}")


def add_options(p, name):
    p.add_argument("--binary", default=os.path.join(REPO, "build", "pbfengine"),
                   help="the pbfengine to measure (default: build/pbfengine)")
    p.add_argument("--out", nargs="?", const=os.path.join(REPO, "docs", "performance"),
                   metavar="DIR", help="also write NAME.md and NAME.png into DIR "
                   "(default DIR: docs/performance/; all always writes)")
    p.add_argument("--repeats", type=positive, help="runs per figure (the median is reported)")
    p.add_argument("--steps", type=positive,
                   help="steps per run (size: up to 100,000 particles; fewer above, "
                   "at least 10)")
    p.add_argument("--particles-override", dest="particles", type=positive, metavar="N",
                   help="particle count asked for (weak: per thread; size: the smallest)")
    p.add_argument("--quick", action="store_true", help="small counts, few steps: a smoke test")
    if name in ("compare", "all"):
        p.add_argument("--commit", help=f"old commit to build (default {BASELINE_TAG}, "
                       f"else {BASELINE_COMMIT})")
        p.add_argument("--old-binary", help="old pbfengine to use instead of building one")
        p.add_argument("--keep", action="store_true", help="keep the old commit's build")
        p.add_argument("--jobs", type=positive, help="build jobs (default: nproc)")
    if name in ("compare", "size", "mesh", "all"):
        p.add_argument("--threads", type=positive,
                       help="threads (compare and mesh: 2 by default; size: all cores)")
    if name in ("strong", "weak", "profile", "all"):
        p.add_argument("--max-threads", type=positive, help="most threads (default: nproc)")
    if name in ("strong", "profile"):
        p.add_argument("--solver", choices=["pbf", "wcsph", "dfsph"], default="pbf",
                       help="init_file.lua's solver (default pbf); another writes NAME_SOLVER.md/.png")
    if name in ("size", "all"):
        p.add_argument("--max-particles", type=positive, help="largest count (default 1,000,000)")
        p.add_argument("--double-binary", help="a double-precision build: adds its bytes per particle")


def positive(text):
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not an integer: {text!r}")
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {value}")
    return value


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                epilog=__doc__.split("\n\n", 1)[1],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name in list(COMMANDS) + ["all"]:
        add_options(sub.add_parser(name, help=f"see '{name}' below"), name)
    return p.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    for name in ("max_threads", "double_binary", "old_binary", "jobs", "commit"):
        setattr(args, name, getattr(args, name, None))
    if args.out or args.command == "all":
        pyplot()  # fail now, not after the runs, where matplotlib is missing
    args.header = header_line(check_binary(args.binary))
    if getattr(args, "solver", "pbf") != "pbf":
        SOLVER.extend(["-v", f"solver={args.solver}"])
        args.header += f"; init_file.lua -v solver={args.solver}"
    print(args.header + "\n", flush=True)
    load = os.getloadavg()[0]
    if load > 0.5:
        warn(f"load average {load:.2f}: other processes use the cores, timings will be noisy")
    with tempfile.TemporaryDirectory(prefix="pbf-scaling.") as work:
        if args.command == "all":
            cmd_all(args, work)
        else:
            emit(args, *COMMANDS[args.command](args, work))


if __name__ == "__main__":
    try:
        main()
    except KeyboardInterrupt:
        sys.exit("scaling.py: interrupted")
