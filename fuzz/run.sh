#!/usr/bin/env bash
# Builds the fuzz targets (clang's libFuzzer with AddressSanitizer and UndefinedBehavior-
# Sanitizer) and runs each from a copy of its seed corpus: the CI stage (.ci/run, a minute
# each) and longer runs (fuzz/README.md).
#
#   fuzz/run.sh [-t SECONDS] [-j JOBS] [-d DIR] [TARGET...]
#
# TARGET: scene_file restart vtu csv mesh (default: all), JOBS of them at a time (default 1).
#
# Everything is written under DIR (default: a new temporary directory): DIR/build, and for
# each target DIR/TARGET/corpus (the seeds, then what the fuzzer adds), DIR/TARGET/log, and
# any crashing input as DIR/TARGET/crash-* (leak-*, timeout-*, oom-*). The repository is
# only read. Exit status 1 if a target found anything; DIR is then kept, else removed
# (unless given).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=60
jobs=1
dir=""
while getopts "t:j:d:" opt; do
  case $opt in
    t) seconds=$OPTARG ;;
    j) jobs=$OPTARG ;;
    d) dir=$OPTARG ;;
    *) exit 2 ;;
  esac
done
shift $((OPTIND - 1))
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene_file restart vtu csv mesh)
if ! command -v clang++ > /dev/null; then
  echo "fuzz/run.sh: clang++ not found (apt-get install clang libclang-rt-14-dev libomp-14-dev)" >&2
  exit 2
fi
keep=1
if [ -z "$dir" ]; then
  dir=$(mktemp -d "${TMPDIR:-/tmp}/pbf-fuzz.XXXXXX")
  keep=0
fi
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)

echo "fuzz: building the targets in $dir/build"
cmake -S "$root" -B "$dir/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DPBF_FUZZ=ON -DPBF_BUILD_TESTS=OFF > "$dir/configure.log" || { cat "$dir/configure.log"; exit 1; }
cmake --build "$dir/build" -j"$(nproc)" --target fuzz > "$dir/build.log" 2>&1 || { tail -50 "$dir/build.log"; exit 1; }

export UBSAN_OPTIONS=print_stacktrace=1
# One target: its exit status goes to DIR/TARGET/status. The input files the target writes
# go to DIR/TARGET/tmp (fuzz/fuzz_input.hpp). -timeout: an input that takes 10 s is a hang;
# libFuzzer's default 2 GB limit catches allocations sized by garbage.
fuzz_one() {
  local t=$1 work="$dir/$1" status=0
  mkdir -p "$work/corpus" "$work/tmp"
  cp "$root/fuzz/corpus/$t/"* "$work/corpus/"
  (cd "$work" && TMPDIR="$work/tmp" "$dir/build/fuzz_$t" -max_total_time="$seconds" -timeout=10 -max_len=8192 \
     -dict="$root/fuzz/dict/$t.dict" -artifact_prefix="$work/" -print_final_stats=1 corpus) > "$work/log" 2>&1 ||
    status=$?
  echo $status > "$work/status"
}
running=0
for t in "${targets[@]}"; do
  if [ "$running" -ge "$jobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
  echo "fuzz: $t for ${seconds} s"
  fuzz_one "$t" &
  running=$((running + 1))
done
wait

failed=()
for t in "${targets[@]}"; do
  if [ "$(cat "$dir/$t/status")" -ne 0 ]; then
    echo "fuzz: $t found something:"
    tail -60 "$dir/$t/log"
    failed+=("$t")
  else
    echo "fuzz: $t"
    grep -E "^#[0-9]+[[:space:]]+DONE|^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)" \
      "$dir/$t/log" | sed 's/^/  /'
  fi
done

if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: FAILED: ${failed[*]}; inputs and logs are in $dir" >&2
  exit 1
fi
[ $keep -eq 1 ] || rm -rf "$dir"
echo "fuzz: no crash"
