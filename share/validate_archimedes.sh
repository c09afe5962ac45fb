#!/usr/bin/env bash
# Archimedes' principle for the floating bodies (issue 33): the box of
# share/validation/archimedes.lua, of relative density 0.25, 0.5 and 0.75, floating in a
# quasi-2D slab, with both solvers, at a / s = 10 and 15 spacings per body height (PBF at 20
# too), 10 s each; and the 0.25 box released 10 mm above and below its expected draft (PBF at
# 10, 15 and 20 spacings, WCSPH at 10).
# Writes docs/validation/archimedes.md (with the date and machine) and
# docs/validation/archimedes.png (share/validation/plot_archimedes.py).
#
#   share/validate_archimedes.sh [BINARY]      (default build/pbfengine; about an hour on 1 core)
#
# Run it with OMP_NUM_THREADS=1 on a shared machine. ARCHIMEDES_WORK=DIR keeps the runs'
# files in DIR, and a later call with the same DIR reuses each run that reached t_end (to
# rewrite the report without running again).
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-build/pbfengine}
if [ -n "${ARCHIMEDES_WORK:-}" ]; then
  work=$ARCHIMEDES_WORK
  mkdir -p "$work"
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi
py=/usr/bin/python3
[ -x "$py" ] || py=python3
out=docs/validation/archimedes.md
t_end=10

run() {  # NAME [VAR=VALUE...]
  local name=$1
  shift
  local vars=()
  for v in "$@"; do vars+=(-v "$v"); done
  if [ -f "$work/$name.seconds" ]; then return; fi  # done in an earlier call (ARCHIMEDES_WORK)
  echo "validate_archimedes: $name" >&2
  local start=$SECONDS
  "$exe" run share/validation/archimedes.lua -v t_end=$t_end -v csv="$work/$name.csv" "${vars[@]}" --log none \
    > "$work/$name.log"
  echo $((SECONDS - start)) > "$work/$name.seconds"
}

for n in 10 15 20; do
  for rel in 0.25 0.5 0.75; do run "pbf_rel${rel}_n$n" solver=pbf rel=$rel n=$n; done
done
for n in 10 15 20; do
  run "pbf_rel0.25_n${n}_high" solver=pbf rel=0.25 n=$n offset=0.01
  run "pbf_rel0.25_n${n}_low" solver=pbf rel=0.25 n=$n offset=-0.01
done
for n in 10 15; do
  for rel in 0.25 0.5 0.75; do run "wcsph_rel${rel}_n$n" solver=wcsph rel=$rel n=$n; done
done
run "wcsph_rel0.25_n10_high" solver=wcsph rel=0.25 n=10 offset=0.01
run "wcsph_rel0.25_n10_low" solver=wcsph rel=0.25 n=10 offset=-0.01

"$py" share/validation/plot_archimedes.py "$work" docs/validation/archimedes.png
{
  echo "# Archimedes: floating boxes"
  echo
  echo "Measured $(date -u +%Y-%m-%d) on $(lscpu | grep -m1 'Model name' | cut -d: -f2 | sed 's/^ *//')"
  echo "($(nproc --all) logical CPUs; OMP_NUM_THREADS=${OMP_NUM_THREADS:-unset}), source tree at $(git rev-parse --short HEAD 2>/dev/null || echo '?'),"
  echo "by \`share/validate_archimedes.sh $exe\`, the scene"
  echo "\`share/validation/archimedes.lua\`: a box a = 0.1 m high and long, of density rel x 1000 kg/m^3,"
  echo "spanning a slab tank 0.4 m long and 0.04 m wide with water 0.16 m deep, free to heave only, held"
  echo "0.5 s while the water settles, then released at its expected draft rel x a (the '10 mm high / low'"
  echo "runs 10 mm above or below it); $t_end s each. PBF: 4 iterations, XSPH c = 0.01, dt = 0.4 h / sqrt(2 g 0.32 m);"
  echo "WCSPH: share/lua/solvers.lua's defaults (Tait, c0 = 10 sqrt(2 g 0.16 m), Monaghan alpha 0.1, fix cfl)."
  echo "Spacing s = a / n, h = 2 s; the tank is a whole number of spacings, so the lattice fills it."
  echo
  echo "Draft: the water level (the mean of twelve gauges, every 2 cm from 3 cm off the tank's ends to"
  echo "4 cm off the body: where the fluid fraction falls to 1/2) less the body's bottom, averaged over"
  echo "6-10 s. Drift: the body's mean centre z over 6-10 s less that over 2-6 s. Oscillation: half the"
  echo "range (peak to peak) of z over 6-10 s. Level spread: the range of the twelve gauges' means over"
  echo "6-10 s (the surface is not flat to better than this). Force: the fluid's mean vertical force over"
  echo "6-10 s against the body's weight m g. Bound: the draft within 3% of rel x a."
  echo
  "$py" - "$work" <<'PY'
import csv, glob, os, re, sys
work = sys.argv[1]
A = 0.1

def load(path):
    rows = list(csv.DictReader(l for l in open(path) if not l.startswith("#")))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}

runs = {}
for path in glob.glob(os.path.join(work, "*.csv")):
    m = re.match(r"(pbf|wcsph)_rel([0-9.]+)_n(\d+)(?:_(\w+))?\.csv$", os.path.basename(path))
    if m:
        runs[(m.group(1), float(m.group(2)), int(m.group(3)), m.group(4) or "")] = (load(path), path[:-4])

def window(d, t0, t1):
    return [i for i, t in enumerate(d["time"]) if t0 <= t < t1 + 1e-9]

def mean(xs):
    return sum(xs) / len(xs)

def stats(key):
    d, stem = runs[key]
    rel = key[1]
    gauges = [k for k in d if k.startswith("g.h")]
    level = [mean([d[k][i] for k in gauges]) for i in range(len(d["time"]))]
    late, mid = window(d, 6, 10), window(d, 2, 6)
    draft = mean([level[i] - (d["b.z"][i] - A / 2) for i in late])
    z = [d["b.z"][i] for i in late]
    weight = float(re.search(r"weight ([0-9.e+-]+) N", open(stem + ".log").read()).group(1))
    return dict(draft=draft, err=100 * (draft / (rel * A) - 1), drift=1000 * (mean(z) - mean([d["b.z"][i] for i in mid])),
                osc=500 * (max(z) - min(z)), spread=1000 * (max(mean([d[k][i] for i in late]) for k in gauges)
                                                          - min(mean([d[k][i] for i in late]) for k in gauges)),
                force=100 * (mean([d["b.fz"][i] for i in late]) / weight - 1),
                comp=100 * mean([d["err.compression"][i] for i in late]),
                seconds=int(open(stem + ".seconds").read()))

def row(key, label=None):
    s = stats(key)
    solver, rel, n, tag = key
    ok = "yes" if abs(s["err"]) <= 3 else "**no**"
    print(f"| {solver.upper()} | {rel:g} | {1000 * A / n:.3g} mm (a/{n}) | {label or '-'} | {1000 * rel * A:.1f} | "
          f"{1000 * s['draft']:.2f} | {s['err']:+.1f}% | {ok} | {s['drift']:+.3f} | {s['osc']:.3f} | "
          f"{s['spread']:.2f} | {s['force']:+.2f}% | {s['comp']:.2f}% | {s['seconds']} |")
    return s

print("| solver | rel. density | spacing | released | expected draft (mm) | measured draft (mm) | error | within 3% | "
      "drift (mm) | oscillation (mm) | level spread (mm) | force / weight - 1 | mean compression | run (s) |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
fails, total = [], 0
for solver in ("pbf", "wcsph"):
    for rel in (0.25, 0.5, 0.75):
        for n in sorted({k[2] for k in runs if k[0] == solver}):
            if (solver, rel, n, "") in runs:
                s = row((solver, rel, n, ""), "at draft")
                total += 1
                if abs(s["err"]) > 3:
                    fails.append(f"{solver.upper()} {rel:g} at a/{n} ({s['err']:+.1f}%)")
print()
print(f"Released at the expected draft: {total - len(fails)} of {total} cases within 3%"
      + (f"; outside: {', '.join(fails)}." if fails else "."))
print()
print("## Where the light box comes to rest depends on where it is released")
print()
print("The 0.25 box released at its expected draft, 10 mm above it and 10 mm below it (same columns):")
print()
print("| solver | rel. density | spacing | released | expected draft (mm) | measured draft (mm) | error | within 3% | "
      "drift (mm) | oscillation (mm) | level spread (mm) | force / weight - 1 | mean compression | run (s) |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for solver in ("pbf", "wcsph"):
    for n in sorted({k[2] for k in runs if k[0] == solver}):
        group = [(solver, 0.25, n, tag) for tag in ("high", "", "low") if (solver, 0.25, n, tag) in runs]
        if len(group) < 2:
            continue
        for key in group:
            row(key, {"high": "10 mm high", "low": "10 mm low", "": "at draft"}[key[3]])
print()
for solver in ("pbf", "wcsph"):
    for n in sorted({k[2] for k in runs if k[0] == solver}):
        group = [(solver, 0.25, n, tag) for tag in ("high", "", "low") if (solver, 0.25, n, tag) in runs]
        if len(group) < 2:
            continue
        drafts = [stats(key)["draft"] for key in group]
        span = max(drafts) - min(drafts)
        print(f"- {solver.upper()} at a/{n}: the rest drafts span {1000 * span:.2f} mm, {span * n / A:.2f} spacings, "
              f"{100 * span / (0.25 * A):.1f}% of the expected draft.")
print()
print("## Settling: does the body's oscillation grow or decay?")
print()
print("Half the range of the body's centre z (mm) in windows after the release at 0.5 s:")
print()
wins = [(0.5, 1), (1, 2), (2, 4), (4, 6), (6, 8), (8, 10)]
print("| solver | rel. density | spacing | released | " + " | ".join(f"{a:g}-{b:g} s" for a, b in wins) + " |")
print("|---|---|---|---|" + "---|" * len(wins))
for key in sorted(runs, key=lambda k: (k[0], k[1], k[2], k[3])):
    d = runs[key][0]
    amps = []
    for a, b in wins:
        z = [d["b.z"][i] for i in window(d, a, b)]
        amps.append(f"{500 * (max(z) - min(z)):.2f}")
    label = {"high": "10 mm high", "low": "10 mm low", "": "at draft"}[key[3]]
    print(f"| {key[0].upper()} | {key[1]:g} | a/{key[2]} | {label} | " + " | ".join(amps) + " |")
print()
def half_range(d, a, b):
    z = [d["b.z"][i] for i in window(d, a, b)]
    return 500 * (max(z) - min(z))
grew = [key for key in runs if half_range(runs[key][0], 8, 10) > half_range(runs[key][0], 1, 2)]
print(f"In 8-10 s the half-range is at most {max(half_range(runs[k][0], 8, 10) for k in runs):.2f} mm; "
      f"runs where it exceeds that of 1-2 s (a growing oscillation): "
      + (", ".join(f"{k[0].upper()} {k[1]:g} a/{k[2]} {k[3] or 'at draft'}" for k in sorted(grew)) or "none") + ".")
all_stats = [stats(k) for k in runs]
print(f"Over all {len(runs)} runs: |force / weight - 1| at most {max(abs(x['force']) for x in all_stats):.2f}%, "
      f"|drift| at most {max(abs(x['drift']) for x in all_stats):.3f} mm.")
PY
  echo
  echo "![The body's centre z(t)](archimedes.png)"
  echo
  echo "Run times: the sum of the runs' wall times above, $(cat "$work"/*.seconds | awk '{t += $1} END {print t}') s on one thread."
} > "$out"
cat "$out"
