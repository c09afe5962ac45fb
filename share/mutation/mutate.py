#!/usr/bin/env python3
"""Mutation check: plant one known bug at a time in a scratch copy of the repository and see
whether the tests catch it.

Each mutant of share/mutation/mutants.txt replaces one exact piece of one source line (a bug a
physics engine could really have: a sign, a factor of two, an off-by-one); the script builds
the engine with it, runs the tests the list says should catch it, and records whether they
did (killed, and by which tests), did not (survived), or whether the mutant did not compile.
A mutant whose tests pass is a hole in the test suite.

The repository itself is never touched: the check runs in a detached `git worktree` of HEAD
under a temporary directory (so uncommitted changes are not part of it), with one Release
build there reused for every mutant (each rebuild is incremental). Standard library only.

    python3 share/mutation/mutate.py --out docs/mutation.md          # every mutant (hours)
    python3 share/mutation/mutate.py --only grad-sign-simd,visc-laplacian-half
    python3 share/mutation/mutate.py --check                          # the list still applies
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

PROG = "mutate.py"
HERE = Path(__file__).resolve().parent
KEYS = ("file", "find", "replace", "what", "gtest", "ctest")
REQUIRED = ("file", "find", "replace", "what")
TEST_ENV = {"GOMP_SPINCOUNT": "1000", "KMP_BLOCKTIME": "0", "PBF_WAITING": "pbfengine"}


class Failure(Exception):
    """An error that ends the run with one line on stderr."""


# ---------------------------------------------------------------------------------------------
# The list


@dataclass
class Mutant:
    id: str
    line: int  # where it is defined in the list
    file: str = ""
    find: str = ""
    replace: str = ""
    what: str = ""
    gtest: str = ""
    ctest: str = ""


def parse_list(path: Path) -> list[Mutant]:
    """Blocks of `key: value` lines, each opened by `[id]`; `#` lines and blank lines are
    ignored. A value is everything after `key: ` to the end of the line, spaces included."""
    mutants: list[Mutant] = []
    current: Mutant | None = None
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as e:
        raise Failure(f"cannot read the list {path}: {e.strerror}")
    for number, raw in enumerate(text.splitlines(), 1):
        where = f"{path}:{number}"
        if not raw.strip() or raw.lstrip().startswith("#"):
            continue
        m = re.fullmatch(r"\[([A-Za-z0-9][A-Za-z0-9_.-]*)\]\s*", raw)
        if m:
            current = Mutant(id=m.group(1), line=number)
            mutants.append(current)
            continue
        m = re.match(r"([a-z]+):(?: (.*)|)$", raw)
        if not m:
            raise Failure(f"{where}: expected '[id]' or 'key: value', got {raw!r}")
        key, value = m.group(1), m.group(2) or ""
        if current is None:
            raise Failure(f"{where}: '{key}:' before the first '[id]'")
        if key not in KEYS:
            raise Failure(f"{where}: unknown key '{key}' (keys: {', '.join(KEYS)})")
        if getattr(current, key):
            raise Failure(f"{where}: '{key}' given twice for mutant {current.id}")
        setattr(current, key, value)
    seen: dict[str, int] = {}
    for mu in mutants:
        where = f"{path}:{mu.line}"
        if mu.id in seen:
            raise Failure(f"{where}: mutant id {mu.id} already used at line {seen[mu.id]}")
        seen[mu.id] = mu.line
        for key in REQUIRED:
            if not getattr(mu, key) and key != "replace":
                raise Failure(f"{where}: mutant {mu.id} has no '{key}'")
        if mu.find == mu.replace:
            raise Failure(f"{where}: mutant {mu.id} replaces its text by itself")
        if not mu.gtest and not mu.ctest:
            raise Failure(f"{where}: mutant {mu.id} names no test to catch it (gtest: or ctest:)")
        if mu.ctest:
            try:
                re.compile(mu.ctest)
            except re.error as e:
                raise Failure(f"{where}: mutant {mu.id}: ctest regex {mu.ctest!r}: {e}")
    return mutants


def locate(root: Path, mu: Mutant) -> tuple[str, int]:
    """The file's text and the line number of the mutant's text; fails unless it occurs
    exactly once."""
    path = root / mu.file
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as e:
        raise Failure(f"mutant {mu.id}: cannot read {mu.file}: {e.strerror}")
    count = text.count(mu.find)
    if count == 0:
        raise Failure(f"mutant {mu.id}: its text is not in {mu.file} (was the line edited? "
                      f"update share/mutation/mutants.txt): {mu.find!r}")
    if count > 1:
        raise Failure(f"mutant {mu.id}: its text occurs {count} times in {mu.file}; "
                      f"make it longer so it is unique: {mu.find!r}")
    return text, text[: text.index(mu.find)].count("\n") + 1


# ---------------------------------------------------------------------------------------------
# Processes


@dataclass
class Ran:
    rc: int | None  # None: killed at the time limit
    output: str
    seconds: float


def run(cmd: list[str], cwd: Path, timeout: float | None, env: dict | None = None,
        log=None) -> Ran:
    """Runs cmd in its own process group; at the time limit the whole group is killed."""
    start = time.monotonic()
    full_env = dict(os.environ)
    full_env.update(env or {})
    with tempfile.TemporaryFile(mode="w+", encoding="utf-8", errors="replace") as out:
        proc = subprocess.Popen(cmd, cwd=cwd, env=full_env, stdout=out, stderr=subprocess.STDOUT,
                                stdin=subprocess.DEVNULL, start_new_session=True)
        try:
            rc: int | None = proc.wait(timeout=None if timeout is None else max(timeout, 1))
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
            rc = None
        except BaseException:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
            raise
        out.seek(0)
        text = out.read()
    if log is not None:
        log.write(f"$ {shlex.join(cmd)}   (in {cwd})\n{text}\n")
        log.write(f"-> {'timeout' if rc is None else rc} after {time.monotonic() - start:.1f} s\n\n")
        log.flush()
    return Ran(rc, text, time.monotonic() - start)


# ---------------------------------------------------------------------------------------------
# Tests

GTEST_FAILED = re.compile(r"^\[  FAILED  \] ([^\s,]+\.[^\s,]+)", re.M)
GTEST_RUN = re.compile(r"^\[ RUN      \] (\S+)", re.M)
GTEST_OK = re.compile(r"^\[       OK \] (\S+)", re.M)
CTEST_FAILED = re.compile(r"^\s*\d+ - (\S+) \(([^)]*)\)", re.M)


@dataclass
class Outcome:
    killers: list[str] = field(default_factory=list)
    timed_out: bool = False
    ran_nothing: list[str] = field(default_factory=list)  # filters that matched no test


def run_gtest(build: Path, filt: str, timeout: float, log) -> Outcome:
    binary = build / "pbf_tests"
    cmd = [str(binary), f"--gtest_filter={filt}", "--gtest_color=no"]
    ran = run(cmd, build / "tests", timeout, TEST_ENV, log)
    out = Outcome()
    if re.search(r"^\[==========\] 0 tests from", ran.output, re.M):
        out.ran_nothing.append(f"gtest {filt}")
    failed = sorted(set(GTEST_FAILED.findall(ran.output)))
    out.killers += failed
    if ran.rc is None or (ran.rc != 0 and not failed):
        # A hang or a crash: the test that started last and did not finish.
        started = GTEST_RUN.findall(ran.output)
        finished = set(GTEST_OK.findall(ran.output)) | set(failed)
        unfinished = [t for t in started if t not in finished]
        name = unfinished[-1] if unfinished else "pbf_tests"
        if ran.rc is None:
            out.timed_out = True
            out.killers.append(f"{name} (timeout)")
        else:
            how = f"signal {-ran.rc}" if ran.rc < 0 else f"exit {ran.rc}"
            out.killers.append(f"{name} ({how})")
    return out


def run_ctest(build: Path, regex: str | None, jobs: int, timeout: float, log) -> Outcome:
    cmd = ["ctest", "--test-dir", str(build), "--output-on-failure", "-j", str(jobs)]
    if regex is not None:
        cmd += ["-R", regex]
    ran = run(cmd, build, timeout, TEST_ENV, log)
    what = "ctest" if regex is None else f"ctest -R {regex}"
    out = Outcome()
    if "No tests were found" in ran.output:
        out.ran_nothing.append(what)
    for name, why in CTEST_FAILED.findall(ran.output.split("The following tests FAILED:")[-1]
                                          if "The following tests FAILED:" in ran.output else ""):
        out.killers.append(name if why == "Failed" else f"{name} ({why.lower()})")
        if why == "Timeout":
            out.timed_out = True
    if ran.rc is None:
        out.timed_out = True
        out.killers.append(f"{what} (timeout)")
    elif ran.rc != 0 and not out.killers and not out.ran_nothing:
        out.killers.append(f"{what} (exit {ran.rc})")
    return out


def unmatched_patterns(build: Path, filt: str, log) -> list[str]:
    """The positive patterns of a gtest filter that select no test (a misspelt suite)."""
    positive = filt.split("-", 1)[0] if not filt.startswith("-") else ""
    missing = []
    for pattern in filter(None, positive.split(":")):
        ran = run([str(build / "pbf_tests"), f"--gtest_filter={pattern}", "--gtest_list_tests"],
                  build / "tests", 120, TEST_ENV, None)
        if ran.rc != 0 or not re.search(r"^  \S", ran.output, re.M):
            missing.append(pattern)
    return missing


def run_tests(build: Path, mu: Mutant, args, log) -> Outcome:
    deadline = time.monotonic() + args.timeout
    total = Outcome()
    parts: list[tuple[str, str]] = []
    if args.all_tests:
        parts.append(("ctest", ""))
    else:
        if mu.gtest:
            parts.append(("gtest", mu.gtest))
        if mu.ctest:
            parts.append(("ctest", mu.ctest))
    for kind, what in parts:
        left = deadline - time.monotonic()
        if left <= 0:
            total.timed_out = True
            total.killers.append(f"{kind} {what} (not started: the mutant's time ran out)")
            break
        if kind == "gtest":
            o = run_gtest(build, what, left, log)
        else:
            o = run_ctest(build, what or None, args.jobs, left, log)
        total.killers += o.killers
        total.timed_out |= o.timed_out
        total.ran_nothing += o.ran_nothing
        if args.first_kill and total.killers:
            break
    return total


# ---------------------------------------------------------------------------------------------
# The scratch copy and its build


def git(repo: Path, *a: str) -> str:
    r = subprocess.run(["git", "-C", str(repo), *a], capture_output=True, text=True)
    if r.returncode != 0:
        raise Failure(f"git {' '.join(a)}: {r.stderr.strip()}")
    return r.stdout.strip()


def make_scratch(repo: Path, where: Path | None) -> tuple[Path, bool]:
    """A detached worktree of the repository's HEAD (an existing one is moved there); returns
    it and whether this run made it."""
    if where is not None and where.exists():
        if not (where / ".git").exists():
            raise Failure(f"--scratch {where} exists and is not a git worktree")
        dirty = git(where, "status", "--porcelain", "--untracked-files=no")
        if dirty:
            raise Failure(f"--scratch {where} has changes (an interrupted run?): "
                          f"`git -C {where} checkout -- .` restores it")
        git(where, "checkout", "--quiet", "--detach", git(repo, "rev-parse", "HEAD"))  # the repository's HEAD
        return where, False
    if where is None:
        where = Path(tempfile.mkdtemp(prefix="pbf-mutation-")) / "src"
    git(repo, "worktree", "add", "--detach", str(where), "HEAD")
    return where, True


def configure(src: Path, build: Path, log) -> None:
    if (build / "CMakeCache.txt").exists():
        return
    cmd = ["cmake", "-S", str(src), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
           "-DPBF_BUILD_BENCHMARKS=OFF"]
    if shutil.which("ninja"):
        cmd += ["-G", "Ninja"]
    ran = run(cmd, src, None, None, log)
    if ran.rc != 0:
        raise Failure(f"cmake could not configure the scratch build in {build} "
                      f"(its output is in the log)")


def build_targets(build: Path, jobs: int, timeout: float, log) -> Ran:
    return run(["cmake", "--build", str(build), "--target", "pbfengine", "pbf_tests",
                "-j", str(jobs)], build, timeout, None, log)


def compile_commands(build: Path) -> dict:
    """Each engine source's compile command (from the build's compile_commands.json, or
    ninja's), keyed by its path relative to the source root."""
    db = build / "compile_commands.json"
    if not db.exists() and (build / "build.ninja").exists():
        ran = run(["ninja", "-C", str(build), "-t", "compdb"], build, 120, None, None)
        if ran.rc == 0:
            db.write_text(ran.output[ran.output.index("["):] if "[" in ran.output else "[]", encoding="utf-8")
    if not db.exists():
        raise Failure(f"no compile_commands.json in {build} (configure with -G Ninja or "
                      "-DCMAKE_EXPORT_COMPILE_COMMANDS=ON)")
    out: dict = {}
    for entry in json.loads(db.read_text(encoding="utf-8")):
        args = entry.get("arguments") or shlex.split(entry["command"])
        out[str(Path(entry["file"]).resolve())] = (args, entry["directory"])
    return out


def syntax_check(src: Path, build: Path, mu: Mutant, commands: dict, log) -> tuple[bool, str]:
    """Compiles the mutated file (a header: the first engine source that includes it) with
    -fsyntax-only: whether the mutant compiles, without building."""
    target = (src / mu.file).resolve()
    unit = str(target) if str(target) in commands else None
    if unit is None:
        name = f'#include "{mu.file}"'
        for path in sorted(commands):
            try:
                if name in Path(path).read_text(encoding="utf-8", errors="replace"):
                    unit = path
                    break
            except OSError:
                continue
    if unit is None:
        return False, f"no translation unit compiles or includes {mu.file}"
    args, directory = commands[unit]
    cmd, skip = [], False
    for a in args:  # no object, no dependency file: nothing in the build changes
        if skip:
            skip = False
            continue
        if a in ("-o", "-MF", "-MT", "-MQ"):
            skip = True
            continue
        if a in ("-c", "-MD", "-MMD"):
            continue
        cmd.append(a)
    ran = run(cmd + ["-fsyntax-only"], Path(directory), 600, None, log)
    return ran.rc == 0, ("" if ran.rc == 0 else first_error(ran.output))


def first_error(output: str) -> str:
    for line in output.splitlines():
        if "error:" in line:
            return line.strip()[:200]
    return "the build failed (see the log)"


# ---------------------------------------------------------------------------------------------
# The report


def machine() -> str:
    model = ""
    try:
        for line in open("/proc/cpuinfo", encoding="utf-8"):
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    distro = ""
    try:
        for line in open("/etc/os-release", encoding="utf-8"):
            if line.startswith("PRETTY_NAME="):
                distro = line.split("=", 1)[1].strip().strip('"')
    except OSError:
        pass
    cpus = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    parts = [distro or platform.platform(), f"{cpus} cores" + (f" ({model})" if model else "")]
    try:
        mem = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30
        parts.append(f"{mem:.0f} GB of memory")
    except (ValueError, OSError, AttributeError):
        pass
    return ", ".join(parts)


def code(text: str) -> str:
    """Markdown inline code for text that may hold backticks and pipes."""
    text = text.replace("|", "\\|")
    ticks = "``" if "`" in text else "`"
    pad = " " if text.startswith("`") or text.endswith("`") else ""
    return f"{ticks}{pad}{text}{pad}{ticks}" if text else "(nothing)"


@dataclass
class Row:
    mu: Mutant
    where: str
    result: str
    killers: list[str]
    seconds: float


def expected(mu: Mutant, all_tests: bool) -> str:
    parts = []
    if mu.gtest:
        parts.append(f"gtest {code(mu.gtest)}")
    if mu.ctest:
        parts.append(f"ctest -R {code(mu.ctest)}")
    text = "; ".join(parts)
    return text + (" (ran the whole suite)" if all_tests else "")


def cell(text: str) -> str:
    """Text for a table cell: a '|' (|omega|, in code spans too) would end the cell."""
    return text.replace("|", "\\|")


def write_report(path: Path, header: list[str], rows: list[Row], all_tests: bool) -> None:
    lines = list(header)
    lines += ["", "| id | where | mutant | expected killer | result | killing tests | seconds |",
              "|---|---|---|---|---|---|---|"]
    for r in rows:
        mutant = cell(f"{code(r.mu.find)} → {code(r.mu.replace)}: {r.mu.what}")
        killers = ", ".join(code(k) for k in r.killers) if r.killers else "—"
        lines.append(f"| {r.mu.id} | {code(r.where)} | {mutant} | {expected(r.mu, all_tests)} | "
                     f"**{r.result}** | {killers} | {r.seconds:.0f} |")
    counts: dict[str, int] = {}
    for r in rows:
        key = "did not compile" if r.result.startswith("did not") else r.result
        counts[key] = counts.get(key, 0) + 1
    lines += ["", "Totals: " + (", ".join(f"{k} {v}" for k, v in sorted(counts.items())) or "none")
              + f" of {len(rows)}."]
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text("\n".join(lines) + "\n", encoding="utf-8")
    tmp.replace(path)


# ---------------------------------------------------------------------------------------------


def main() -> int:
    ap = argparse.ArgumentParser(
        prog=PROG, description=__doc__.split("\n\n")[0],
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog="The list's format is described at the top of share/mutation/mutants.txt.")
    ap.add_argument("--list", type=Path, default=HERE / "mutants.txt",
                    help="the mutants (default: share/mutation/mutants.txt)")
    ap.add_argument("--only", metavar="ID[,ID]", action="append", default=[],
                    help="run these mutants only (repeatable)")
    ap.add_argument("--all-tests", action="store_true",
                    help="run the whole ctest suite for each mutant instead of its listed tests (slow)")
    ap.add_argument("--first-kill", action="store_true",
                    help="stop a mutant's tests at the first part (gtest, then ctest) that kills it")
    ap.add_argument("--jobs", "-j", type=int, default=os.cpu_count() or 2,
                    help="build jobs and ctest -j (default: the number of cores)")
    ap.add_argument("--timeout", type=float, default=900,
                    help="seconds for one mutant's tests; past it the mutant counts as killed by "
                         "timeout (default 900)")
    ap.add_argument("--build-timeout", type=float, default=1800,
                    help="seconds for one rebuild (default 1800; the first build takes longest)")
    ap.add_argument("--out", type=Path, help="write the Markdown table here (rewritten after each mutant)")
    ap.add_argument("--repo", type=Path, help="the repository (default: the one holding this script)")
    ap.add_argument("--scratch", type=Path,
                    help="the scratch worktree: made if missing and then kept, reused (with its build) "
                         "if it exists; default: a new temporary one, removed at the end")
    ap.add_argument("--keep", action="store_true", help="keep the temporary scratch worktree and its build")
    ap.add_argument("--no-baseline", action="store_true",
                    help="skip running the selected tests on the unmutated build first")
    ap.add_argument("--check", action="store_true",
                    help="only check that every mutant's text occurs once in the repository's working "
                         "tree; build nothing")
    ap.add_argument("--compile-only", action="store_true",
                    help="only check that each mutant compiles (its file, or a source including the header, "
                         "with -fsyntax-only); configures the scratch build but builds and tests nothing")
    ap.add_argument("--list-ids", action="store_true", help="print the ids and descriptions and exit")
    args = ap.parse_args()

    try:
        mutants = parse_list(args.list)
        if args.list_ids:
            for mu in mutants:
                print(f"{mu.id:28} {mu.file}: {mu.what}")
            return 0
        if args.only:
            wanted = [w.strip() for part in args.only for w in part.split(",") if w.strip()]
            known = {mu.id: mu for mu in mutants}
            unknown = [w for w in wanted if w not in known]
            if unknown:
                raise Failure(f"--only: no mutant {', '.join(unknown)} in {args.list}")
            mutants = [known[w] for w in dict.fromkeys(wanted)]
        repo = args.repo or Path(git(HERE, "rev-parse", "--show-toplevel"))
        repo = Path(git(repo, "rev-parse", "--show-toplevel"))

        if args.check:
            for mu in mutants:
                _, line = locate(repo, mu)
                print(f"ok {mu.id:28} {mu.file}:{line}")
            print(f"{len(mutants)} mutants apply to {repo}")
            return 0

        return mutate(args, repo, mutants)
    except Failure as e:
        print(f"{PROG}: error: {e}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted", file=sys.stderr)
        return 130


def compile_only(src: Path, build: Path, mutants: list[Mutant], texts: dict, log) -> int:
    commands = compile_commands(build)
    bad = 0
    for mu in mutants:
        text, line = texts[mu.id]
        path = src / mu.file
        stat = path.stat()
        path.write_text(text.replace(mu.find, mu.replace, 1), encoding="utf-8")
        try:
            t0 = time.monotonic()
            ok, why = syntax_check(src, build, mu, commands, log)
        finally:
            path.write_text(text, encoding="utf-8")
            # The file as it was, its time included: the build need not compile it again.
            os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns))
        bad += not ok
        print(f"{'compiles' if ok else 'DOES NOT COMPILE'}  {mu.id:28} {mu.file}:{line} "
              f"({time.monotonic() - t0:.0f} s){'  ' + why if why else ''}", flush=True)
    print(f"{len(mutants) - bad} of {len(mutants)} mutants compile")
    return 1 if bad else 0


def mutate(args, repo: Path, mutants: list[Mutant]) -> int:
    commit = git(repo, "rev-parse", "--short=12", "HEAD")
    dirty = bool(git(repo, "status", "--porcelain", "--untracked-files=no"))
    src, made = make_scratch(repo, args.scratch)
    remove = made and args.scratch is None and not args.keep
    build = src / "build-mutation"
    log_path = src / "mutation.log" if not remove else Path(tempfile.gettempdir()) / f"pbf-mutation-{os.getpid()}.log"
    print(f"scratch worktree {src} (HEAD {commit}{', the uncommitted changes of the working tree are not in it' if dirty else ''})")
    print(f"log: {log_path}")
    rows: list[Row] = []
    started = time.monotonic()
    date = datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z")
    command = shlex.join(["python3", *sys.argv])
    header = [
        "# Mutation check",
        "",
        f"* date: {date}",
        f"* machine: {machine()}",
        f"* commit: {commit}" + (" (the working tree had uncommitted changes, not checked)" if dirty else ""),
        f"* command: `{command}`",
        f"* tests per mutant: {'the whole ctest suite' if args.all_tests else 'those the list names'}"
        f"; time limit {args.timeout:.0f} s per mutant",
    ]
    try:
        with open(log_path, "a", encoding="utf-8") as log:
            texts = {}
            for mu in mutants:  # before the long build: every mutant must apply
                texts[mu.id] = locate(src, mu)
            configure(src, build, log)
            if args.compile_only:
                return compile_only(src, build, mutants, texts, log)
            print(f"building the unmutated engine and tests in {build} ...", flush=True)
            ran = build_targets(build, args.jobs, args.build_timeout, log)
            if ran.rc != 0:
                raise Failure(f"the unmutated tree does not build: {first_error(ran.output)}")
            print(f"  {ran.seconds:.0f} s", flush=True)

            baseline_failures: set[str] = set()
            if not args.no_baseline and not args.all_tests:
                print("the selected tests on the unmutated build ...", flush=True)
                base = time.monotonic()
                done: set[tuple[str, str]] = set()
                for mu in mutants:
                    if mu.gtest:
                        missing = unmatched_patterns(build, mu.gtest, log)
                        if missing:
                            raise Failure(f"mutant {mu.id}: gtest pattern {', '.join(missing)} matches no test")
                    if (mu.gtest, mu.ctest) in done:  # the same tests as an earlier mutant's
                        continue
                    done.add((mu.gtest, mu.ctest))
                    o = run_tests(build, mu, argparse.Namespace(**{**vars(args), "first_kill": False}), log)
                    for k in o.ran_nothing:
                        raise Failure(f"mutant {mu.id}: {k} matches no test")
                    baseline_failures.update(o.killers)
                print(f"  {time.monotonic() - base:.0f} s"
                      + (f"; failing already: {', '.join(sorted(baseline_failures))}" if baseline_failures else ""),
                      flush=True)
                if baseline_failures:
                    header.append(f"* failing before any mutation (not counted as kills): "
                                  f"{', '.join(code(k) for k in sorted(baseline_failures))}")

            for n, mu in enumerate(mutants, 1):
                text, line = texts[mu.id]
                where = f"{mu.file}:{line}"
                path = src / mu.file
                print(f"[{n}/{len(mutants)}] {mu.id} ({where}): {mu.what}", flush=True)
                log.write(f"===== mutant {mu.id} at {where}: {mu.find!r} -> {mu.replace!r}\n")
                t0 = time.monotonic()
                path.write_text(text.replace(mu.find, mu.replace, 1), encoding="utf-8")
                try:
                    ran = build_targets(build, args.jobs, args.build_timeout, log)
                    built = ran.seconds
                    if ran.rc is None:
                        result, killers = "did not compile (build timeout)", []
                    elif ran.rc != 0:
                        result, killers = "did not compile", [first_error(ran.output)]
                    else:
                        o = run_tests(build, mu, args, log)
                        killers = [k for k in o.killers if k not in baseline_failures]
                        if o.ran_nothing:
                            killers += [f"{k} matched no test" for k in o.ran_nothing]
                        if o.timed_out:
                            result = "killed (timeout)"
                        elif killers and not all(k.endswith("matched no test") for k in killers):
                            result = "killed"
                        else:
                            result = "SURVIVED"
                finally:
                    path.write_text(text, encoding="utf-8")
                seconds = time.monotonic() - t0
                rows.append(Row(mu, where, result, killers, seconds))
                print(f"  {result}" + (f" by {', '.join(killers)}" if killers and result.startswith("killed") else "")
                      + f" ({seconds:.0f} s, the rebuild {built:.0f} s)", flush=True)
                if args.out:
                    write_report(args.out, header + [f"* total time so far: {(time.monotonic() - started) / 60:.0f} min"],
                                 rows, args.all_tests)
        if args.out:
            write_report(args.out, header + [f"* total time: {(time.monotonic() - started) / 60:.0f} min "
                                             "(the first build and the baseline included)"], rows, args.all_tests)
            print(f"wrote {args.out}")
    finally:
        if remove:
            subprocess.run(["git", "-C", str(repo), "worktree", "remove", "--force", str(src)],
                           capture_output=True)
            shutil.rmtree(src.parent, ignore_errors=True)
    survived = sum(r.result == "SURVIVED" for r in rows)
    print(f"{len(rows)} mutants: {sum(r.result.startswith('killed') for r in rows)} killed, "
          f"{survived} survived, {sum(r.result.startswith('did not') for r in rows)} did not compile")
    return 0


if __name__ == "__main__":
    sys.exit(main())
