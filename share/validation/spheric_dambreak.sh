#!/usr/bin/env bash
# SPHERIC benchmark Test 2 (Kleefsman et al. 2005): runs scenarios/spheric_dambreak.lua with
# both solvers at two resolutions each, then compares the water heights at the four gauges
# and the pressures P1-P4 with the MARIN measurements (share/validation/spheric_compare.py):
# arrival times, RMS height errors, the P1 peak. Writes, under OUTDIR:
#   SOLVER_SPACING/probes.csv, thermo.csv, run.log    each run
#   spheric_table.md                                  the tables of docs/validation/spheric.md
#   spheric_heights.png, spheric_pressures.png,
#   spheric_p1_impact.png                             the plots
#
#   share/validation/spheric_dambreak.sh [BINARY] [OUTDIR] [--quick] [--cases "SOLVER:SPACING ..."]
#                                        [--t-end T] [--var NAME=VALUE]... [--reuse]
#
# BINARY defaults to build/pbfengine, OUTDIR to out/spheric (relative paths: from the
# repository root). The default cases are pbf:0.03 pbf:0.02 pbf:0.015 wcsph:0.04 wcsph:0.03, run
# one after another (about 12 minutes on 2 cores, measured 2026-11-26); --quick runs pbf:0.04
# alone (12 s on an idle machine); --cases chooses others; --t-end the simulated time (default 2.02 s);
# --var passes -v NAME=VALUE to every run (e.g. --var probe_offset=0); --reuse keeps a case
# whose run.log already reports its Timing line. Threads: OMP_NUM_THREADS as set (every core
# by default).
# docs/validation/spheric.md was made with
#   share/validation/spheric_dambreak.sh build/pbfengine out/spheric
#   cp out/spheric/spheric_*.png docs/validation/
set -euo pipefail
cd "$(dirname "$0")/../.."
exe=build/pbfengine
outdir=out/spheric
cases="pbf:0.03 pbf:0.02 pbf:0.015 wcsph:0.04 wcsph:0.03"
t_end=2.02
reuse=0
positional=0
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) cases="pbf:0.04" ;;
    --cases) cases="$2"; shift ;;
    --t-end) t_end="$2"; shift ;;
    --var) extra+=(-v "$2"); shift ;;
    --reuse) reuse=1 ;;
    -h|--help) sed -n '2,23p' "$0"; exit 0 ;;
    -*) echo "spheric_dambreak.sh: unknown option $1" >&2; exit 2 ;;
    *)
      if [ $positional -eq 0 ]; then exe="$1"; else outdir="$1"; fi
      positional=$((positional + 1)) ;;
  esac
  shift
done
[ -x "$exe" ] || { echo "spheric_dambreak.sh: no binary at $exe" >&2; exit 2; }
py=/usr/bin/python3
[ -x "$py" ] || py=python3
mkdir -p "$outdir"

labels=()
for c in $cases; do
  solver=${c%%:*}
  spacing=${c##*:}
  dir="$outdir/${solver}_${spacing}"
  mkdir -p "$dir"
  if [ $reuse -eq 1 ] && grep -q "^Timing:" "$dir/run.log" 2>/dev/null; then
    echo "$solver, spacing $spacing: kept ($dir)"
  else
    echo "$solver, spacing $spacing: running ($dir) ..."
    start=$(date +%s)
    "$exe" run scenarios/spheric_dambreak.lua -v solver="$solver" -v spacing="$spacing" -v t_end="$t_end" \
      -v out="$dir" "${extra[@]}" --log none > "$dir/run.log" 2>&1 || { echo "  failed: see $dir/run.log" >&2; tail -3 "$dir/run.log" >&2; exit 1; }
    echo "  done in $(( $(date +%s) - start )) s: $(grep '^spheric' "$dir/run.log")"
  fi
  labels+=("$solver, spacing $spacing m=$dir")
done

"$py" share/validation/spheric_compare.py --out-dir "$outdir" --table "$outdir/spheric_table.md" "${labels[@]}"
