#!/usr/bin/env python3
"""Replays the hostile-input corpus against a pbfengine binary.

    python3 tests/hostile/replay.py --binary build/pbfengine [--group lua] [--jobs 2] [-v]
    python3 tests/hostile/replay.py --binary build/pbfengine --group python --pythonpath build/python

Every group directory beside this script (cli/, lua/, scene/, particles/, restart/, disk/,
mesh/, probes/, python/) holds a manifest, cases.tsv, one case a line, five tab-separated
columns:

    name    command    outcome    expect    setup

command   what follows `pbfengine`, split like a shell line; placeholders: {dir} the group's
          directory, {hostile} this directory, {scratch} the case's scratch directory (also
          the current directory of the run, so relative paths land there).
outcome   refused   exit 1 (or the `exit=` of setup), not killed by a signal, stderr is one
                    line besides any warnings, the error message, and it contains `expect`;
          warned    exit 0 and exactly one line starting with "warning:" that contains
                    `expect`;
          accepted  exit 0 and no "warning:" line;
          double:OUTCOME/float:OUTCOME   the outcome for a double- and a single-precision
                    build (read from the restart the binary writes).
          In every case no "Segmentation fault", "terminate called", "runtime error:",
          "AddressSanitizer", "Assertion" ... anywhere in the output, and no hang: a run
          past its wall-clock timeout fails.
expect    substrings the message must contain: "a && b" both, "a || b" either; "-" none.
          A substring that names no file of the command is looked for in the message with
          those file names taken out (p_cfl_courant_huge.lua names 'courant' already).
          Refused messages outside the cli group must also have the form "FILE: ..." or
          "FILE:LINE: ...".
setup     ';'-separated directives, applied in order:
          exit=N            the exit code of a refusal (command-line errors exit with 2)
          warn=TEXT         a refusal that also prints one warning containing TEXT
          raw               do not add the logging options to the command (--log none and
                            --log-level warn, when `pbfengine run --help` lists them)
          multiline         a refusal whose stderr is more than one line (the usage); the
                            expected text may be on any of them
          env=NAME=VALUE    an environment variable for the run (the replay sets
                            OMP_NUM_THREADS=1 and LC_ALL=C unless a case sets them)
          fsize=BYTES       RLIMIT_FSIZE for the run (a full disk); SIGXFSZ is left at its
                            default, so a binary that does not handle it dies of it and fails
          as=BYTES          RLIMIT_AS for the run (K, M, G suffixes), for cases whose broken
                            behaviour would be to allocate without bound (not applied to a
                            sanitizer build, nor with HOSTILE_NO_AS=1 in the environment)
          timeout=SECONDS   the wall-clock limit (default --timeout)
          xfail=REASON      a known defect: the case records the correct outcome, which the
                            engine does not give yet; its failure is reported as "xfail"
                            (not a failure of the replay), and its passing as a failure
                            ("XPASS": remove the marker in gen.py). '\;' for a ';' in REASON
          needs=PROGRAM     skip the case when PROGRAM is not on the PATH (ffmpeg)
          touch=NAME        create an empty regular file NAME in the scratch directory
          mkdir=NAME        create the directory NAME (and its parents) in the scratch directory
          link=NAME:TARGET  create a symbolic link NAME -> TARGET
          repeat=NAME:N:TEXT append TEXT (with \\n, \\r, \\t, \\xHH escapes) N times to NAME
          derive=OP         build d.restart from the base restart (see below), in order
          absent=GLOB       after the run, no file of the scratch directory matches GLOB
          present=GLOB      after the run, at least one file matches GLOB
          then=COMMAND      after the run, COMMAND (same placeholders) must exit 0: e.g. a
                            restart written before a full disk still reads back

Restart derivations (restart/cases.tsv): the replay first runs `run {dir}/make_base.lua` in
a scratch directory of its own, which writes base.restart with the binary under test (so
the corpus serves a double and a float build alike). A case with derive= directives starts
from a copy of it and applies each OP to the bytes, then writes d.restart in its scratch
directory. Offsets: N (from the start), -N (from the end), P% (of the size), or a name of
the layout (engine/io/restart.hpp): version, bom, real_size, crc, payload_size, lo0..lo2,
hi0..hi2, h, dt, rho0, step, step_base, time_base, count, id0, id1, field_count,
field:NAME:C:I (component C of particle I of the saved field NAME), field:NAME:name_len,
field:NAME:components, fix_count, fix:K:id_len, fix:K:size (the K-th saved fix state).
          trunc:OFF           keep the bytes before OFF
          append:N            append N bytes 0xA5
          flip:OFF:BIT        invert bit BIT (0-7) of the byte at OFF
          set:OFF:TYPE:VALUE  store VALUE (a number, nan, inf, -inf) as TYPE (u32, u64, i64,
                              f64, or real: the build's precision) at OFF
          crc                 recompute the payload's CRC-32 (only for semantic cases: a
                              flip must be caught by the CRC, so flips never recompute it)

The python group (python/cases.tsv) runs Python programs against the module (python/,
pbfengine): the command is the program, run by the interpreter of --python (default: the
one running the replay) with --pythonpath (default: the binary's directory's python/, where
the build puts the module) first on PYTHONPATH, in the case's scratch directory, with
PYTHONFAULTHANDLER=1 (a crash prints the Python stack). A program catches nothing: it ends
normally, or with an uncaught exception whose traceback's last entry, "TYPE: message", is
what it raised. Outcomes and `expect` there:
refused   `expect` is "TYPE: text && text ..." (or "TYPE" alone), alternatives separated by
          " || ": the program ends with an uncaught exception whose class is named TYPE
          (module left out: Error is pbfengine.Error, StaleViewError, Interrupted, TypeError,
          ...) and whose message contains every text; a text written "!text" must not be in
          it. Exit status 1, or death by SIGINT after an uncaught KeyboardInterrupt (Python's
          way). "SystemExit: N" is an exit with status N and no traceback.
warned    exit 0 and exactly one warning line ("warning: ..." from the engine, or Python's
          "FILE:LINE: SomeWarning: ...") containing `expect` ("a && b").
accepted  exit 0 and no warning: the program's own asserts passed.
Any signal (but SIGINT as above), a hang, "Fatal Python error", "Exception ignored in" or a
crash marker fails the case. A setup directive more: stdout=TEXT, TEXT must be on stdout.
When the module cannot be imported the python cases fail, or are skipped when the group was
not asked for by name.

The replay prints one line per failing case and a summary, and exits 1 on any failure.
Standard library only.
"""
import argparse
import codecs
import concurrent.futures
import fnmatch
import glob
import os
import re
import resource
import shlex
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
CRASH_MARKERS = ("Segmentation fault", "terminate called", "runtime error:", "AddressSanitizer",
                 "LeakSanitizer", "UndefinedBehaviorSanitizer", "Assertion", "core dumped",
                 "stack smashing", "double free", "free(): invalid", "malloc(): ")
CLI_HINT = "Run with --help for more information."
# The Python group's: a C assert's "Assertion `...' failed", not Python's AssertionError.
PY_CRASH_MARKERS = tuple(m for m in CRASH_MARKERS if m != "Assertion") + (
    "Assertion `", "Fatal Python error", "Exception ignored in")
PY_WARNING = re.compile(r"^(warning: |\S.*:\d+: \w*Warning: )")
FORM = re.compile(r"^[^:\s][^:]*:(\d+:)? ")


class Case:
    def __init__(self, group, name, command, outcome, expect, setup, lineno):
        self.group, self.name, self.command, self.outcome = group, name, command, outcome
        self.expect, self.lineno = expect, lineno
        self.setup = []
        for item in split_setup(setup):
            key, _, value = item.partition("=")
            self.setup.append((key.strip(), value))

    def get(self, key, default=None):
        for k, v in self.setup:
            if k == key:
                return v
        return default

    def all(self, key):
        return [v for k, v in self.setup if k == key]

    @property
    def full(self):
        return f"{self.group}/{self.name}"


def split_setup(text):
    """Directives are ';'-separated; '\\;' is a literal ';' inside one."""
    if text.strip() in ("", "-"):
        return []
    items, cur, i = [], "", 0
    while i < len(text):
        if text[i] == "\\" and i + 1 < len(text) and text[i + 1] == ";":
            cur += ";"
            i += 2
            continue
        if text[i] == ";":
            items.append(cur)
            cur = ""
        else:
            cur += text[i]
        i += 1
    items.append(cur)
    return [s.strip() for s in items if s.strip()]


def load_group(group):
    path = os.path.join(HERE, group, "cases.tsv")
    cases = []
    with open(path, encoding="utf-8") as f:
        for lineno, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if not line.strip() or line.startswith("#"):
                continue
            cols = line.split("\t")
            if len(cols) < 4:
                raise SystemExit(f"{path}:{lineno}: expected 4 or 5 tab-separated columns, found {len(cols)}")
            while len(cols) < 5:
                cols.append("")
            cases.append(Case(group, cols[0], cols[1], cols[2], cols[3], cols[4], lineno))
    names = [c.name for c in cases]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        raise SystemExit(f"{path}: duplicate case names: {', '.join(sorted(dup))}")
    return cases


def parse_size(text):
    text = text.strip()
    mult = {"K": 1 << 10, "M": 1 << 20, "G": 1 << 30}.get(text[-1:].upper(), 1)
    return int(float(text[:-1] if mult > 1 else text) * mult)


def unescape(text):
    return codecs.decode(text.encode("latin-1", "backslashreplace"), "unicode_escape").encode("latin-1")


# ---------------------------------------------------------------- restart derivations

class RestartLayout:
    """Offsets of the named items of a restart file (engine/io/restart.hpp)."""

    def __init__(self, data):
        self.data = data
        self.real = struct.unpack_from("<I", data, 16)[0]
        self.names = {"version": 8, "bom": 12, "real_size": 16, "crc": 20, "payload_size": 24,
                      "h": 80, "dt": 88, "rho0": 96, "step": 104, "step_base": 112, "time_base": 120}
        # Version 2 adds the periodic axes (u32) and the next id (i64) after the clock.
        at = 128
        if struct.unpack_from("<I", data, 8)[0] >= 2:
            self.names.update({"periodic": 128, "next_id": 132})
            at = 140
        self.names.update({"count": at, "id0": at + 8, "id1": at + 16})
        for k in range(3):
            self.names[f"lo{k}"] = 32 + 8 * k
            self.names[f"hi{k}"] = 56 + 8 * k
        n = struct.unpack_from("<Q", data, at)[0]
        p = at + 8 + 8 * n
        self.names["field_count"] = p
        nfields = struct.unpack_from("<I", data, p)[0]
        p += 4
        self.fields = {}
        for _ in range(nfields):
            name_at = p
            length = struct.unpack_from("<Q", data, p)[0]
            name = data[p + 8:p + 8 + length].decode()
            p += 8 + length
            comp_at = p
            comps = struct.unpack_from("<I", data, p)[0]
            p += 4
            self.fields[name] = (name_at, comp_at, p, comps, n)
            p += comps * n * self.real
        self.names["fix_count"] = p
        nfix = struct.unpack_from("<I", data, p)[0]
        p += 4
        self.fixes = []
        for _ in range(nfix):
            id_at = p
            p += 8 + struct.unpack_from("<Q", data, p)[0]
            p += 8 + struct.unpack_from("<Q", data, p)[0]
            size_at = p
            p += 8 + struct.unpack_from("<Q", data, p)[0]
            self.fixes.append((id_at, size_at))

    def offset(self, text, size):
        text = text.strip()
        if text in self.names:
            return self.names[text]
        parts = text.split(":")
        if parts[0] == "field":
            name_at, comp_at, data_at, comps, n = self.fields[parts[1]]
            if parts[2] == "name_len":
                return name_at
            if parts[2] == "components":
                return comp_at
            c, i = int(parts[2]), int(parts[3])
            return data_at + (c * n + i) * self.real
        if parts[0] == "fix":
            id_at, size_at = self.fixes[int(parts[1])]
            return {"id_len": id_at, "size": size_at}[parts[2]]
        if text.endswith("%"):
            return int(size * float(text[:-1]) / 100)
        value = int(text, 0)
        return size + value if value < 0 else value


def derive(base, ops):
    data = bytearray(base)
    layout = RestartLayout(bytes(base))
    for op in ops:
        kind, _, rest = op.partition(":")
        if kind == "trunc":
            del data[layout.offset(rest, len(data)):]
        elif kind == "append":
            data += b"\xa5" * int(rest)
        elif kind == "flip":
            where, bit = rest.rsplit(":", 1)
            data[layout.offset(where, len(data))] ^= 1 << int(bit)
        elif kind == "set":
            where, typ, value = rest.rsplit(":", 2)
            at = layout.offset(where, len(data))
            if typ == "real":
                typ = "f64" if layout.real == 8 else "f32"
            fmt = {"u32": "<I", "u64": "<Q", "i64": "<q", "f64": "<d", "f32": "<f"}[typ]
            num = float(value) if typ.startswith("f") else int(value, 0)
            data[at:at + struct.calcsize(fmt)] = struct.pack(fmt, num)
        elif kind == "crc":
            struct.pack_into("<I", data, 20, zlib.crc32(bytes(data[32:])) & 0xFFFFFFFF)
        else:
            raise ValueError(f"unknown derivation '{op}'")
    return bytes(data)


# ---------------------------------------------------------------- running a case

class Runner:
    def __init__(self, args):
        self.binary = os.path.abspath(args.binary)
        self.timeout = args.timeout
        self.verbose = args.verbose
        self.root = tempfile.mkdtemp(prefix="pbf-hostile-", dir=os.environ.get("TMPDIR") or None)
        self.log_args = self.logging_options()
        self.base = None
        self.base_error = None
        self.precision = None
        # A sanitizer's runtime reserves terabytes of address space: no RLIMIT_AS for it.
        self.no_as = bool(os.environ.get("HOSTILE_NO_AS")) or self.sanitized()
        self.python = args.python
        self.pythonpath = os.path.abspath(args.pythonpath or os.path.join(os.path.dirname(self.binary), "python"))
        self.python_problem = None  # why the module cannot be imported (check_python)
        self.python_optional = False  # skip, rather than fail, the python cases then

    def sanitized(self):
        try:
            with open(self.binary, "rb") as f:
                data = f.read()
        except OSError:
            return False
        return any(tag in data for tag in (b"__asan_init", b"__tsan_init", b"__msan_init", b"__hwasan_init"))

    def logging_options(self):
        try:
            out = subprocess.run([self.binary, "run", "--help"], capture_output=True, text=True,
                                 timeout=30, errors="replace")
            text = out.stdout + out.stderr
        except (OSError, subprocess.TimeoutExpired):
            return []
        opts = []
        if re.search(r"--log(?![-\w])", text):
            opts += ["--log", "none"]
        if "--log-level" in text:
            opts += ["--log-level", "warn"]
        return opts

    def make_base(self):
        """The base restart of the restart group, written by the binary under test."""
        if self.base is not None or self.base_error is not None:
            return
        work = os.path.join(self.root, "_base")
        os.makedirs(work)
        cmd = [self.binary, "run", os.path.join(HERE, "restart", "make_base.lua")] + self.log_args
        try:
            r = subprocess.run(cmd, cwd=work, capture_output=True, text=True, timeout=60,
                               env=self.env(), errors="replace")
        except subprocess.TimeoutExpired:
            self.base_error = "restart/make_base.lua timed out"
            return
        path = os.path.join(work, "base.restart")
        if r.returncode != 0 or not os.path.exists(path):
            self.base_error = (f"restart/make_base.lua failed (exit {r.returncode}): "
                               f"{lines_of(r.stderr.strip())[-1:] or ''}")
            return
        with open(path, "rb") as f:
            self.base = f.read()
        self.precision = {4: "float", 8: "double"}.get(struct.unpack_from("<I", self.base, 16)[0], "unknown")

    def env(self, case=None):
        env = dict(os.environ)
        env["OMP_NUM_THREADS"] = "1"
        env["LC_ALL"] = "C"
        for item in case.all("env") if case else []:
            name, _, value = item.partition("=")
            env[name] = value
        return env

    def expand(self, text, case, scratch):
        return (text.replace("{dir}", shlex.quote(os.path.join(HERE, case.group)))
                .replace("{hostile}", shlex.quote(HERE))
                .replace("{scratch}", shlex.quote(scratch)))

    def argv(self, command, case, scratch, raw):
        words = shlex.split(self.expand(command, case, scratch))
        if not raw and words and words[0] == "run":
            words += self.log_args
        return [self.binary] + words

    def execute(self, argv, scratch, timeout, fsize=None, as_limit=None, env=None):
        # Cases with resource limits run after the parallel ones, from the main thread only
        # (a preexec_fn is not safe beside other threads).
        def limits():
            if fsize is not None:
                resource.setrlimit(resource.RLIMIT_FSIZE, (fsize, fsize))
            if as_limit is not None:
                resource.setrlimit(resource.RLIMIT_AS, (as_limit, as_limit))

        start = time.monotonic()
        proc = subprocess.Popen(argv, cwd=scratch, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, env=env or self.env(),
                                preexec_fn=limits if fsize is not None or as_limit is not None else None,
                                start_new_session=True)
        try:
            out, err = proc.communicate(timeout=timeout)
            hung = False
        except subprocess.TimeoutExpired:
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            out, err = proc.communicate()
            hung = True
        return (proc.returncode, out.decode("utf-8", "replace"), err.decode("utf-8", "replace"), hung,
                time.monotonic() - start)

    def prepare(self, case, scratch):
        ops = case.all("derive")
        if ops:
            self.make_base()
            if self.base is None:
                return self.base_error
            with open(os.path.join(scratch, "d.restart"), "wb") as f:
                f.write(derive(self.base, ops))
        for key, value in case.setup:
            if key == "touch":
                open(os.path.join(scratch, value), "a").close()
            elif key == "mkdir":
                os.makedirs(os.path.join(scratch, value), exist_ok=True)
            elif key == "link":
                name, target = value.split(":", 1)
                os.symlink(target, os.path.join(scratch, name))
            elif key == "repeat":
                name, count, text = value.split(":", 2)
                with open(os.path.join(scratch, name), "ab") as f:
                    f.write(unescape(text) * int(count))
        return None

    def outcome_of(self, case):
        outcome = case.outcome.strip()
        if "/" in outcome or ":" in outcome:
            self.make_base()
            table = dict(part.split(":", 1) for part in outcome.split("/"))
            if self.precision not in table:
                return None
            return table[self.precision]
        return outcome

    def run_case(self, case):
        """Returns (status, detail): status 'pass', 'fail', 'skip' or 'xfail' (a known defect, as
        the case's xfail= says)."""
        if case.group == "python" and self.python_problem:
            return ("skip" if self.python_optional else "fail"), self.python_problem
        status, detail = self.run_one(case)
        reason = case.get("xfail")
        if reason is None or status == "skip":
            return status, detail
        if status == "fail":
            return "xfail", f"known defect: {reason} [now: {detail}]"
        return "fail", f"XPASS: the case passes now; remove its xfail= marker in gen.py (it said: {reason})"

    def run_one(self, case):
        if case.group == "python":
            return self.run_python(case)
        needs = case.get("needs")
        if needs and shutil.which(needs) is None:
            return "skip", f"needs {needs}"
        scratch = os.path.join(self.root, case.group, case.name)
        os.makedirs(scratch)
        problem = self.prepare(case, scratch)
        if problem:
            return "fail", problem
        outcome = self.outcome_of(case)
        if outcome is None:
            return "fail", f"cannot tell the build's precision: {self.base_error or self.precision}"
        raw = any(k == "raw" for k, _ in case.setup)
        timeout = float(case.get("timeout", self.timeout))
        fsize = case.get("fsize")
        as_limit = case.get("as")
        argv = self.argv(case.command, case, scratch, raw)
        rc, out, err, hung, seconds = self.execute(
            argv, scratch, timeout, parse_size(fsize) if fsize else None,
            parse_size(as_limit) if as_limit and not self.no_as else None, self.env(case))
        problems = self.check(case, outcome, rc, out, err, hung, timeout, file_names(argv))
        if not problems:
            problems = self.check_files(case, scratch)
        if not problems:
            for then in case.all("then"):
                rc2, out2, err2, hung2, _ = self.execute(self.argv(then, case, scratch, False), scratch, timeout)
                if hung2 or rc2 != 0 or any(m in out2 + err2 for m in CRASH_MARKERS):
                    last = (lines_of(err2.strip()) or ["(no message)"])[-1]
                    problems.append(f"then-command `{then}` " +
                                    ("hung" if hung2 else f"exited {rc2}: {last}"))
        if problems:
            return "fail", "; ".join(problems)
        shown = [line for line in (lines_of(err.strip()) or [""]) if line.strip()][-1:] or [""]
        warned = [line for line in lines_of(out + err) if line.startswith("warning:")][:1]
        return "pass", f"{seconds:.2f} s, exit {rc}: {(warned + shown)[0][:300]!r}" if (shown[0] or warned) \
            else f"{seconds:.2f} s, exit {rc}"

    # ------------------------------------------------------------ the python group

    def python_env(self, case):
        env = self.env(case)
        env["PYTHONPATH"] = os.pathsep.join(p for p in (self.pythonpath, os.environ.get("PYTHONPATH")) if p)
        env["PYTHONFAULTHANDLER"] = "1"
        env["PYTHONDONTWRITEBYTECODE"] = "1"
        return env

    def check_python(self):
        """Sets python_problem when the interpreter cannot import the module."""
        try:
            r = subprocess.run([self.python, "-c", "import numpy, pbfengine"], capture_output=True, text=True,
                               timeout=120, env=self.python_env(None), errors="replace", stdin=subprocess.DEVNULL)
            last = (lines_of(r.stderr.strip()) or [""])[-1]
            if r.returncode != 0:
                self.python_problem = (f"cannot import pbfengine with {self.python} and PYTHONPATH={self.pythonpath} "
                                       f"(--python, --pythonpath): {last}")
        except (OSError, subprocess.TimeoutExpired) as e:
            self.python_problem = f"cannot run {self.python} (--python): {e}"

    def run_python(self, case):
        scratch = os.path.join(self.root, case.group, case.name)
        os.makedirs(scratch)
        problem = self.prepare(case, scratch)
        if problem:
            return "fail", problem
        timeout = float(case.get("timeout", self.timeout))
        as_limit = case.get("as")
        if as_limit and os.environ.get("HOSTILE_NO_AS"):
            # The limit is the Python process's (the module's sanitizer, if any, cannot load
            # without one of its own): a case that needs it is not run without it.
            return "skip", "needs its address-space limit (HOSTILE_NO_AS is set)"
        argv = [self.python] + shlex.split(self.expand(case.command, case, scratch))
        rc, out, err, hung, seconds = self.execute(
            argv, scratch, timeout, None, parse_size(as_limit) if as_limit else None, self.python_env(case))
        problems = self.check_python_outcome(case, case.outcome.strip(), rc, out, err, hung, timeout)
        if not problems:
            problems = self.check_files(case, scratch)
        if problems:
            return "fail", "; ".join(problems)
        exc = last_exception(err)
        shown = f"{exc[0]}: {exc[1]}" if exc else (lines_of(err.strip()) or [""])[-1]
        return "pass", f"{seconds:.2f} s, exit {rc}" + (f": {shown[:300]!r}" if shown else "")

    def check_python_outcome(self, case, outcome, rc, out, err, hung, timeout):
        if hung:
            return [f"no result within {timeout:g} s (a hang)"]
        problems = []
        both = out + "\n" + err
        crashes = [m for m in PY_CRASH_MARKERS if m in both]
        if crashes:
            problems.append(f"{crashes[0]!r} in the output")
        exc = last_exception(err)
        interrupted = rc == -signal.SIGINT and exc is not None and short_type(exc[0]) == "KeyboardInterrupt"
        got = describe_python(rc, exc, err)
        if rc < 0 and not interrupted:
            name = signal.Signals(-rc).name if -rc in signal.Signals._value2member_map_ else str(-rc)
            return problems + [f"killed by signal {name}" + (f" ({got})" if exc else "")]
        warnings = [line for line in lines_of(both) if PY_WARNING.match(line)]
        for text in case.all("stdout"):
            if text not in out:
                problems.append(f"{text!r} is not on stdout")
        if outcome == "refused":
            if not any(python_matches(alternative, rc, exc, interrupted)
                       for alternative in case.expect.strip().split(" || ")):
                problems.append(f"expected {case.expect.strip()!r}, got {got}")
        else:
            problems += self.check_not_refused(case, outcome, rc, warnings, got)
        return problems

    def check(self, case, outcome, rc, out, err, hung, timeout, names=()):
        problems = []
        if hung:
            return [f"no result within {timeout:g} s (a hang)"]
        got = describe(rc, err)
        both = out + "\n" + err
        crashes = [m for m in CRASH_MARKERS if m in both]
        if crashes:
            problems.append(f"crash marker {crashes[0]!r} in the output")
        if rc < 0:
            name = signal.Signals(-rc).name if -rc in signal.Signals._value2member_map_ else str(-rc)
            return problems + [f"killed by signal {name}"]
        warnings = [line for line in lines_of(both) if line.startswith("warning:")]
        if outcome == "refused":
            want = int(case.get("exit", "1"))
            # Warnings go to stderr too; the `warn=` directive checks them.
            lines = [line for line in lines_of(err)
                     if line.strip() and line.strip() != CLI_HINT and not line.startswith("warning:")]
            if rc != want:
                problems.append(f"expected refused (exit {want}), got {got}")
            elif not lines:
                problems.append(f"exit {rc} without a message on stderr")
            else:
                multiline = any(k == "multiline" for k, _ in case.setup)
                message = "\n".join(lines) if multiline else lines[-1]
                if not multiline and len(lines) != 1:
                    problems.append(f"{len(lines)} lines on stderr, expected one message: {lines[0][:200]!r} ...")
                if not matches(message, case.expect, names):
                    problems.append(f"message does not contain {case.expect!r}: {message[:300]!r}")
                if case.group != "cli" and not FORM.match(message):
                    problems.append(f"message is not 'FILE:LINE: ...': {message[:200]!r}")
            extra = case.get("warn")
            if extra is not None:
                hit = [w for w in warnings if extra in w]
                if len(warnings) != 1 or not hit:
                    problems.append(f"expected one warning containing {extra!r}, got {warnings[:3]!r}")
        else:
            problems += self.check_not_refused(case, outcome, rc, warnings, got, names)
        return problems

    @staticmethod
    def check_not_refused(case, outcome, rc, warnings, got, names=()):
        """What is wrong with a case that should have been warned or accepted."""
        problems = []
        if outcome == "warned":
            if rc != 0:
                problems.append(f"expected warned (exit 0), got {got}")
            if len(warnings) != 1:
                problems.append(f"expected one warning line, got {len(warnings)}: {warnings[:3]!r}")
            elif not matches(warnings[0], case.expect, names):
                problems.append(f"warning does not contain {case.expect!r}: {warnings[0][:300]!r}")
        elif outcome == "accepted":
            if rc != 0:
                problems.append(f"expected accepted (exit 0), got {got}")
            if warnings:
                problems.append(f"expected no warning, got {len(warnings)}: {warnings[0][:300]!r}")
        else:
            problems.append(f"unknown outcome {outcome!r} in the manifest")
        return problems

    def check_files(self, case, scratch):
        problems = []
        for pattern in case.all("absent"):
            hits = glob.glob(os.path.join(scratch, pattern))
            if hits:
                problems.append(f"{os.path.relpath(hits[0], scratch)} exists (a partial file under its final name)")
        for pattern in case.all("present"):
            if not glob.glob(os.path.join(scratch, pattern)):
                problems.append(f"no file matches {pattern}")
        return problems

    def cleanup(self):
        def onerror(func, path, _):
            try:
                os.chmod(os.path.dirname(path), 0o700)
                os.chmod(path, 0o700)
                func(path)
            except OSError:
                pass
        shutil.rmtree(self.root, onerror=onerror)


def lines_of(text):
    """Lines split at '\n' only: a message may hold other control characters."""
    return [line.rstrip("\r") for line in text.split("\n")] if text else []


def describe(rc, err):
    if rc < 0:
        return f"signal {-rc}"
    lines = [line for line in lines_of(err) if line.strip() and line.strip() != CLI_HINT]
    return f"exit {rc}" + (f": {lines[-1][:300]!r}" if lines else "")


def matches(message, expect, names=()):
    """`names`: the file names of the command (a case's script, its data file). The message
    names them anyway, and they often contain the parameter a case is about
    (p_cfl_courant_huge.lua): a part of `expect` that does not name a file must be found in
    the message with those names taken out."""
    expect = expect.strip()
    if expect in ("", "-"):
        return True
    scrubbed = message
    for name in sorted(names, key=len, reverse=True):
        scrubbed = scrubbed.replace(name, "")
    for alternative in expect.split(" || "):
        parts = [part.strip() for part in alternative.split(" && ")]
        if all(part in (message if any(n in part for n in names) else scrubbed) for part in parts):
            return True
    return False


def file_names(argv):
    """The base names of the files a command names: its arguments and -v NAME=PATH values."""
    names = set()
    for word in argv[1:]:
        value = word.split("=", 1)[1] if "=" in word else word
        base = os.path.basename(value)
        if "." in base and len(base) > 4:
            names.add(base)
    return names


EXCEPTION_LINE = re.compile(r"^([A-Za-z_][\w.]*)(?::(?: (.*))?)?$")


def last_exception(err):
    """(class name, message) of the last traceback on stderr, or None. The message runs to the
    end of stderr (pybind11's TypeErrors span several lines)."""
    at = err.rfind("Traceback (most recent call last):")
    if at < 0:
        return None
    lines = lines_of(err[at:])[1:]
    for k, line in enumerate(lines):
        if line and not line[0].isspace():
            m = EXCEPTION_LINE.match(line)
            if not m:
                return None
            rest = "\n".join([m.group(2) or ""] + lines[k + 1:]).strip("\n")
            return m.group(1), rest
    return None


def short_type(name):
    return name.rsplit(".", 1)[-1]


def describe_python(rc, exc, err):
    if exc:
        return f"exit {rc}: {short_type(exc[0])}: {exc[1][:300]!r}"
    lines = [line for line in lines_of(err) if line.strip()]
    return f"exit {rc}" + (f", no exception; stderr ends {lines[-1][:300]!r}" if lines else ", no exception")


def python_matches(alternative, rc, exc, interrupted):
    """One alternative of a refused python case's `expect`: "TYPE: a && !b" or "TYPE"."""
    kind, _, text = alternative.strip().partition(": ")
    kind = kind.strip().rstrip(":")
    if kind == "SystemExit":
        return exc is None and rc == int(text.strip() or "0")
    if exc is None or short_type(exc[0]) != kind or not (rc == 1 or interrupted):
        return False
    for part in (p.strip() for p in text.split(" && ") if p.strip()):
        if part.startswith("!") and len(part) > 1:
            if part[1:] in exc[1]:
                return False
        elif part not in exc[1]:
            return False
    return True


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--binary", required=True, help="the pbfengine binary under test")
    p.add_argument("--group", action="append", help="replay only this group (repeatable)")
    p.add_argument("--case", action="append", help="replay only cases whose name matches this glob")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    p.add_argument("--timeout", type=float, default=10.0, help="wall-clock seconds per run")
    p.add_argument("--keep", action="store_true", help="keep the scratch directory")
    p.add_argument("-v", "--verbose", action="store_true", help="print every case")
    p.add_argument("--python", default=sys.executable,
                   help="the interpreter of the python group's programs (default: this one)")
    p.add_argument("--pythonpath", help="where the module pbfengine is (default: the binary's directory/python)")
    args = p.parse_args()
    if not os.access(args.binary, os.X_OK):
        raise SystemExit(f"replay.py: {args.binary} is not an executable")

    groups = sorted(d for d in os.listdir(HERE) if os.path.isfile(os.path.join(HERE, d, "cases.tsv")))
    if args.group:
        unknown = set(args.group) - set(groups)
        if unknown:
            raise SystemExit(f"replay.py: unknown group(s) {', '.join(sorted(unknown))}; groups: {', '.join(groups)}")
        groups = [g for g in groups if g in args.group]
    cases = [c for g in groups for c in load_group(g)]
    if args.case:
        cases = [c for c in cases if any(fnmatch.fnmatch(c.name, pat) for pat in args.case)]

    runner = Runner(args)
    start = time.monotonic()
    results = {}
    try:
        if any(c.group == "python" for c in cases):
            runner.python_optional = not args.group or "python" not in args.group
            runner.check_python()
            if runner.python_problem:
                print(f"python group: {runner.python_problem}" +
                      (" (its cases skipped)" if runner.python_optional else ""))
        if any(c.all("derive") or "/" in c.outcome for c in cases):
            runner.make_base()  # before the threads start: they only read it
        def one(c):
            try:
                return runner.run_case(c)
            except Exception as e:  # a bug in the replay itself counts as a failure
                return "fail", f"replay error: {type(e).__name__}: {e}"

        limited = [c for c in cases if c.get("fsize") or c.get("as")]
        parallel = [c for c in cases if c not in limited]
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
            for c, result in zip(parallel, pool.map(one, parallel)):
                results[c.full] = result
        for c in limited:
            results[c.full] = one(c)
    finally:
        if args.keep:
            print(f"scratch kept in {runner.root}")
        else:
            runner.cleanup()

    by_group = {}
    for c in cases:
        status, detail = results[c.full]
        g = by_group.setdefault(c.group, {"pass": 0, "fail": 0, "skip": 0, "xfail": 0})
        g[status] += 1
        if status == "fail":
            print(f"FAIL {c.full} ({c.outcome}; cases.tsv:{c.lineno}): {detail}")
        elif status == "xfail" and not args.verbose:
            print(f"xfail {c.full}: {c.get('xfail')}")
        elif args.verbose:
            print(f"{status:4} {c.full}: {detail}")
    total = len(cases)
    failed = sum(g["fail"] for g in by_group.values())
    skipped = sum(g["skip"] for g in by_group.values())
    xfailed = sum(g["xfail"] for g in by_group.values())
    parts = ", ".join(f"{g} {v['fail']}/{sum(v.values())}" for g, v in sorted(by_group.items()))
    precision = f", {runner.precision} build" if runner.precision else ""
    known = f", {xfailed} known defects (xfail)" if xfailed else ""
    print(f"hostile: {total} cases, {total - failed - skipped - xfailed} passed, {failed} failed, {skipped} skipped"
          f"{known} in {time.monotonic() - start:.1f} s{precision}; failed by group: {parts}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
