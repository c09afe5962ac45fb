#!/usr/bin/env bash
# Time per step of two pbfengine binaries on one scene, side by side: the dam break of
# `share/make_scene.py --kind dambreak` (33,750 particles by default) run through
# scenarios/init_file.lua for 75 steps, the two binaries alternating, `repeats` times each
# (default 5); prints each run's loop time (the timing table's wall time), the medians and
# their ratio B / A. For a change that must not cost time (a refactoring), or to measure one
# that should save some: build the old commit elsewhere and compare it with build/pbfengine.
#
#   share/benchmarks/compare_step.sh OLD_PBFENGINE NEW_PBFENGINE [repeats] [particles] [threads]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
a="$1"
b="$2"
repeats="${3:-5}"
particles="${4:-33750}"
threads="${5:-2}"
out="$(mktemp -d "${TMPDIR:-/tmp}/pbf-compare-step.XXXXXX")"
trap 'rm -rf "$out"' EXIT
# 75 steps of 2 ms, one frame at the start and one at the end.
python3 "$here/../make_scene.py" --kind dambreak --particles "$particles" --dt 0.002 --interval 0.15 \
  --t-final 0.15 -o "$out/scene.txt" 2> /dev/null
# A binary older than the log file has no --log option.
log_option() { "$1" run --help 2>&1 | grep -q -- "--log " && echo "--log none" || true; }
loop_seconds() {
  # shellcheck disable=SC2046
  "$1" run $(log_option "$1") "$here/../../scenarios/init_file.lua" -v init="$out/scene.txt" -v out="$out/frames" \
    --threads "$threads" 2>&1 | sed -n 's/^Timing: .* in \([0-9.]*\) s$/\1/p'
}
echo "# $(date -u +%Y-%m-%d) $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)," \
  "$particles particles, $threads threads"
for r in $(seq "$repeats"); do
  echo "A $(loop_seconds "$a")"
  echo "B $(loop_seconds "$b")"
done | tee "$out/times"
python3 - "$out/times" <<'PY'
import statistics, sys
times = {"A": [], "B": []}
for line in open(sys.argv[1]):
    name, seconds = line.split()
    times[name].append(float(seconds))
a, b = statistics.median(times["A"]), statistics.median(times["B"])
print(f"median A {a:.3f} s, B {b:.3f} s: B / A = {b / a:.4f}")
PY
