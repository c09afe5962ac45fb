#!/usr/bin/env bash
# Makes the pictures of docs/gallery.md and the README with the scenarios themselves: each
# runs with -v images=T (dump/image) and the chosen frames are copied into docs/.
#
#   share/make_gallery.sh [PBFENGINE]        (about half an hour on 2 cores)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
engine="${1:-$root/build/pbfengine}"
out="$(mktemp -d /tmp/pbf-gallery.XXXXXX)"
mkdir -p "$root/docs/gallery" "$root/docs/images"
run() { "$engine" run "$@" --log-level warn; }

run "$root/scenarios/dambreak.lua" -v t_end=0.6 -v images=0.1 -v out="$out/dambreak" -v restart_interval=0
run "$root/scenarios/drop.lua" -v t_end=0.3 -v images=0.05 -v out="$out/drop"
run "$root/scenarios/double_dambreak.lua" -v t_end=0.6 -v images=0.1 -v out="$out/double"
run "$root/scenarios/obstacle.lua" -v t_end=0.4 -v images=0.1 -v out="$out/obstacle"
run "$root/scenarios/wave_flume.lua" -v t_end=5.5 -v images=0.5 -v out="$out/flume"
run "$root/scenarios/fountain.lua" -v t_end=2 -v images=0.5 -v out="$out/fountain" -v restart_interval=0
run "$root/scenarios/channel.lua" -v t_end=1.5 -v images=0.25 -v out="$out/channel" -v restart_interval=0
run "$root/scenarios/floating.lua" -v t_end=2 -v images=0.2 -v out="$out/floating"
# The same scenes as water: dump/image's draw = "surface" (-v draw=surface).
run "$root/scenarios/dambreak.lua" -v t_end=0.6 -v images=0.1 -v draw=surface -v out="$out/dambreak_water" -v restart_interval=0
run "$root/scenarios/spheric_dambreak.lua" -v t_end=1 -v images=0.2 -v draw=surface -v out="$out/spheric_water"
run "$root/scenarios/wave_flume.lua" -v t_end=5.5 -v images=0.5 -v draw=surface -v out="$out/flume_water"

cp "$out/dambreak_water/image_00003.png" "$root/docs/images/dambreak.png"   # t = 0.3 s as water, the README's
for k in 1 3 6; do cp "$out/dambreak_water/image_0000$k.png" "$root/docs/gallery/dambreak_water_$k.png"; done
for k in 1 2 4; do cp "$out/spheric_water/image_0000$k.png" "$root/docs/gallery/spheric_water_$k.png"; done
for k in 10 11; do cp "$out/flume_water/image_000$k.png" "$root/docs/gallery/wave_flume_water_$k.png"; done
for k in 1 3 6; do cp "$out/dambreak/image_0000$k.png" "$root/docs/gallery/dambreak_$k.png"; done
for k in 1 2 4; do cp "$out/drop/image_0000$k.png" "$root/docs/gallery/drop_$k.png"; done
for k in 2 3 5; do cp "$out/double/image_0000$k.png" "$root/docs/gallery/double_dambreak_$k.png"; done
for k in 2 3 4; do cp "$out/obstacle/image_0000$k.png" "$root/docs/gallery/obstacle_$k.png"; done
for k in 10 11; do cp "$out/flume/image_000$k.png" "$root/docs/gallery/wave_flume_$k.png"; done
for k in 1 2 4; do cp "$out/fountain/image_0000$k.png" "$root/docs/gallery/fountain_$k.png"; done
for k in 1 2 6; do cp "$out/channel/image_0000$k.png" "$root/docs/gallery/channel_$k.png"; done
for k in 02 03 10; do cp "$out/floating/image_000$k.png" "$root/docs/gallery/floating_${k#0}.png"; done
rm -rf "$out"
echo "make_gallery.sh: pictures in docs/gallery/ and docs/images/dambreak.png"
