#!/usr/bin/env bash
# The surface reconstruction's speed and memory on the 1M-particle dam break frame
# (docs/performance/surface.md): runs scenarios/dambreak.lua at 1,000,000 particles to
# t = 0.3 s (the surge mid-tank, about 20 minutes on 2 cores), then times dump/surface's code
# (build/bench/surface_rate) at 1 and 2 threads, and, if it was built, OpenVDB's path
# (build/bench/surface_openvdb) for comparison.
#
#   share/benchmarks/surface_rate.sh [OUT_DIR (default out/surface_rate)] [REPEATS (default 5)]
#
# A frame already in OUT_DIR (frame_00003.txt) is reused.
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-out/surface_rate}
repeats=${2:-5}
for tool in build/pbfengine build/bench/surface_rate; do
  [ -x "$tool" ] || { echo "surface_rate.sh: $tool is missing: build first (./setup.sh)" >&2; exit 1; }
done
mkdir -p "$out"
if [ ! -f "$out/frame_00003.txt" ]; then
  build/pbfengine run scenarios/dambreak.lua -v particles=1000000 -v t_end=0.3 -v interval=0.1 \
    -v restart_interval=0 -v out="$out" --log none > "$out/run.log"
fi
frame="$out/frame_00003.txt"
domain="0 0 0 0.5 0.05 0.4"  # the tank of dambreak.lua (a = 0.1 m)
for threads in 1 2; do
  OMP_NUM_THREADS=$threads build/bench/surface_rate "$frame" --spacing 0.001 --repeats "$repeats" \
    --threads "$threads" --domain $domain
done
echo "without smoothing:"
OMP_NUM_THREADS=1 build/bench/surface_rate "$frame" --spacing 0.001 --repeats "$repeats" --threads 1 \
  --smoothing 0 --domain $domain
if [ -x build/bench/surface_openvdb ]; then
  echo "OpenVDB (ParticlesToLevelSet, LevelSetFilter::meanCurvature, volumeToMesh):"
  awk 'NR > 1 { print $1, $2, $3 }' "$frame" > "$out/frame.xyz"  # its reader takes x y z lines only
  for smooth in 0 1; do
    build/bench/surface_openvdb "$out/frame.xyz" --spacing 0.001 --smooth $smooth --threads 1 --repeats 3
  done
fi
