#!/usr/bin/env bash
# Floating bodies (issue 33) against the heave decay of a floating sphere, Kramer et al. (2021):
# share/validation/heave_decay.lua (a quarter model) for H0 = 0.3 D, 0.1 D and 0.5 D with PBF,
# PBF variants for 0.3 D (XSPH off, 10 iterations, half the step, two-sided constraint, a finer
# spacing) and WCSPH for all three (0.3 D at a finer spacing too);
# share/validation/plot_heave_decay.py compares the first trough and crest with the measured
# mean. Writes docs/validation/heave_decay.md and heave_decay.png, with the date and machine.
#
#   share/validate_heave_decay.sh [BINARY]    (default build/pbfengine; about 80 minutes on 1 thread)
#
# One simulation at a time; OMP_NUM_THREADS as the caller sets it (the report says which).
# The report's "Assessment" section is written by hand after a run: a new run rewrites the file
# without it, and the assessment must be written again from the new numbers.
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-build/pbfengine}
work=$(mktemp -d)
out=docs/validation
mkdir -p "$out"
py=/usr/bin/python3
[ -x "$py" ] || py=python3
script=share/validation/heave_decay.lua
runs=()
commands=()

run() {  # NAME LABEL [VAR=VALUE...]
  local name=$1 label=$2
  shift 2
  local vars=() shown=""
  for v in "$@"; do vars+=(-v "$v"); shown+=" -v $v"; done
  echo "validate_heave_decay: $label" >&2
  local start=$SECONDS
  if "$exe" run "$script" -v out="$work/$name" "${vars[@]}" > "$work/$name.log" 2>&1; then
    runs+=("$work/$name:$label")
  else
    echo "  $label stopped: $(tail -n 1 "$work/$name.log")" >&2
  fi
  commands+=("| $label | \`pbfengine run $script$shown\` | $((SECONDS - start)) s | $(grep -o 'particle-steps per second: .*' "$work/$name.log" | tail -n 1 | cut -d: -f2) |")
  grep -E "^heave_decay" "$work/$name.log" | sed "s/^/  /" >&2 || true
}

run pbf_03 "PBF, H0 = 0.3 D" h0=0.3
run wcsph_03 "WCSPH, H0 = 0.3 D, spacing 0.025 m" h0=0.3 solver=wcsph
run pbf_01 "PBF, H0 = 0.1 D" h0=0.1
run pbf_05 "PBF, H0 = 0.5 D" h0=0.5
run pbf_03_noxsph "PBF, H0 = 0.3 D, XSPH off" h0=0.3 xsph=0
run pbf_03_it10 "PBF, H0 = 0.3 D, 10 iterations" h0=0.3 iterations=10
run pbf_03_dt2 "PBF, H0 = 0.3 D, half the step" h0=0.3 dt=0.0017481
run pbf_03_twosided "PBF, H0 = 0.3 D, two-sided constraint" h0=0.3 one_sided=false
run pbf_03_s010 "PBF, H0 = 0.3 D, spacing 0.01 m" h0=0.3 spacing=0.01
run wcsph_01 "WCSPH, H0 = 0.1 D, spacing 0.025 m" h0=0.1 solver=wcsph
run wcsph_05 "WCSPH, H0 = 0.5 D, spacing 0.025 m" h0=0.5 solver=wcsph
run wcsph_03_s020 "WCSPH, H0 = 0.3 D, spacing 0.02 m" h0=0.3 solver=wcsph spacing=0.02

"$py" share/validation/plot_heave_decay.py --png "$out/heave_decay.png" --table "$work/tables.md" "${runs[@]}"

{
  echo "# Heave decay of a floating sphere (Kramer et al. 2021)"
  echo
  echo "Measured $(date -u +%Y-%m-%d) on $(lscpu | grep 'Model name' | sed 's/.*: *//') with OMP_NUM_THREADS=${OMP_NUM_THREADS:-unset},"
  echo "by \`share/validate_heave_decay.sh\` (engine $(git rev-parse --short HEAD)), one simulation at a time."
  echo
  echo "**The experiment** (\`../shared/validation/kramer_2021_sphere_heave_decay_{01D,03D,05D}.csv\`, the"
  echo "mean of 4 repetitions and its 95% band): a sphere D = 0.3 m, mass 7.056 kg, floating half submerged in"
  echo "water of 998.2 kg/m^3 (g = 9.82 m/s^2), 0.9 m deep, released from rest with its centre H0 above"
  echo "equilibrium, heave only. Compared: z(t)/z(0) against t/Te0, Te0 = 0.7561 s; the requirement (issue 33):"
  echo "the first trough and crest within 10% in height and 5% in time of the measured mean."
  echo
  echo "**The model** (\`share/validation/heave_decay.lua\`): a QUARTER model. The sphere's centre stands on"
  echo "the domain corner x = y = 0, where the box's free-slip walls are two symmetry planes, and the body"
  echo "has a quarter of the mass, 1.764 kg (the fluid presses only on the quarter inside the domain)."
  echo "Rest density 998.2 kg/m^3 (\`pbf.rest_density\`), gravity 9.82 m/s^2, heave only"
  echo "(free_translation {0, 0, 1}, free_rotation {0, 0, 0}). The quarter basin is 0.75 x 0.75 m and"
  echo "0.6 m deep, not 0.9 m (deep water for the radiated wave, about 0.9 m long: tanh(2 pi 0.6 / 0.9) = 0.98),"
  echo "with damping zones (fix \`damping\`, rate 10/s) over its last 0.25 m along x and along y so"
  echo "that the radiated wave does not come back. Equilibrium and H0: the fluid settles alone for 0.6 s and"
  echo "the still-water level is measured (compute \`gauge\`, five gauges 0.42 m from the sphere's axis, mean over"
  echo "the last 40%); the sphere is added at the level where it will float half submerged (the level its"
  echo "displacement raises in this finite basin) plus H0 and held 0.4 s while the fluid settles around it;"
  echo "the level measured over the hold's second half gives the equilibrium by volume conservation,"
  echo "z_eq = level_hold + (V_q(0) - V_q(a)) / basin^2 (V_q(a): the quarter sphere's volume below a flat"
  echo "surface with its centre a above it), and H0m = z(0) - z_eq normalises z, as the experiment"
  echo "normalises by each run's measured offset. The fluid's force on the held sphere is compared with"
  echo "rho0 g V_q(a) as a check of the model's buoyancy. Extrema: refined by a parabola through the extreme"
  echo "sample (every 0.004 s) and its neighbours, the measured ones the same way from the CSV (every 0.016 s)."
  echo
  echo "## Runs"
  echo
  echo "| case | command | wall time | particle-steps/s |"
  echo "|---|---|---|---|"
  for c in "${commands[@]}"; do echo "$c"; done
  echo
  echo "## First trough and crest"
  echo
  cat "$work/tables.md"
  echo "![z/H0 against t/Te0, simulated and measured](heave_decay.png)"
} > "$out/heave_decay.md"
cat "$out/heave_decay.md"
rm -rf "$work"
