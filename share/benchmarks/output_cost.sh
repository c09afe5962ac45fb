#!/usr/bin/env bash
# The cost of output at 30,000 particles (docs/performance.md). Builds the dam break and
# writes a restart, then runs the same 100 steps from it once per output style (and once
# without output), `repeats` times (default 3), and prints medians: each style's seconds
# per frame from its timing-table line, the run time it added per frame over the
# baseline, and a restart's size and write and read times.
#
#   share/benchmarks/output_cost.sh [PBFENGINE] [particles] [repeats]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
engine="${1:-$here/../../build/pbfengine}"
particles="${2:-30000}"
repeats="${3:-3}"
out="$(mktemp -d /tmp/pbf-output-cost.XXXXXX)"
run() { "$engine" run "$here/output_cost.lua" -v out="$out" --log-level warn "$@" | grep RESULT; }
echo "# $(date -u +%Y-%m-%d) $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $particles particles"
{
  run -v particles="$particles"
  for r in $(seq "$repeats"); do
    for k in 0 1 2 3 4 5 6 7; do run -v style=$k; done
  done
} > "$out/results"
python3 - "$out/results" <<'PY'
import re, statistics, sys
values, order = {}, []
for line in open(sys.argv[1]):
    m = re.match(r"RESULT (.*?) (wall|fix|write|read) ([0-9.e+-]+) (s/frame|s)(.*)$", line.strip())
    if not m:
        continue
    key = (m.group(1), m.group(2))
    if key not in values:
        order.append(key)
        values[key] = []
    values[key].append(float(m.group(3)))
    if m.group(2) == "write":
        print("restart size:", m.group(5).strip())
med = {k: statistics.median(v) for k, v in values.items()}
base = med[("no output", "wall")]
steps, every = 100, 10
print(f"baseline: {base / steps * 1e3:.2f} ms/step")
print("| output | fix line, ms/frame | run time added, ms/frame |")
print("|---|---|---|")
for name, kind in order:
    if kind == "fix":
        frames = steps // every + (0 if name == "restart fix" else 1)  # dumps also write frame 0
        added = (med[(name, "wall")] - base) / frames
        lo, hi = min(values[(name, "fix")]), max(values[(name, "fix")])
        print(f"| {name} | {med[(name, 'fix')] * 1e3:.2f} ({lo * 1e3:.2f}-{hi * 1e3:.2f}) | {added * 1e3:.2f} |")
print(f"restart write: {med[('restart', 'write')] * 1e3:.2f} ms; read: {med[('restart', 'read')] * 1e3:.2f} ms "
      f"(median of {len(values[('restart', 'read')])})")
PY
rm -rf "$out"
