#!/usr/bin/env bash
# Solid containers against the analytic box, on two scenes, in three containers that are the
# same box: the `box` fix, a `solid` box primitive, and a `solid` read from
# scenarios/geometry/unit_box.obj. Prints two tables for docs/validation/solids.md:
#  - the hydrostatic column of scenarios/hydrostatic.lua (8,192 particles, 12.5 mm spacing):
#    height (99th percentile of z) and mean compression, averaged over t = 1 to 2 s;
#  - the dam break of share/make_scene.py (33,750 particles, column a = 0.2 m wide and 2a
#    high in the cube L = 1 m): the surge front (99.5th percentile of x plus half a spacing,
#    and the farthest particle) at T = t sqrt(2 g / a) = 1, 2, 3, and the time per step.
#
#   share/validation/solid_box_dambreak.sh [BINARY]     (about two minutes on 2 cores)
#
# The time per step leaves out the set-up ("other (loop, setup)" of the timing table), where
# a solid builds its map once; the map's build time is its own column.
set -euo pipefail
cd "$(dirname "$0")/../.."
exe=${1:-build/pbfengine}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
py=/usr/bin/python3
[ -x "$py" ] || py=python3
# One frame per unit of T: t(T = 1) = 1 / sqrt(2 g / a) = 0.100964 s.
"$py" share/make_scene.py --kind dambreak --particles 33750 --t-final 0.3029 --interval 0.100964 \
  -o "$work/scene.txt" > /dev/null
for walls in box solid mesh; do
  "$exe" run scenarios/hydrostatic.lua -v walls=$walls -v t_end=2 -v csv="$work/column_$walls.csv" --log none \
    > "$work/column_$walls.log" 2>&1
  "$exe" run scenarios/init_file.lua -v init="$work/scene.txt" -v out="$work/$walls" -v walls=$walls \
    --log none > "$work/$walls.log" 2>&1
done
"$py" - "$work" <<'PY'
import glob, math, os, re, sys
work = sys.argv[1]
s = 0.2 / 15  # the lattice spacing: 15 particles across a
def fronts(walls):
    rows = []
    for path in sorted(glob.glob(os.path.join(work, walls, "frame_*.txt")))[1:4]:
        lines = open(path).read().splitlines()[1:]  # line 1: the particle count
        xs = sorted(float(line.split()[0]) for line in lines if line.strip() and not line.startswith("#"))
        k = min(len(xs) - 1, int(math.ceil(0.995 * len(xs))) - 1)
        rows.append((xs[k] + s / 2, xs[-1]))
    return rows
def per_step(walls):  # without the set-up (a solid's map is built then)
    log = open(os.path.join(work, walls + ".log")).read()
    m = re.search(r"Timing: (\d+) steps of (\d+) particles in ([0-9.]+) s", log)
    setup = float(re.search(r"other \(loop, setup\)\s+([0-9.]+)", log).group(1))
    return (float(m.group(3)) - setup) / int(m.group(1))
def map_build(walls):
    m = re.search(r"built in ([0-9.]+) s", open(os.path.join(work, walls + ".log")).read())
    return f"{m.group(1)} s" if m else "-"

def column(walls):
    import csv
    lines = [l for l in open(os.path.join(work, f"column_{walls}.csv")) if not l.startswith("#")]  # "# units: ..."
    rows = [r for r in csv.DictReader(lines) if float(r["time"]) >= 1]
    mean = lambda key: sum(float(r[key]) for r in rows) / len(rows)
    return mean("top"), mean("err.compression")
print("| container | column height (m) | difference from box (spacings of 12.5 mm) | mean compression | relative to box |")
print("|---|---|---|---|---|")
top0, comp0 = column("box")
for walls in ["box", "solid", "mesh"]:
    top, comp = column(walls)
    print(f"| {walls} | {top:.4f} | {(top - top0) / 0.0125:+.3f} | {100 * comp:.3f}% | {100 * (comp / comp0 - 1):+.1f}% |")
print()
base = fronts("box")
print("| container | front at T = 1, 2, 3 (99.5th percentile, m) | difference from box | farthest particle (m) | time per step (ms) | cost / box | map built in |")
print("|---|---|---|---|---|---|---|")
for walls in ["box", "solid", "mesh"]:
    f = fronts(walls)
    diff = ", ".join(f"{100 * (a[0] / b[0] - 1):+.2f}%" for a, b in zip(f, base))
    print(f"| {walls} | {', '.join(f'{a[0]:.4f}' for a in f)} | {diff} | {', '.join(f'{a[1]:.4f}' for a in f)} | "
          f"{1000 * per_step(walls):.1f} | {per_step(walls) / per_step('box'):.2f} | {map_build(walls)} |")
PY
