#!/usr/bin/env python3
"""Single against double precision: is a -DPBF_REAL=float build accurate enough to be the default?

Runs the same scenes with two builds of pbfengine, --float-binary (default
build/pbfengine) and --double-binary (default build-double/pbfengine), one OpenMP thread
each (--threads 1, --log none), and compares what each measures:

  1. The Martin & Moyce (1952) dam break, the tall column (a = 2.25 in = 0.05715 m, 2a
     high): speed_vs_error.py's PBF default row, run by martin_moyce.py's runner
     (scenarios/dambreak.lua -v a=0.05715, 16 particles across a, to T = t sqrt(2 g / a) =
     3.9). Front: the 99.5th percentile of x plus half a spacing, Z = front / a, read at
     T = 1, 2, 3.                    Criterion: |Z_float - Z_double| <= 0.005 at each T.
  2. The column at rest of docs/physics.md ("A column at rest"): scenarios/hydrostatic.lua
     -v particles=6912 -v height=0.12 -v width=0.24 -v dt=0.002 (10 mm spacing, PBF
     defaults), its thermo CSV every 0.1 s. Over the lines with 1 s <= t <= 2 s: the mean
     compression (density_error's `compression`, the mean over particles of
     max(rho/rho0 - 1, 0)) averaged over the lines, the mean particle speed averaged over
     them, and the largest particle speed at any of them.
                                      Criterion: compression within 10% (relative) of double's.
  3. The same column with WCSPH (-v solver=wcsph), the same quantities and criterion
     (leave it out with --no-wcsph).

The dam break's time-averaged compression and every run's CPU time are reported too, with
no criterion. It prints a Markdown table (scene, quantity, float, double, difference,
criterion, pass/fail) and a verdict; --out FILE writes them as a Markdown report section
(date UTC, machine, the builds' precision from the CMakeCache.txt beside each binary, the
exact commands). --quick runs small versions for smoke tests (8 particles across a; a
column of 864 particles, 20 mm spacing, same window of t = 1 to 2 s); their numbers decide
nothing.

    /usr/bin/python3 share/validation/precision.py [--float-binary build/pbfengine]
        [--double-binary build-double/pbfengine] [--quick] [--no-wcsph] [--out FILE]

The full run takes about two minutes of CPU on one core (per build: the dam break 1.5 s,
the PBF column 9 s, the WCSPH column 50 s; --no-wcsph: 20 s in all), the quick one 10 s.
Exit status: 0 when every criterion passes, 1 when one fails, 2 when a binary is missing or
a run fails (one line on stderr, `precision.py: error: ...`).
"""
import argparse
import csv
import datetime
import os
import platform
import resource
import shlex
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import martin_moyce as mm  # noqa: E402  (the dam break's runner and scores)
import speed_vs_error as sve  # noqa: E402  (its PBF default row)

from machine import machine  # share/validation/machine.py

ROOT = mm.ROOT
PROG = "precision.py"
ENGINE_FLAGS = ["--threads", "1", "--log", "none"]  # one thread; no log.pbfengine in the working directory
Z_TOLERANCE = 0.005       # |Z_float - Z_double| at T = 1, 2, 3
COMPRESSION_TOLERANCE = 0.10  # relative, of double's
WINDOW = (1.0, 2.0)       # s, the column's averaging window
# The column at rest: hydrostatic.lua's variables (physics.md, "A column at rest").
COLUMN = {"height": 0.12, "width": 0.24, "dt": 0.002}
COLUMN_PARTICLES = {False: 6912, True: 864}  # 10 mm spacing; --quick: 20 mm
DAMBREAK_ACROSS = {False: 16, True: 8}       # particles across a; --quick: 8


class RunFailed(Exception):
    pass


def fail(message):
    print(f"{PROG}: error: {message}", file=sys.stderr)
    sys.exit(2)


def last_line(done):
    for text in (done.stderr, done.stdout):
        lines = [x.strip() for x in (text or "").splitlines() if x.strip()]
        if lines:
            return lines[-1]
    return "no output"


class Engine:
    """Runs pbfengine with ENGINE_FLAGS and records every command line exactly as run.

    martin_moyce.run() calls subprocess.run through its module's `subprocess`; while the dam
    break runs, that name points here, so the runner and its scores are martin_moyce.py's own
    and only the thread count, the log file and the record are added."""

    def __init__(self):
        self.commands = []
        self.last = None

    def run(self, cmd, **kwargs):
        cmd = list(cmd) + ENGINE_FLAGS
        self.commands.append(cmd)
        try:
            self.last = subprocess.run(cmd, **kwargs)
        except OSError as e:  # a binary being rebuilt: "Text file busy", a half-written file
            raise RunFailed(f"{shlex.join(cmd)}: {e.strerror or e}")
        return self.last


def precision_of(binary):
    """PBF_REAL of the build the binary comes from (CMakeCache.txt beside it), or 'unknown'."""
    try:
        with open(os.path.join(os.path.dirname(binary), "CMakeCache.txt")) as f:
            for line in f:
                if line.startswith("PBF_REAL:"):
                    return line.split("=", 1)[1].strip()
    except OSError:
        pass
    return "unknown"


def dambreak(engine, binary, across, work):
    """speed_vs_error.py's PBF default row through martin_moyce.run(); returns a dict."""
    solver, _, _, n, _, settings = next(v for v in sve.variants(across) if v[:2] == ("pbf", "default"))
    saved, runs = mm.subprocess, len(engine.commands)
    mm.subprocess = engine
    try:
        r = mm.run(binary, 2, n, settings, work)
    except SystemExit as e:  # martin_moyce.run() exits on a failed run with the whole output
        if len(engine.commands) == runs:  # it did not get to run (the binary went missing)
            raise RunFailed(str(e.code).splitlines()[0])
        raise RunFailed(f"{shlex.join(engine.commands[-1])} exited with status {engine.last.returncode}: "
                        f"{last_line(engine.last)}")
    finally:
        mm.subprocess = saved
    out = {f"Z{t}": mm.interpolate(r.T, r.front, t) for t in (1, 2, 3)}
    out.update(compression=r.compression, cpu=r.cpu)
    return out


def column(engine, binary, particles, solver, work):
    """hydrostatic.lua's column at rest; averages over the thermo lines with t in WINDOW."""
    path = os.path.join(work, f"column_{solver}.csv")
    cmd = [binary, "run", os.path.join(ROOT, "scenarios", "hydrostatic.lua"), "-v", f"particles={particles}"]
    cmd += [x for k, v in COLUMN.items() for x in ("-v", f"{k}={v}")]
    if solver != "pbf":
        cmd += ["-v", f"solver={solver}"]
    cmd += ["-v", f"t_end={WINDOW[1]}", "-v", f"csv={path}"]
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = engine.run(cmd, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise RunFailed(f"{shlex.join(engine.commands[-1])} exited with status {done.returncode}: {last_line(done)}")
    with open(path) as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))  # "# units: ..."
                if WINDOW[0] - 1e-6 <= float(r["time"]) <= WINDOW[1] + 1e-6]
    if not rows:
        raise RunFailed(f"{path}: no thermo line between t = {WINDOW[0]} and {WINDOW[1]} s")
    return dict(compression=sum(float(r["err.compression"]) for r in rows) / len(rows),
                mean_speed=sum(float(r["v.avg"]) for r in rows) / len(rows),
                max_speed=max(float(r["v.max"]) for r in rows),
                lines=len(rows),
                cpu=after.ru_utime + after.ru_stime - used.ru_utime - used.ru_stime)


def measure(engine, binary, quick, wcsph, work):
    """Every scene with one binary: {scene key: results}."""
    os.makedirs(work)
    out = {"dambreak": dambreak(engine, binary, DAMBREAK_ACROSS[quick], work)}
    solvers = ["pbf", "wcsph"] if wcsph else ["pbf"]
    for solver in solvers:
        out[f"column_{solver}"] = column(engine, binary, COLUMN_PARTICLES[quick], solver, work)
    return out


def rows(f, d, quick, wcsph):
    """Table rows: (scene, quantity, float, double, difference, criterion, verdict or '-')."""
    table = []
    scene = f"dam break, PBF, {DAMBREAK_ACROSS[quick]} across a"
    for t in (1, 2, 3):
        zf, zd = f["dambreak"][f"Z{t}"], d["dambreak"][f"Z{t}"]
        ok = abs(zf - zd) <= Z_TOLERANCE
        table.append((scene, f"Z at T = {t}", f"{zf:.4f}", f"{zd:.4f}", f"{zf - zd:+.4f}",
                      f"abs. difference <= {Z_TOLERANCE}", "pass" if ok else "FAIL"))
    table.append((scene, "mean compression, time average", *percent(f["dambreak"]["compression"],
                                                                    d["dambreak"]["compression"]), "-", "-"))
    table.append((scene, "CPU time", f"{f['dambreak']['cpu']:.2f} s", f"{d['dambreak']['cpu']:.2f} s",
                  relative(f["dambreak"]["cpu"], d["dambreak"]["cpu"]), "-", "-"))
    for solver in (["pbf", "wcsph"] if wcsph else ["pbf"]):
        key = f"column_{solver}"
        cf, cd = f[key], d[key]
        scene = f"column at rest, {solver.upper()}, {COLUMN_PARTICLES[quick]} particles"
        window = f"t = {WINDOW[0]:g} to {WINDOW[1]:g} s"
        if cd["compression"] > 0:
            ok = abs(cf["compression"] - cd["compression"]) <= COMPRESSION_TOLERANCE * cd["compression"]
        else:
            ok = cf["compression"] == 0
        table.append((scene, f"mean compression, {window}", *percent(cf["compression"], cd["compression"]),
                      f"relative difference <= {100 * COMPRESSION_TOLERANCE:g}%", "pass" if ok else "FAIL"))
        table.append((scene, f"mean speed, {window}", f"{cf['mean_speed']:.3g} m/s", f"{cd['mean_speed']:.3g} m/s",
                      f"{cf['mean_speed'] - cd['mean_speed']:+.2g} m/s ({relative(cf['mean_speed'], cd['mean_speed'])})",
                      "-", "-"))
        table.append((scene, f"largest speed, {window}", f"{cf['max_speed']:.3g} m/s", f"{cd['max_speed']:.3g} m/s",
                      f"{cf['max_speed'] - cd['max_speed']:+.2g} m/s ({relative(cf['max_speed'], cd['max_speed'])})",
                      "-", "-"))
        table.append((scene, "CPU time", f"{cf['cpu']:.2f} s", f"{cd['cpu']:.2f} s",
                      relative(cf["cpu"], cd["cpu"]), "-", "-"))
    return table


def relative(a, b):
    return f"{100 * (a / b - 1):+.1f}%" if b else "n/a"


def percent(a, b):
    """float, double, difference of two fractions shown in %."""
    return f"{100 * a:.4f}%", f"{100 * b:.4f}%", f"{100 * (a - b):+.4f} points ({relative(a, b)})"



def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--float-binary", default=os.path.join(ROOT, "build", "pbfengine"),
                    help="a build with -DPBF_REAL=float (default build/pbfengine)")
    ap.add_argument("--double-binary", default=os.path.join(ROOT, "build-double", "pbfengine"),
                    help="a build with -DPBF_REAL=double (default build-double/pbfengine)")
    ap.add_argument("--quick", action="store_true", help="small, short runs for a smoke test (decide nothing)")
    ap.add_argument("--no-wcsph", action="store_true", help="leave out the WCSPH column")
    ap.add_argument("--out", metavar="FILE", help="write the table as a Markdown report section to FILE")
    args = ap.parse_args()
    binaries = {"float": os.path.abspath(args.float_binary), "double": os.path.abspath(args.double_binary)}
    for name, path in binaries.items():
        if not os.path.isfile(path) or not os.access(path, os.X_OK):
            fail(f"--{name}-binary {path}: no such executable (build it, or give --{name}-binary)")
    precision = {name: precision_of(path) for name, path in binaries.items()}
    for name in binaries:
        if precision[name] not in (name, "unknown"):
            print(f"{PROG}: warning: --{name}-binary {binaries[name]} comes from a {precision[name]} build "
                  "(CMakeCache.txt beside it)", file=sys.stderr)
    wcsph = not args.no_wcsph
    engine = Engine()
    results = {}
    start = time.time()
    try:
        with tempfile.TemporaryDirectory(prefix="pbf_precision_") as work:
            for name, path in binaries.items():
                print(f"{PROG}: running the scenes with the {name} binary {path}", file=sys.stderr)
                results[name] = measure(engine, path, args.quick, wcsph, os.path.join(work, name))
    except RunFailed as e:
        fail(str(e))
    wall = time.time() - start
    table = rows(results["float"], results["double"], args.quick, wcsph)
    verdicts = [r for r in table if r[6] != "-"]
    failed = [f"{r[0]}: {r[1]}" for r in verdicts if r[6] != "pass"]
    if failed:
        verdict = (f"**FAIL**: single precision misses {len(failed)} of {len(verdicts)} criteria ("
                   + "; ".join(failed) + ").")
    else:
        verdict = f"**PASS**: single precision meets all {len(verdicts)} criteria."
    if args.quick:
        verdict += " (--quick: a smoke test at small sizes; it decides nothing.)"
    if binaries["float"] == binaries["double"] or precision["float"] == precision["double"] != "unknown":
        verdict += f" Both binaries are {precision['float']} builds: this compares a precision with itself."
    md = ["| scene | quantity | float | double | difference (float - double) | criterion | result |",
          "|---|---|---|---|---|---|---|"]
    md += ["| " + " | ".join(r) + " |" for r in table]
    print("\n".join(md))
    print(f"\n{verdict}")
    print(f"\n{PROG}: {len(engine.commands)} runs, {wall:.0f} s wall", file=sys.stderr)
    if args.out:
        write_report(args, binaries, precision, engine.commands, md, verdict, wall)
        print(f"{PROG}: report written to {args.out}", file=sys.stderr)
    sys.exit(1 if failed else 0)


def write_report(args, binaries, precision, commands, md, verdict, wall):
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    invocation = shlex.join(["/usr/bin/python3", os.path.relpath(os.path.abspath(sys.argv[0]), ROOT)] + sys.argv[1:])
    lines = [f"## Single against double precision{' (--quick)' if args.quick else ''}", "",
             f"Measured {now} on {machine()} by `{invocation}` ({wall:.0f} s wall), one OpenMP thread per run:",
             ""]
    for name, path in binaries.items():
        lines.append(f"- {name}: `{path}` (PBF_REAL = {precision[name]}, from the CMakeCache.txt beside it)")
    lines += ["", "The runs, in order (the CSV files lie in a temporary directory):", "", "```sh"]
    lines += [shlex.join(c) for c in commands]
    lines += ["```", "",
              f"Z: the 99.5th percentile of x plus half a spacing, over a, at T = t sqrt(2 g / a); criterion "
              f"|Z_float - Z_double| <= {Z_TOLERANCE}. Column: thermo lines (every 0.1 s) with "
              f"{WINDOW[0]:g} s <= t <= {WINDOW[1]:g} s; the mean compression (mean over particles of "
              f"max(rho/rho0 - 1, 0)) and mean speed averaged over them, the largest speed their maximum; "
              f"criterion: float's compression within {100 * COMPRESSION_TOLERANCE:g}% of double's. CPU time: "
              "user + system seconds of the run.", ""]
    lines += md + ["", verdict, ""]
    try:
        with open(args.out, "w") as f:
            f.write("\n".join(lines))
    except OSError as e:
        fail(f"--out {args.out}: {e.strerror}")


if __name__ == "__main__":
    main()
