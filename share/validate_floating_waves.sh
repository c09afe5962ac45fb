#!/usr/bin/env bash
# Floating bodies (issue 33): a floating box in regular waves against the experiment of Ren et al.
# (2015): share/validation/floating_waves.lua (a quasi-2D slab flume, second-order piston waves
# H = 0.10 m, T = 1.2 s, depth 0.4 m, the box 1.8 m from the paddle) with WCSPH and PBF at spacing
# 0.02 m (PBF also with the paddle starting 1.5 s earlier), WCSPH with the paddle making H = 0.115 m
# (for 0.10 m at the box's place), DFSPH at 0.02 m, and each solver without the box for the incident
# wave there;
# share/validation/plot_floating_waves.py compares heave, surge and roll with the measured ones.
# Writes docs/validation/floating_waves.md and floating_waves.png, with the date and machine.
#
#   share/validate_floating_waves.sh [BINARY]    (default build/pbfengine; about 75 minutes on 2 threads)
#   FINE=1 share/validate_floating_waves.sh      (also WCSPH at spacing 0.0125 m: hours)
#   WORK=DIR share/validate_floating_waves.sh    (runs in DIR; a run whose DIR/NAME/meta.txt and
#                                                 DIR/NAME.time exist is reused, not run again)
#
# One simulation at a time; OMP_NUM_THREADS as the caller sets it (the report says which).
# The report's "Assessment" section is written by hand after a run: a new run rewrites the file
# without it, and the assessment must be written again from the new numbers.
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-build/pbfengine}
work=${WORK:-$(mktemp -d)}
mkdir -p "$work"
out=docs/validation
mkdir -p "$out"
py=/usr/bin/python3
[ -x "$py" ] || py=python3
script=share/validation/floating_waves.lua
runs=()
nobox=()
commands=()

run() {  # NAME LABEL [VAR=VALUE...]
  local name=$1 label=$2
  shift 2
  local vars=() shown=""
  for v in "$@"; do vars+=(-v "$v"); shown+=" -v $v"; done
  if [ -f "$work/$name/meta.txt" ] && [ -f "$work/$name.time" ]; then
    echo "validate_floating_waves: $label (reused from $work/$name)" >&2
  else
    echo "validate_floating_waves: $label" >&2
    local start=$SECONDS
    "$exe" run "$script" -v out="$work/$name" "${vars[@]}" > "$work/$name.log" 2>&1 || echo "  $label stopped: $(tail -n 1 "$work/$name.log")" >&2
    echo $((SECONDS - start)) > "$work/$name.time"
  fi
  if [ -f "$work/$name/meta.txt" ]; then
    case " $* " in *" box=false "*) nobox+=(--nobox "$work/$name:$label") ;; *) runs+=("$work/$name:$label") ;; esac
  fi
  commands+=("| $label | \`pbfengine run $script$shown\` | $(cat "$work/$name.time") s | $(grep -o 'particle-steps per second: .*' "$work/$name.log" | tail -n 1 | cut -d: -f2) |")
  grep -E "^floating_waves" "$work/$name.log" | sed "s/^/  /" >&2 || true
}

run wcsph "WCSPH, spacing 0.02 m" solver=wcsph
run pbf_settle3 "PBF, spacing 0.02 m, paddle at 3 s" solver=pbf settle=3
run pbf "PBF, spacing 0.02 m, paddle at 1.5 s" solver=pbf
run wcsph_h115 "WCSPH, H = 0.115 m at the paddle" solver=wcsph height=0.115
run wcsph_nobox "WCSPH, no box" solver=wcsph box=false t_end=5
run pbf_nobox "PBF, no box" solver=pbf box=false t_end=5
run dfsph "DFSPH, spacing 0.02 m" solver=dfsph
run dfsph_nobox "DFSPH, no box" solver=dfsph box=false t_end=5
if [ -n "${FINE:-}" ]; then run wcsph_fine "WCSPH, spacing 0.0125 m" solver=wcsph spacing=0.0125; fi

"$py" share/validation/plot_floating_waves.py --png "$out/floating_waves.png" --table "$work/tables.md" "${nobox[@]}" "${runs[@]}"

{
  echo "# A floating box in regular waves (Ren et al. 2015)"
  echo
  echo "Measured $(date -u +%Y-%m-%d) on $(lscpu | grep 'Model name' | sed 's/.*: *//') with OMP_NUM_THREADS=${OMP_NUM_THREADS:-unset},"
  echo "by \`share/validate_floating_waves.sh $exe\` (scripts at $(git rev-parse --short HEAD)), one simulation at a time."
  echo
  echo "**The experiment** (\`../shared/validation/ren_2015_floating_box_motion.csv\`, as DualSPHysics ships it:"
  echo "measured surge, heave and roll every 1/15 s over t = 1.91 to 8.98 s after the paddle's start): a flume"
  echo "0.4 m deep, a piston making second-order Stokes waves H = 0.10 m, T = 1.2 s (linear theory: k = 3.245 1/m,"
  echo "L = 1.94 m, kh = 1.30, c_g = 1.12 m/s); a box 0.30 m long, 0.20 m high and 0.42 m wide (the flume's"
  echo "width), density 500 kg/m^3, floating half submerged with its centre 1.8 m from the paddle, free (no"
  echo "mooring); a 1:3.9 beach from 4.8 m after the paddle."
  echo
  echo "**The model** (\`share/validation/floating_waves.lua\`): a quasi-2D slab 4 spacings wide (0.08 m) whose"
  echo "free-slip y faces are symmetry planes; the box spans the slab, touching both faces, and is held across"
  echo "them (free_translation {1, 0, 1}, free_rotation {0, 1, 0}) with the slab's share of the mass (2.4 kg),"
  echo "its centre of mass 5 mm above the geometric centre (DualSPHysics's case) and a uniform box's inertia about"
  echo "it (Iyy = m (0.3^2 + 0.2^2) / 12). The paddle (a \`solid\` box moved by a Lua function) follows"
  echo "Madsen's (1971) second-order piston motion, X(t) = (S/2) sin(omega t) + X2 sin(2 omega t), S = H / m1 ="
  echo "0.0807 m (Biesel), X2 = H^2/(32 h) (3 cosh kh / sinh^3 kh - 2/m1) = -0.31 mm, no ramp, as in the"
  echo "experiment. The flume is 6.6 m long: flat to x = 4.8 m, then the 1:3.9 beach (a plane \`solid\`, friction"
  echo "20/s) to the domain's end wall. Settling: the fluid alone settles from its lattice for 0.8 s, and"
  echo "gauges away from the box measure the still level (mean over 0.5 to 0.8 s); the box is placed with its"
  echo "geometric centre at that level (a density-500 box's draft), held until 1.0 s, released, and floats to its"
  echo "own level for 0.5 s (2 s with PBF, whose box was still rocking 0.5 s after its release, see below); the"
  echo "paddle starts at 1.5 s (3 s with PBF; time 0 of the outputs), and surge and heave count from"
  echo "the box's position then, roll from its placement. Roll: the body's turn about +y (positive turns z towards"
  echo "x, anticlockwise seen from +y), compared with the measured roll as it stands. WCSPH: kernel radius"
  echo "2.5 spacings, artificial viscosity alpha 0.02, continuity density, no diffusion (the flume's best waves,"
  echo "[wave_flume.md](wave_flume.md)); PBF: 2.5 spacings, 4 iterations, one-sided, XSPH, step 0.025 h /"
  echo "sqrt(g h) (as scenarios/wave_flume.lua). The no-box runs put a gauge at x = 1.8 m for the incident wave."
  echo
  echo "## Runs"
  echo
  echo "| case | command | wall time | particle-steps/s |"
  echo "|---|---|---|---|"
  for c in "${commands[@]}"; do echo "$c"; done
  echo
  echo "## Motions over the measured window"
  echo
  cat "$work/tables.md"
  echo
  echo "![heave, surge and roll against time, simulated and measured; the incident wave at the box's place](floating_waves.png)"
} > "$out/floating_waves.md"
cat "$out/floating_waves.md"
[ -n "${WORK:-}" ] || rm -rf "$work"
