#!/usr/bin/env bash
# The cost of output at 30,000 particles (docs/performance.md): each dump style's seconds
# per frame from the timing table, and the size and write/read time of a restart. Runs the
# measurement `repeats` times (default 3) and prints each figure's median and range, since
# timings on a shared machine are noisy.
#
#   share/benchmarks/output_cost.sh [PBFENGINE] [particles] [repeats]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
engine="${1:-$here/../../build/pbfengine}"
particles="${2:-30000}"
repeats="${3:-3}"
out="$(mktemp -d /tmp/pbf-output-cost.XXXXXX)"
echo "# $(date -u +%Y-%m-%d) $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
for r in $(seq "$repeats"); do
  "$engine" run "$here/output_cost.lua" -v particles="$particles" -v out="$out" --log-level warn | grep RESULT
  "$engine" run "$here/output_cost.lua" -v read="$out/bench.restart" --log-level warn | grep RESULT
done > "$out/results"
python3 - "$out/results" <<'PY'
import re, statistics, sys
rows = {}
for line in open(sys.argv[1]):
    m = re.match(r"RESULT (.*?) ([0-9.e+-]+) (s/step|s/frame|s)( .*)?$", line.strip())
    if m: rows.setdefault(m.group(1), []).append(float(m.group(2)))
    else: print(line.strip())
for name, values in rows.items():
    print(f"{name}: median {statistics.median(values)*1e3:.2f} ms (range {min(values)*1e3:.2f}-{max(values)*1e3:.2f}, {len(values)} runs)")
PY
rm -rf "$out"
