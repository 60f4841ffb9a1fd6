#!/bin/bash
# Time per sample of photovr's path tracer against Blender Cycles (../shared/peer/) on the
# built-in scenes exported as glTF (issue 20): the same file, camera, size and bounce cap,
# both on every core, runs alternating photovr / Cycles. Time per sample is the slope
# between a low and a high sample count, (t_hi - t_lo) / ((hi - lo) W H), which leaves out
# what a render costs once (start-up, import, BVH build, writing the image). Needs Debian's
# blender and python3-numpy, which the peer script imports (not installed by set-up: large
# packages, for measurement only). Punctual lights
# go to Cycles in the importer's COMPAT mode (W = 4 pi cd, no 683 lm/W): photovr reads a
# candela as a W/sr, and the default (SPEC) mode renders the atrium ~700x darker.
#   bench/pt_vs_cycles.sh [BUILD=build] [OUT=out/pt_vs_cycles] [PAIRS=2]
# Environment: SCENES (default "atrium cornell spheres"), SIZE (WxH, default 240x270),
# LO and HI (sample counts, default 16 and 64), BOUNCES (default 8).
set -euo pipefail
BUILD=${1:-build}
OUT=${2:-out/pt_vs_cycles}
PAIRS=${3:-2}
PEER=${PEER:-../shared/peer/cycles_render.py}
SCENES=${SCENES:-atrium cornell spheres}
SIZE=${SIZE:-240x270}
LO=${LO:-16}
HI=${HI:-64}
BOUNCES=${BOUNCES:-8}
W=${SIZE%x*}
H=${SIZE#*x}
command -v blender > /dev/null || { echo "pt_vs_cycles: blender is not installed" >&2; exit 1; }
mkdir -p "$OUT"
now() { date +%s.%N; }
photovr_s() {  # seconds of one photovr render of $1 at $2 spp
  local t0 t1
  t0=$(now)
  "$BUILD/photovr" render --mode pt --eyes mono --scene "$OUT/$1.glb" --width "$W" --height "$H" \
    --spp "$2" --bounces "$BOUNCES" --out "$OUT/$1-photovr-$2" > "$OUT/$1-photovr-$2.log"
  t1=$(now)
  awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.3f", b - a}'
}
cycles_s() {  # the same for Cycles (wall time of the whole blender process)
  local t0 t1
  t0=$(now)
  blender -b --factory-startup --python "$PEER" -- --gltf "$OUT/$1.glb" --spp "$2" \
    --width "$W" --height "$H" --max-bounces "$BOUNCES" --filter box --light-mode COMPAT \
    --out "$OUT/$1-cycles-$2.exr" > "$OUT/$1-cycles-$2.log" 2>&1
  t1=$(now)
  awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.3f", b - a}'
}
mean() {  # mean of the three channels' averages
  oiiotool "$1" --printstats 2>/dev/null | awk '/Stats Avg:/ {print ($3 + $4 + $5) / 3; exit}'
}
csv="$OUT/pt_vs_cycles.csv"
echo "scene,pair,photovr_lo_s,photovr_hi_s,cycles_lo_s,cycles_hi_s,photovr_ns_per_sample,cycles_ns_per_sample,cycles_over_photovr,photovr_mean,cycles_mean" > "$csv"
printf '%-8s %4s %12s %12s %8s %10s %10s\n' scene pair "photovr ns" "cycles ns" speedup \
  "photovr" "cycles"
for scene in $SCENES; do
  "$BUILD/photovr" export-scene "$scene" "$OUT/$scene.glb" 2> /dev/null > /dev/null
  for pair in $(seq 1 "$PAIRS"); do
    plo=$(photovr_s "$scene" "$LO"); clo=$(cycles_s "$scene" "$LO")
    phi=$(photovr_s "$scene" "$HI"); chi=$(cycles_s "$scene" "$HI")
    read -r pns cns ratio < <(awk -v a="$plo" -v b="$phi" -v c="$clo" -v d="$chi" \
      -v n="$(( (HI - LO) * W * H ))" \
      'BEGIN {p = (b - a) / n * 1e9; q = (d - c) / n * 1e9; printf "%.1f %.1f %.3f\n", p, q, q / p}')
    pm=$(mean "$OUT/$scene-photovr-$HI/mono/color.exr")
    cm=$(mean "$OUT/$scene-cycles-$HI.exr")
    echo "$scene,$pair,$plo,$phi,$clo,$chi,$pns,$cns,$ratio,$pm,$cm" >> "$csv"
    printf '%-8s %4s %12s %12s %7sx %10.5f %10.5f\n' "$scene" "$pair" "$pns" "$cns" "$ratio" "$pm" "$cm"
  done
done
echo "wrote $csv"
