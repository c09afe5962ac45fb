#!/usr/bin/env bash
# The hydrostatic column (scenarios/hydrostatic.lua) for the solver variants docs/physics.md
# compares: one- or two-sided constraint, walls with or without density, two resolutions.
# Writes docs/validation/hydrostatic.md with the date and machine.
#
#   share/validate_hydrostatic.sh [BINARY]      (default build/pbfengine; a few minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-build/pbfengine}
work=$(mktemp -d)
out=docs/validation/hydrostatic.md
t_end=3

run() {  # NAME PARTICLES [VAR=VALUE...]
  local name=$1 n=$2
  shift 2
  local vars=()
  for v in "$@"; do vars+=(-v "$v"); done
  echo "validate_hydrostatic: $name" >&2
  "$exe" run scenarios/hydrostatic.lua -v particles="$n" -v t_end=$t_end -v csv="$work/$name.csv" "${vars[@]}" \
    > "$work/$name.log"
}

run "one-sided, wall density, 8k" 8000
run "one-sided, wall density, 30k" 30000
run "two-sided, wall density, 8k" 8000 one_sided=false
run "one-sided, wall density, scorr_k 0.1, 8k" 8000 scorr_k=0.1
run "8 iterations, 8k" 8000 iterations=8
run "time step halved, 8k" 8000 dt=0.0017857
run "XSPH c 0.05, 8k" 8000 xsph=0.05
run "one-sided, no wall density, 8k" 8000 wall_density=false
run "two-sided, no wall density, 8k" 8000 one_sided=false wall_density=false

{
  echo "# Hydrostatic column: solver variants"
  echo
  echo "Measured $(date -u +%Y-%m-%d) on $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'))"
  echo "by \`share/validate_hydrostatic.sh\`: a column 0.4 m high on a 0.2 m square, at rest at t = 0,"
  echo "run for $t_end s with the pbf defaults (4 iterations, no s_corr) unless the variant says otherwise, XSPH c = 0.01. Statistics over t >= 1 s (after the initial settling)."
  echo "Height: the 99th percentile of z, against its initial value; 'layers lost' divides the loss by the spacing."
  echo
  python3 - "$work" <<'PY'
import csv, glob, os, sys
work = sys.argv[1]
print("| variant | height change | layers lost | mean compression | max rho/rho0 - 1 | mean speed (m/s) | max speed (m/s) |")
print("|---|---|---|---|---|---|---|")
order = ["one-sided, wall density, 8k", "one-sided, wall density, 30k", "two-sided, wall density, 8k",
         "one-sided, wall density, scorr_k 0.1, 8k", "8 iterations, 8k", "time step halved, 8k",
         "XSPH c 0.05, 8k", "one-sided, no wall density, 8k",
         "two-sided, no wall density, 8k"]
for name in order:
    rows = list(csv.DictReader(l for l in open(os.path.join(work, name + ".csv")) if not l.startswith("#")))
    spacing = None
    for line in open(os.path.join(work, name + ".log")):
        if line.startswith("hydrostatic:"):
            spacing = float(line.split("spacing")[1].split()[0])
    top0 = float(rows[0]["top"])
    late = [r for r in rows if float(r["time"]) >= 1.0]
    top = sum(float(r["top"]) for r in late) / len(late)
    comp = sum(float(r["err.compression"]) for r in late) / len(late)
    errmax = max(float(r["err.max"]) for r in late)
    vmax = max(float(r["v.max"]) for r in late)
    vavg = sum(float(r["v.avg"]) for r in late) / len(late)
    print(f"| {name} | {100 * (top / top0 - 1):+.1f}% | {(top0 - top) / spacing:.2f} | {100 * comp:.2f}% | "
          f"{errmax:.3f} | {vavg:.3f} | {vmax:.2f} |")
PY
  echo
  echo "## A free cube in zero gravity"
  echo
  echo "\`share/validation/free_cube.lua\`: 1,000 particles at rest density and at rest, no gravity, no walls;"
  echo "in equilibrium, so nothing should move. After 2 s:"
  echo
  echo "| variant | result |"
  echo "|---|---|"
  for v in "scorr_k=0" "scorr_k=0.0001" "scorr_k=0.001" "scorr_k=0.1" "one_sided=false scorr_k=0" \
           "one_sided=false scorr_k=0.1"; do
    args=()
    for a in $v; do args+=(-v "$a"); done
    echo "| $v | $("$exe" run share/validation/free_cube.lua "${args[@]}" --log-level warn | sed 's/^free_cube: //') |"
  done
} > "$out"
cat "$out"
rm -rf "$work"
