#!/usr/bin/env bash
# The time per step of variants of one benchmark scene: the dam break of compare_step.sh
# (33,750 particles, 75 steps of 2 ms) run through SCRIPT with -v init=SCENE and -v
# VARIABLE=VALUE for each value, the variants alternating, `repeats` times each (default 7);
# prints each run's loop time (the timing table's wall time), the medians and each median's
# ratio to the first value's.
#
#   share/benchmarks/variant_cost.sh SCRIPT VARIABLE "VALUE1 VALUE2 ..." [PBFENGINE] [repeats] [particles]
#
# share/benchmarks/flow_cost.sh and body_cost.sh call it for their scenes.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
script="$1"
variable="$2"
read -r -a values <<< "$3"
engine="${4:-$here/../../build/pbfengine}"
repeats="${5:-7}"
particles="${6:-33750}"
out="$(mktemp -d "${TMPDIR:-/tmp}/pbf-variant-cost.XXXXXX")"
trap 'rm -rf "$out"' EXIT
python3 "$here/../make_scene.py" --kind dambreak --particles "$particles" --dt 0.002 --interval 0.15 \
  --t-final 0.15 -o "$out/scene.txt" 2> /dev/null
echo "# $(date -u +%Y-%m-%d) $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)," \
  "$particles particles, $(basename "$script") -v $variable"
for ((k = 0; k < repeats; ++k)); do
  for value in "${values[@]}"; do
    seconds=$("$engine" run --log none "$script" -v init="$out/scene.txt" -v "$variable=$value" 2>&1 |
      sed -n 's/^Timing: .* in \([0-9.]*\) s$/\1/p')
    echo "$value $seconds"
  done
done | tee "$out/times"
python3 - "$out/times" "${values[@]}" <<'PY'
import statistics, sys
times = {}
for line in open(sys.argv[1]):
    value, seconds = line.split()
    times.setdefault(value, []).append(float(seconds))
first = statistics.median(times[sys.argv[2]])
for value in sys.argv[2:]:
    m = statistics.median(times[value])
    print(f"median {value}: {m:.3f} s, {m / first:.4f} of {sys.argv[2]}'s")
PY
