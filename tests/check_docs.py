#!/usr/bin/env python3
"""Checks that what the docs show pbfengine printing is what it prints.

    python3 tests/check_docs.py [--binary build/pbfengine] [--real double|float]
                                [--update [--because REASON] [--ledger FILE]] [--keep] [-v] [FILE.md ...]

Without FILE it reads README.md, share/README.md and every docs/**/*.md but the generated
docs/styles.md (a unit test keeps that one current). Standard library only.

Markers are HTML comments, each alone on its line, right before the fenced block (or, for
`check`, the table) they describe:

<!-- file: NAME -->              the block is a file: written as NAME into the scratch
                                 directory before the checks that follow it run
<!-- file: NAME into=BASE -->    NAME is the file BASE (written before) with this block
                                 inserted before BASE's first line that starts with `pbf.run`
<!-- check: COMMAND; OPTION; ... -->
                                 the block is what `pbfengine COMMAND` prints (COMMAND &&
                                 COMMAND ...: what they print, one after the other)
<!-- check: OPTION; ... -->      the block is a transcript: each line `$ build/pbfengine ARGS`
                                 (or `$ NAME=VALUE ... build/pbfengine ARGS`, or
                                 `$ python3 share/SCRIPT.py ARGS`) is run, and the lines up
                                 to the next `$` line are what it prints
<!-- no-check: REASON -->        the block shows output that cannot be produced here

Options:
  stdout | stderr   compare that stream only (default: both, in the order printed)
  exit N            the exit status every command must end with (default 0; 1 with each)
  head | tail | excerpt
                    the block is the start / the end / a run of consecutive lines of the
                    output (default: all of it)
  grep TEXT         keep only the output lines that contain TEXT
  file PATH         compare with the file PATH (in the scratch directory) that the command,
                    or an earlier check when COMMAND is left out, wrote
  each FILE         FILE (relative to the repository) holds one-line scripts, one a line
                    (blank lines and lines starting with '#' skipped; a script that ends in
                    the Lua comment `-- numbers` prints what the default (single-precision) build
                    prints); each runs alone as
                    `pbfengine run e.lua`, and the block's lines (or, before a table, the
                    cells of column `column N`, each one code span) are the last line of
                    each one's standard error (with stdout: standard output; with grep: the
                    last line that holds TEXT); lines with numbers are compared only in a
                    build of the reference precision (REFERENCE, the default build's)
  setup SCRIPT      with each: run `pbfengine run SCRIPT` (a repository path) first
  column N          with each before a table: the column (1-based) that holds the messages
  mask              compare with every number masked and runs of blanks shrunk (timings)
  numbers           the block's numbers are those of the reference build (assumed of
                    any block that shows a decimal fraction or an exponent)
  log               keep the log file (else the checker adds `--log none` to every run)
  slow              run in the background while the other checks go on

In a block, a line `...` stands for one or more lines left out. Wall-clock figures
(the seconds of the timing table, progress lines, which are left out of the output of a
block that shows none), the thread counts of the first line and
of the --threads limits, and the log file's start time are compared masked wherever they
appear, as are the memory size in messages about memory. A bare (language-less) fenced
block, or one with `$ ` lines, is output: it needs a marker. Blocks tagged with a language
(lua, sh, text, ...) are input and need none. An empty block always fails (--update fills it
with the whole output, to be cut down by hand).

Commands run from a scratch directory under $TMPDIR that holds links to the repository's
scenarios/, share/ and docs/ and build/pbfengine (the binary under test), so paths read as
from the repository root and outputs land in the scratch directory; it is removed at the
end (--keep keeps it). The docs show the numbers of the default build, single precision
(REFERENCE); in a build of the other precision (--real double, or detected from a restart
the binary writes) the blocks with numbers still run, but are not compared.
--update rewrites every block that fails from what was printed (blocks that pass keep
their text), and says what it rewrote; a block whose shape changed must be edited by hand.

The check is a change detector: a changed number in a shown output needs a stated physical
reason before it is updated. Numbers are those compared, so not the masked figures above, nor
a `mask` block's, nor version strings. A block whose numbers changed fails saying how many
and by how much at most, and --update leaves it as it is, unless --because REASON gives the
reason: then it updates it and appends the numbers (old -> new) with the reason, the date and
the commit to the ledger, docs/changed-numbers.md (--ledger FILE: another, as
tests/test_check_docs.py does). Why and how: docs/robustness.md, "The docs check as a change
detector".
"""

import argparse
import datetime
import difflib
import math
import os
import re
import shlex
import shutil
import struct
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass
from pathlib import Path

REFERENCE = "float"  # the precision whose numbers the docs show: the default build's

REPO = Path(__file__).resolve().parent.parent
GENERATED = {"docs/styles.md"}
LEDGER = "docs/changed-numbers.md"  # where --because records the numbers it let change
DEFAULT_BINARY = str(REPO / "build" / "pbfengine")
OPTIONS = {"stdout", "stderr", "exit", "head", "tail", "excerpt", "grep", "file", "each", "setup", "column",
           "mask", "numbers", "log", "slow"}
TIMEOUT = 300  # s per command: a machine shared with other runs can be many times slower

FENCE = re.compile(r"^(\s*)(```+|~~~+)\s*([^`\s]*)")
MARKER = re.compile(r"^\s*<!--\s*(check|file|no-check)\b:?(.*?)-->\s*$")
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
FRACTION = re.compile(r"\d\.\d|\d[eE][-+]?\d")
VERSION = re.compile(r"\b\d+\.\d+\.\d+\b")


# --- comparing --------------------------------------------------------------------------

def mask(line):
    return re.sub(r"\s+", " ", NUMBER.sub("#", line)).strip()


VOLATILE = [
    # The thread count and why it is what it is (the cores this process may use) depend on the machine.
    (re.compile(r"^pbfengine (\S+) on \d+ OpenMP threads? \(.*\)$"), r"pbfengine \1 on # OpenMP threads (#)"),
    (re.compile(r"^threads: \d+ \(.*\)$"), "threads: # (#)"),
    (re.compile(r"from 1 to \d+ \(4 per hardware thread of this machine\)"),
     "from 1 to # (4 per hardware thread of this machine)"),
    (re.compile(r"^started: .*$"), "started: #"),
    (re.compile(r"this machine has [\d.]+ GB"), "this machine has # GB"),
    (re.compile(r"^(Timing: \d+ steps of \d+ particles in )\S+( s)$"), r"\1#\2"),
]


def canonical(lines):
    """The lines as compared: wall-clock and machine-dependent figures masked."""
    out, timing = [], False
    for line in lines:
        line = line.rstrip()
        if line.startswith("Timing: "):
            timing = True
        elif timing and line != "..." and not line.startswith("  "):
            timing = False
        if line.startswith("progress: ") or (timing and line.startswith("  ")
                                             and not line.startswith("  neighbours per particle:")):
            line = mask(line)
        for pattern, replacement in VOLATILE:
            line = pattern.sub(replacement, line)
        out.append(line)
    return out


def align(block, output, mode, same):
    """Indices of the output lines that the block's lines stand for (None for '...'), or
    None when the block does not match. '...' stands for one or more lines; mode head,
    tail or excerpt leaves lines out after, before or around the block."""
    memo = {}
    lead = mode in ("tail", "excerpt")
    trail = mode in ("head", "excerpt")

    def go(i, j):
        key = (i, j)
        if key in memo:
            return memo[key]
        result = None
        if i == len(block):
            result = [] if (j == len(output) or trail) else None
        elif block[i] == "...":
            for k in range(j + 1, len(output) + 1):
                rest = go(i + 1, k)
                if rest is not None:
                    result = [None] + rest
                    break
        elif j < len(output) and same(i, j):
            rest = go(i + 1, j + 1)
            if rest is not None:
                result = [j] + rest
        memo[key] = result
        return result

    starts = range(len(output) + 1) if lead else [0]
    for s in starts:
        found = go(0, s)
        if found is not None:
            return found
    return None


def compare(block, output, mode, masked):
    """(matches, lines to write on --update or None)."""
    if not any(x.startswith("progress: ") for x in block):  # a slow machine's, unless shown
        output = [x for x in output if not x.startswith("progress: ")]
    if not block:  # nothing shown: a failure, and --update fills in the whole output
        return False, list(output)
    cb, co = canonical(block), canonical(output)
    if masked:
        cb, co = [mask(x) if x != "..." else x for x in cb], [mask(x) for x in co]
    if align(block, output, mode, lambda i, j: cb[i] == co[j]) is not None:
        return True, None
    shape_b = [mask(x) if x != "..." else x for x in cb]
    shape_o = [mask(x) for x in co]
    found = align(block, output, mode, lambda i, j: shape_b[i] == shape_o[j])
    if found is not None:
        return False, [block[i] if j is None else output[j] for i, j in enumerate(found)]
    if mode == "all" and "..." not in block:
        return False, list(output)
    return False, None


# --- changed numbers: what --update takes only with a reason ---------------------------

@dataclass
class NumberChange:
    """A number a block shows that the new output changes: on the block's line `offset`
    (0-based among its lines), `old` becomes `new` (None: the number is gone)."""
    offset: int
    old: str
    new: str | None

    def relative(self):
        """|new - old| / |old| (infinite from 0), or None for a number gone."""
        if self.new is None:
            return None
        old, new = float(self.old), float(self.new)
        if old == new:
            return 0.0
        return abs(new - old) / abs(old) if old != 0 else math.inf


def comparable(lines):
    """The lines as the check compares them, less version strings (a release is not a result):
    what is left of their numbers is what needs a reason to change."""
    return [VERSION.sub("", x) for x in canonical(lines)]


def number_changes(shown, new):
    """The numbers of `shown` (a block's lines) that `new` (what --update would write)
    changes or drops, in order. The numbers the check masks (timings, thread counts, ...) are
    not numbers here, nor are those of lines that `new` adds: the docs did not show them."""
    old_lines, new_lines = comparable(shown), comparable(new)
    # Lines first, by their shape (numbers masked), so that a number is paired with the one in
    # its place on the same line, not with an equal one elsewhere.
    lines = difflib.SequenceMatcher(None, [mask(x) for x in old_lines], [mask(x) for x in new_lines],
                                    autojunk=False)
    changes = []
    for tag, i1, i2, j1, j2 in lines.get_opcodes():
        if tag == "insert":
            continue
        old = [(k, x) for k in range(i1, i2) for x in NUMBER.findall(old_lines[k])]
        new = [x for k in range(j1, j2) for x in NUMBER.findall(new_lines[k])]
        if tag == "equal":  # same shape, so as many numbers, in the same places
            changes += [NumberChange(k, a, b) for (k, a), b in zip(old, new) if a != b]
            continue
        # Lines reworded (or dropped): pair their numbers by order within the run of lines.
        numbers = difflib.SequenceMatcher(None, [x for _, x in old], new, autojunk=False)
        for op, a1, a2, b1, b2 in numbers.get_opcodes():
            if op in ("replace", "delete"):
                changes += [NumberChange(old[a][0], old[a][1], new[b1 + a - a1] if b1 + a - a1 < b2 else None)
                            for a in range(a1, a2)]
    return changes


def describe_relative(r):
    return "from 0" if r == math.inf else f"{100 * r:.3g}%"


def summarise_changes(changes):
    """'3 numbers changed, by at most 1.2% (relative)': how many, and how much."""
    def count(n):
        return f"{n} number{'s' if n != 1 else ''}"
    relative = [r for r in (c.relative() for c in changes) if r is not None]
    parts = []
    if relative:
        largest = max(relative)
        how = "one of them from 0" if largest == math.inf else f"by at most {describe_relative(largest)} (relative)"
        parts.append(f"{count(len(relative))} changed, {how}")
    if len(relative) < len(changes):
        parts.append(f"{count(len(changes) - len(relative))} gone")
    return " and ".join(parts)


SHOWN_CHANGES = 8  # the changed numbers listed per block; the rest are counted


def compact_changes(changes):
    """'0.4123 → 0.4131, 12 → 13, ... (+5 more)': the first changes, for one line."""
    text = ", ".join(f"{c.old} → {c.new if c.new is not None else '(gone)'}" for c in changes[:SHOWN_CHANGES])
    if len(changes) > SHOWN_CHANGES:
        text += f", ... (+{len(changes) - SHOWN_CHANGES} more)"
    return text


LEDGER_HEADER = """\
# Changed numbers in the docs

The numbers in outputs the docs show that changed, each with its reason: one row per block
that `tests/check_docs.py --update --because REASON` updated, with the date, the commit it
was made at, the block, its numbers (old → new, the first few) and the reason. Append only,
the newest at the end. The rule and the commands:
[robustness.md](robustness.md#the-docs-check-as-a-change-detector).

| date (UTC) | commit | block | numbers (old → new) | reason |
|---|---|---|---|---|
"""


def current_commit():
    try:
        p = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=REPO, capture_output=True, text=True,
                           timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return "unknown"
    return p.stdout.strip() if p.returncode == 0 and p.stdout.strip() else "unknown"


def append_to_ledger(ledger, entries, reason):
    """Appends a row per (file:line, changes) to the ledger (opened to append: the rows before
    stay as they are), first writing its header if it is new."""
    def cell(text):  # one table cell: no line breaks, no column separators
        return " ".join(text.split()).replace("|", "\\|")
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M")
    commit = current_commit()
    ledger.parent.mkdir(parents=True, exist_ok=True)
    with ledger.open("a+", encoding="utf-8") as f:
        f.seek(0)
        text = f.read()
        if not text.strip():
            f.truncate(0)
            f.write(LEDGER_HEADER)
        elif not text.endswith("\n"):
            f.write("\n")
        for where, changes in entries:
            f.write(f"| {date} | {commit} | {cell(where)} | {cell(compact_changes(changes))}; "
                    f"{cell(summarise_changes(changes))} | {cell(reason)} |\n")


# --- Markdown ---------------------------------------------------------------------------

class Block:
    def __init__(self, path, marker_line, kind, text, start, end, indent, lang, lines, table=False):
        self.path, self.marker_line, self.kind, self.text = path, marker_line, kind, text
        self.lineno = start + 1 if table else start  # the block's first line (a fence or a table row), 1-based
        self.start, self.end, self.indent, self.lang, self.lines, self.table = start, end, indent, lang, lines, table


def parse(path, text):
    """Marked blocks, and the line numbers of output blocks without a marker."""
    lines = text.split("\n")
    blocks, unmarked, errors = [], [], []
    pending = None  # (line index, kind, text) of a marker waiting for its block
    i = 0
    while i < len(lines):
        line = lines[i]
        m = MARKER.match(line)
        if m:
            if pending:
                errors.append(f"{path}:{pending[0] + 1}: marker not followed by a fenced block")
            pending = (i, m.group(1), m.group(2).strip())
            i += 1
            continue
        f = FENCE.match(line)
        if f:
            indent, fence, lang = f.group(1), f.group(2), f.group(3)
            j = i + 1
            while j < len(lines) and not (lines[j].strip().startswith(fence[0] * len(fence))
                                          and lines[j].strip().strip(fence[0]) == ""):
                j += 1
            content = [x[len(indent):] if x.startswith(indent) else x.lstrip() for x in lines[i + 1:j]]
            if pending:
                blocks.append(Block(path, pending[0] + 1, pending[1], pending[2], i + 1, j, indent, lang, content))
                pending = None
            elif not lang or any(x.startswith("$ ") for x in content):
                unmarked.append(i + 1)
            i = j + 1
            continue
        if pending and line.strip().startswith("|") and pending[1] == "check":
            j = i
            while j < len(lines) and lines[j].strip().startswith("|"):
                j += 1
            blocks.append(Block(path, pending[0] + 1, "check", pending[2], i, j, "", "", lines[i:j], table=True))
            pending = None
            i = j
            continue
        if pending and line.strip():
            errors.append(f"{path}:{pending[0] + 1}: marker not followed by a fenced block")
            pending = None
        i += 1
    if pending:
        errors.append(f"{path}:{pending[0] + 1}: marker at the end of the file")
    return lines, blocks, unmarked, errors


def table_cells(row):
    cells = re.split(r"(?<!\\)\|", row.strip())
    return cells[1:-1]


# --- running ----------------------------------------------------------------------------

class Result:
    def __init__(self, code, text):
        self.code, self.text = code, text


class Scratch:
    def __init__(self, binary, keep):
        self.dir = Path(tempfile.mkdtemp(prefix="check_docs."))
        self.keep = keep
        for name in ("scenarios", "share", "docs"):
            (self.dir / name).symlink_to(REPO / name)
        (self.dir / "build").mkdir()
        (self.dir / "build" / "pbfengine").symlink_to(Path(binary).resolve())
        self.env = dict(os.environ, LC_ALL="C")

    def close(self):
        if self.keep:
            print(f"kept {self.dir}")
        else:
            shutil.rmtree(self.dir, ignore_errors=True)

    def argv(self, words, keep_log=False):
        """(environment, argv) of a command line: `build/pbfengine ARGS`, `python3 ...`, or
        bare pbfengine arguments; leading NAME=VALUE words set the environment."""
        env = dict(self.env)
        while words and re.match(r"^[A-Za-z_][A-Za-z0-9_]*=", words[0]):
            name, value = words[0].split("=", 1)
            env[name] = value
            words = words[1:]
        if words and words[0] in ("python3", "/usr/bin/python3"):
            return env, [sys.executable] + words[1:]
        if words and words[0] == "build/pbfengine":
            words = words[1:]
        if words and words[0] == "run" and not keep_log and not any(w == "--log" or w.startswith("--log=")
                                                                      for w in words):
            words = words + ["--log", "none"]
        return env, ["build/pbfengine"] + words

    def run(self, words, stream="both", keep_log=False, background=False):
        env, argv = self.argv(words, keep_log)
        if background:  # beside the foreground runs: one thread, so that no thread spins waiting for a core
            env.update(OMP_NUM_THREADS="1", OMP_WAIT_POLICY="passive")
        try:
            if stream == "both":
                p = subprocess.run(argv, cwd=self.dir, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                   timeout=TIMEOUT)
                return Result(p.returncode, p.stdout.decode(errors="replace"))
            p = subprocess.run(argv, cwd=self.dir, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               timeout=TIMEOUT)
            chosen = p.stdout if stream == "stdout" else p.stderr
            return Result(p.returncode, chosen.decode(errors="replace"))
        except subprocess.TimeoutExpired:
            return Result(None, f"(timed out after {TIMEOUT} s)")


def detect_real(binary):
    """'double' or 'float', from the header of a restart the binary writes."""
    with tempfile.TemporaryDirectory(prefix="check_docs.") as d:
        script = Path(d) / "r.lua"
        script.write_text("pbf.domain{lo = {0, 0, 0}, hi = {1, 1, 1}}\npbf.kernel_radius(0.2)\n"
                          "pbf.lattice{lo = {0, 0, 0}, hi = {0.2, 0.2, 0.2}, spacing = 0.1}\n"
                          "pbf.write_restart('r.restart')\n")
        subprocess.run([str(Path(binary).resolve()), "run", "r.lua", "--log", "none"], cwd=d,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=TIMEOUT)
        data = (Path(d) / "r.restart").read_bytes()
        return "float" if struct.unpack_from("<I", data, 16)[0] == 4 else "double"


# --- the checks -------------------------------------------------------------------------

class Checker:
    def __init__(self, args):
        self.binary = args.binary
        self.real = args.real or detect_real(args.binary)
        self.update = args.update
        self.verbose = args.verbose
        self.keep = args.keep
        self.because = args.because  # the reason that lets --update change numbers, or None
        self.ledger = REPO / args.ledger  # an absolute path stays as it is
        self.ledger_name = args.ledger
        self.accept_options = accept_options(args)
        self.failures = 0
        self.checked = 0
        self.skipped = 0
        self.updated = 0
        self.refused = 0
        self.lock = threading.Lock()
        self.slow_updates = []
        self.number_updates = {}  # block: its number changes that --because lets --update write

    def say(self, text):
        with self.lock:
            print(text, flush=True)

    def fail(self, block, why, expected=None, actual=None, changes=()):
        with self.lock:
            self.failures += 1
            print(f"{block.path}:{block.lineno}: FAIL: {why}")
            if expected is not None:
                for line in difflib.unified_diff(expected, actual, "docs", "pbfengine", lineterm="", n=2):
                    print("    " + line)
            if changes:
                print(f"    these are numbers, a result changed (not wording): {summarise_changes(changes)}:")
                self.print_changes(block, changes)
                print("    updating them needs the physical reason for the change, given with --because:")
                print("      " + self.accept_command(block))
            sys.stdout.flush()

    def refuse(self, block, why, changes):
        """--update without --because meets changed numbers: the block stays as it is."""
        with self.lock:
            self.failures += 1
            self.refused += 1
            print(f"{block.path}:{block.lineno}: NOT UPDATED: {why}, and {summarise_changes(changes)}:")
            self.print_changes(block, changes)
            print("    a changed number needs a stated physical reason; if the change is meant:")
            print("      " + self.accept_command(block))
            sys.stdout.flush()

    @staticmethod
    def print_changes(block, changes):
        """The first changes, one a line: file:line: old → new (relative change)."""
        for c in changes[:SHOWN_CHANGES]:
            r = c.relative()
            how = "gone" if r is None else describe_relative(r) if r else "the same value, written otherwise"
            print(f"      {block.path}:{block.start + 1 + c.offset}: {c.old} → "
                  f"{c.new if c.new is not None else '(gone)'} ({how})")
        if len(changes) > SHOWN_CHANGES:
            print(f"      ... and {len(changes) - SHOWN_CHANGES} more")

    def accept_command(self, block):
        return shlex.join(["python3", "tests/check_docs.py", *self.accept_options, "--update", "--because",
                           "THE PHYSICAL REASON", block.path])

    def report_update(self, block, why, old, new, changes):
        """Says what --update rewrote: the changed numbers, or the lines (wording)."""
        with self.lock:
            self.updated += 1
            if changes:
                print(f"{block.path}:{block.lineno}: updated ({why}): {summarise_changes(changes)}, "
                      f"recorded in {self.ledger_name}:")
                self.print_changes(block, changes)
            else:
                print(f"{block.path}:{block.lineno}: updated ({why}): no number changed:")
                diff = [x for x in difflib.unified_diff(old, new, lineterm="", n=0)
                        if not x.startswith(("---", "+++", "@@"))]
                for line in diff[:2 * SHOWN_CHANGES]:
                    print("      " + line)
                if len(diff) > 2 * SHOWN_CHANGES:
                    print(f"      ... and {len(diff) - 2 * SHOWN_CHANGES} more lines")
            sys.stdout.flush()

    @staticmethod
    def options(text):
        """(command words, {option: value}) of a check marker's text."""
        parts = [p.strip() for p in text.split(";") if p.strip()]
        words, opts = [], {}
        for k, part in enumerate(parts):
            key, _, value = part.partition(" ")
            if key in OPTIONS:
                value = value.strip()
                if key == "grep" and value[:1] in "'\"":
                    value = shlex.split(value)[0]
                opts[key] = value if value else True
            elif k == 0:
                words = shlex.split(part)
            else:
                raise ValueError(f"unknown option '{key}'")
        return words, opts

    def number_bearing(self, block, opts):
        if "numbers" in opts:
            return True
        text = "\n".join(canonical(block.lines))
        return bool(FRACTION.search(VERSION.sub("", text)))

    def check_file_marker(self, scratch, block, written):
        parts = block.text.split()
        if not parts:
            raise ValueError("file: needs a name")
        name, content = parts[0], "\n".join(block.lines) + "\n"
        for extra in parts[1:]:
            key, _, base = extra.partition("=")
            if key != "into" or base not in written:
                raise ValueError(f"file: unknown '{extra}' (into=BASE, BASE a file written before)")
            base_lines = written[base].split("\n")
            at = next((k for k, x in enumerate(base_lines) if x.lstrip().startswith("pbf.run")), None)
            if at is None:
                raise ValueError(f"file: {base} has no line starting with pbf.run")
            content = "\n".join(base_lines[:at] + block.lines + base_lines[at:])
        target = scratch.dir / name
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(content)
        written[name] = content

    def produce(self, scratch, words, opts):
        """The lines a command (or, without one, a file) gives, and the exit status."""
        stream = "stdout" if "stdout" in opts else "stderr" if "stderr" in opts else "both"
        code = None
        text = ""
        commands, current = [], []
        for w in words:  # COMMAND && COMMAND ...: run one after the other, outputs joined
            if w == "&&":
                commands.append(current)
                current = []
            else:
                current.append(w)
        if current:
            commands.append(current)
        for command in commands:
            r = scratch.run(command, stream, keep_log="log" in opts, background="slow" in opts)
            text += r.text
            if code in (None, 0):
                code = r.code
        if "file" in opts:
            path = scratch.dir / opts["file"]
            text = path.read_text(errors="replace") if path.is_file() else f"(no file {opts['file']})"
        lines = text.split("\n")
        if lines and lines[-1] == "":
            lines.pop()
        if "grep" in opts:
            lines = [x for x in lines if opts["grep"] in x]
        return code, [x.rstrip() for x in lines]

    def mode(self, opts):
        return "head" if "head" in opts else "tail" if "tail" in opts else "excerpt" if "excerpt" in opts else "all"

    def check_segments(self, scratch, block, words, opts):
        """Runs the block's command or transcript; returns (ok, new lines or None, message)."""
        expected_exit = int(opts.get("exit", 0))
        if words:
            segments = [(None, words, block.lines)]
        else:
            segments, current = [], None
            for line in block.lines:
                if line.startswith("$ "):
                    current = (line, shlex.split(line[2:]), [])
                    segments.append(current)
                elif current is None:
                    if "file" in opts:
                        segments.append((None, [], block.lines))
                        break
                    return False, None, "a check without a command needs `$ ` lines or a file option", None
                else:
                    current[2].append(line)
            if not segments:
                if "file" not in opts:
                    return False, None, "a check without a command needs `$ ` lines or a file option", None
                segments.append((None, [], block.lines))
        ok, new, why, diff = True, [], [], ([], [])
        for prompt, cmd, expected in segments:
            code, output = self.produce(scratch, cmd, opts)
            if prompt is not None:
                new.append(prompt)
            if cmd and code != expected_exit:
                ok = False
                why.append(f"`{' '.join(cmd)}` exited with {code}, not {expected_exit}")
            same, lines = compare(expected, output, self.mode(opts), "mask" in opts)
            if not same:
                ok = False
                why.append("output differs" + ("" if lines is not None else " (and its shape changed: edit by hand)"))
                diff = (diff[0] + expected, diff[1] + output)
            new.extend(lines if lines is not None else expected)
        return ok, new, "; ".join(why), diff

    def check_each(self, scratch, block, opts):
        expected_exit = int(opts.get("exit", 1))
        if "setup" in opts:
            r = scratch.run(["run", opts["setup"]])
            if r.code != 0:
                return False, None, f"setup {opts['setup']} exited with {r.code}: {r.text.strip()}", None
        scripts = [x for x in (REPO / opts["each"]).read_text().split("\n") if x.strip() and not x.startswith("#")]
        messages = []
        why = []
        stream = "stdout" if "stdout" in opts else "stderr"
        for script in scripts:
            (scratch.dir / "e.lua").write_text(script + "\n")
            r = scratch.run(["run", "e.lua"], stream)
            if r.code != expected_exit:
                why.append(f"`{script}` exited with {r.code}, not {expected_exit}")
            lines = [x.rstrip() for x in r.text.split("\n") if x.strip() and opts.get("grep", "") in x]
            messages.append(lines[-1] if lines else "")
        if block.table:
            col = int(opts.get("column", 0)) - 1
            rows = block.lines[2:]
            shown = []
            for row in rows:
                cells = table_cells(row)
                cell = cells[col].strip() if 0 <= col < len(cells) else ""
                if not (cell.startswith("`") and cell.endswith("`")):
                    return False, None, f"table column {col + 1} must hold one code span per row", None
                shown.append(cell[1:-1])
        else:
            shown = block.lines
        if len(shown) != len(scripts):
            if block.table:
                return False, None, f"{len(scripts)} scripts in {opts['each']} but {len(shown)} rows", None
            return False, messages, f"{len(scripts)} scripts in {opts['each']} but {len(shown)} messages shown", None
        if self.real != REFERENCE:  # lines with numbers of the reference build, or so marked: not compared
            keep = [k for k, x in enumerate(shown) if not FRACTION.search(VERSION.sub("", x))
                    and not scripts[k].rstrip().endswith("-- numbers") and "numbers" not in opts]
            ok = [canonical(shown)[k] for k in keep] == [canonical(messages)[k] for k in keep] and not why
            self.skipped += len(shown) - len(keep)
            # --update writes the skipped lines as shown: this build's numbers are not the docs'
            messages = [messages[k] if k in keep else shown[k] for k in range(len(shown))]
        else:
            ok = canonical(shown) == canonical(messages) and not why
        if block.table:
            new = list(block.lines[:2])
            for row, message in zip(block.lines[2:], messages):
                cells = re.split(r"(?<!\\)(\|)", row)
                # cells alternate text, '|'; the data cells are at even positions from 2
                k = 2 * (col + 1)
                cells[k] = f" `{message}` "
                new.append("".join(cells))
        else:
            new = messages
        return ok, new, "; ".join(why) or ("messages differ" if not ok else ""), (shown, messages)

    @staticmethod
    def self_contained(words):
        """Whether a command reads only the repository's files, not those the document's
        earlier blocks write: then a slow check can start with the document."""
        paths = [w for w in words[1:] if w.endswith(".lua")]
        return bool(words) and words[0] == "run" and "&&" not in words and all(
            p.startswith(("docs/", "scenarios/")) for p in paths)

    def start_slow(self, scratch, block, words, opts, background):
        def slow():
            new = self.run_check(scratch, block, words, opts)
            if new is not None:
                with self.lock:
                    self.slow_updates.append((block, new))
        t = threading.Thread(target=slow)
        t.start()
        background.append(t)

    def check_block(self, scratch, block, written, background, started=()):
        if block.kind == "no-check":
            if not block.text:
                self.fail(block, "no-check needs a reason")
            return None
        if block.kind == "file":
            self.check_file_marker(scratch, block, written)
            return None
        words, opts = self.options(block.text)
        if "slow" in opts:
            if block not in started:
                self.start_slow(scratch, block, words, opts, background)
            return None
        return self.run_check(scratch, block, words, opts)

    def run_check(self, scratch, block, words, opts):
        start = time.monotonic()
        try:
            return self.run_check_timed(scratch, block, words, opts)
        finally:
            if self.verbose:
                self.say(f"{block.path}:{block.lineno}: {time.monotonic() - start:.1f} s")

    def run_check_timed(self, scratch, block, words, opts):
        if "each" in opts:
            ok, new, why, diff = self.check_each(scratch, block, opts)
        else:
            if block.table:
                self.fail(block, "a table can only be checked with each")
                return None
            ok, new, why, diff = self.check_segments(scratch, block, words, opts)
        bearing = self.number_bearing(block, opts) and "each" not in opts
        with self.lock:
            if ok:
                self.checked += 1
                if self.verbose:
                    print(f"{block.path}:{block.lineno}: ok")
                return None
            if self.real != REFERENCE and bearing:
                self.skipped += 1
                if self.verbose:
                    print(f"{block.path}:{block.lineno}: skipped (numbers of a {REFERENCE}-precision build)")
                return None
        # The docs check is a change detector: numbers the block shows may change only for a
        # stated reason. Those a `mask` block shows are masked (timings): they may change.
        changes = [] if new is None or "mask" in opts else number_changes(block.lines, new)
        if self.update and new is not None:
            if changes and not self.because:
                self.refuse(block, why, changes)
                return None
            self.report_update(block, why, block.lines, new, changes)
            if "exited with" in why or "edit by hand" in why:  # what --update cannot mend
                self.fail(block, why, *(diff or (None, None)))
            if changes:
                with self.lock:
                    self.number_updates[block] = changes
            return new
        self.fail(block, why, *(diff or (None, None)), changes=changes)
        return None

    def check_document(self, rel):
        path = REPO / rel
        text = path.read_text()
        lines, blocks, unmarked, errors = parse(rel, text)
        for e in errors:
            self.failures += 1
            print(f"{e}: FAIL")
        for n in unmarked:
            self.failures += 1
            print(f"{rel}:{n}: FAIL: an output block without a marker (<!-- check: ... -->, or "
                  f"<!-- no-check: REASON -->; input blocks name their language)")
        if not blocks:
            return
        scratch = Scratch(self.binary, self.keep)
        written, background, updates = {}, [], []
        started = []
        try:
            for block in blocks:  # slow checks of the repository's own scripts start at once
                if block.kind == "check":
                    try:
                        words, opts = self.options(block.text)
                    except ValueError:
                        continue
                    if "slow" in opts and self.self_contained(words):
                        self.start_slow(scratch, block, words, opts, background)
                        started.append(block)
            for block in blocks:
                try:
                    new = self.check_block(scratch, block, written, background, started)
                except (ValueError, OSError) as e:
                    self.fail(block, str(e))
                    continue
                if new is not None:
                    updates.append((block, new))
            for t in background:
                t.join()
            updates += self.slow_updates
            self.slow_updates = []
        finally:
            scratch.close()
        if updates and self.update:
            for block, new in sorted(updates, key=lambda u: -u[0].start):
                if block.table:
                    lines[block.start:block.end] = new
                else:
                    lines[block.start:block.end] = [block.indent + x if x else x for x in new]
            path.write_text("\n".join(lines))
            self.record_number_updates(updates)

    def record_number_updates(self, updates):
        """Appends the blocks whose numbers --because let change to the ledger, each at its
        line in the file as updated (the blocks above it may have grown or shrunk)."""
        entries, shift = [], 0
        for block, new in sorted(updates, key=lambda u: u[0].start):
            if block in self.number_updates:
                entries.append((f"{block.path}:{block.lineno + shift}", self.number_updates.pop(block)))
            shift += len(new) - (block.end - block.start)
        if entries:
            append_to_ledger(self.ledger, entries, self.because)


def default_documents():
    docs = ["README.md", "share/README.md"] + sorted(str(p.relative_to(REPO)) for p in (REPO / "docs").rglob("*.md"))
    return [d for d in docs if d not in GENERATED and (REPO / d).is_file()]


def accept_options(args):
    """The options of this run that the command accepting a change repeats."""
    words = []
    if args.binary != DEFAULT_BINARY:
        words += ["--binary", args.binary]
    if args.real:
        words += ["--real", args.real]
    if args.ledger != LEDGER:
        words += ["--ledger", args.ledger]
    return words


def run(argv=None):
    """Checks (or updates) the documents; returns the exit status."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("documents", nargs="*", help="Markdown files, relative to the repository (default: all)")
    ap.add_argument("--binary", default=DEFAULT_BINARY)
    ap.add_argument("--real", choices=["double", "float"], help="the binary's precision (default: detected)")
    ap.add_argument("--update", action="store_true",
                    help="rewrite the blocks that fail from the output (numbers only with --because)")
    ap.add_argument("--because", metavar="REASON",
                    help="with --update: the physical reason the numbers changed; lets --update change them "
                         "and records them with it in the ledger")
    ap.add_argument("--ledger", default=LEDGER, metavar="FILE",
                    help=f"where --because records changed numbers (default: {LEDGER}, relative to the repository)")
    ap.add_argument("--keep", action="store_true", help="keep the scratch directories")
    ap.add_argument("-v", "--verbose", action="store_true")
    args = ap.parse_args(argv)
    if args.because is not None and not args.update:
        ap.error("--because goes with --update")
    if args.because is not None and not args.because.strip():
        ap.error("--because needs the reason the numbers changed")
    if not Path(args.binary).is_file():
        sys.exit(f"check_docs.py: error: no binary {args.binary} (give --binary)")
    checker = Checker(args)
    for rel in args.documents or default_documents():
        checker.check_document(rel)
    updates = ""
    if args.update:
        updates = f", {checker.updated} updated, {checker.refused} refused (numbers changed, no --because)"
    print(f"check_docs.py: {checker.checked} blocks match, {checker.skipped} blocks or lines skipped "
          f"({checker.real} build){updates}, {checker.failures} failed")
    return 1 if checker.failures else 0


if __name__ == "__main__":
    sys.exit(run())
