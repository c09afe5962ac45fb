#!/usr/bin/env bash
# What an emitter and a sink add to a step: the dam break of compare_step.sh (33,750
# particles, 75 steps) without and with a small emitter and a sink (share/benchmarks/flow_cost.lua),
# alternating, `repeats` times each (default 7); prints each run's loop time, the medians and
# their ratio (with / without).
#
#   share/benchmarks/flow_cost.sh [PBFENGINE] [repeats] [particles]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
engine="${1:-$here/../../build/pbfengine}"
repeats="${2:-7}"
particles="${3:-33750}"
out="$(mktemp -d "${TMPDIR:-/tmp}/pbf-flow-cost.XXXXXX")"
trap 'rm -rf "$out"' EXIT
python3 "$here/../make_scene.py" --kind dambreak --particles "$particles" --dt 0.002 --interval 0.15 \
  --t-final 0.15 -o "$out/scene.txt" 2> /dev/null
loop_seconds() {
  "$engine" run --log none "$here/flow_cost.lua" -v init="$out/scene.txt" -v flow="$1" 2>&1 |
    sed -n 's/^Timing: .* in \([0-9.]*\) s$/\1/p'
}
echo "# $(date -u +%Y-%m-%d) $(nproc) cores, $particles particles"
a=() b=()
for ((k = 0; k < repeats; ++k)); do
  a+=("$(loop_seconds 0)"); echo "without $(tail -n1 <<< "${a[-1]}")"
  b+=("$(loop_seconds 1)"); echo "with    $(tail -n1 <<< "${b[-1]}")"
done
median() { printf '%s\n' "$@" | sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
ma=$(median "${a[@]}") mb=$(median "${b[@]}")
echo "median without $ma s, with $mb s: with / without = $(awk -v a="$ma" -v b="$mb" 'BEGIN {printf "%.4f", b / a}')"
