#!/usr/bin/env bash
# The cost of output at 30,000 particles (docs/performance.md): each dump style's seconds
# per frame from the timing table, and the size and write/read time of a restart. Prints
# the RESULT lines; compare variants within one run, as the machine's timings are noisy.
#
#   share/benchmarks/output_cost.sh [PBFENGINE] [particles]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
engine="${1:-$here/../../build/pbfengine}"
particles="${2:-30000}"
out="$(mktemp -d /tmp/pbf-output-cost.XXXXXX)"
echo "# $(date -u +%Y-%m-%d) $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
"$engine" run "$here/output_cost.lua" -v particles="$particles" -v out="$out" --log-level warn | grep RESULT
"$engine" run "$here/output_cost.lua" -v read="$out/bench.restart" --log-level warn | grep RESULT
rm -rf "$out"
