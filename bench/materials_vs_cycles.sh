#!/bin/bash
# The glTF material-extension study (issue 22): each scene of photovr_material_study
# rendered converged by photovr (--mode pt) and by Blender Cycles (../shared/peer/), same
# file, camera and bounce count; prints and writes (OUT/materials_vs_cycles.csv) the mean
# radiance of each and their ratio. Needs Debian's blender (not installed by set-up: a
# large package, for measurement only).
#   bench/materials_vs_cycles.sh [BUILD=build] [OUT=out/materials] [SPP=1024] [SIZE=128]
# Environment: BOUNCES (default 16; 0 = direct light only), SCENES (a space-separated
# subset of the study's scene names).
set -euo pipefail
BUILD=${1:-build}
OUT=${2:-out/materials}
SPP=${3:-1024}
SIZE=${4:-128}
PEER=${PEER:-../shared/peer/cycles_render.py}
BOUNCES=${BOUNCES:-16}
CAM_FROM=0,1,0.9
CAM_AT=0,1,-1
FOVY=55
command -v blender > /dev/null || { echo "materials_vs_cycles: blender is not installed" >&2; exit 1; }
mkdir -p "$OUT"
# The peer zeroes the Principled BSDF's Clearcoat and Sheen inputs ("glTF core never uses
# these"); Blender's importer puts KHR_materials_clearcoat in Clearcoat (and the sheen in a
# separate Velvet BSDF). A copy that leaves the two alone, so the coat reaches Cycles;
# identical for scenes without the extensions (the importer leaves both at 0 there).
peer_copy="$OUT/cycles_render_layers.py"
sed 's/for name in ("Sheen", "Clearcoat", "Anisotropic"):/for name in ("Anisotropic",):/' \
  "$PEER" > "$peer_copy"
grep -q 'for name in ("Anisotropic",):' "$peer_copy" ||
  { echo "materials_vs_cycles: $PEER changed; cannot keep its clearcoat" >&2; exit 1; }
PEER="$peer_copy"
mean() {  # mean of the three channels' averages
  oiiotool "$1" --printstats 2>/dev/null | awk '/Stats Avg:/ {print ($3 + $4 + $5) / 3; exit}'
}
csv="$OUT/materials_vs_cycles.csv"
echo "scene,photovr_mean,cycles_mean,photovr_over_cycles,photovr_s,cycles_s" > "$csv"
printf '%-22s %12s %12s %8s %10s %10s\n' scene photovr cycles ratio photovr_s cycles_s
for scene in $("$BUILD/bench/photovr_material_study" "$OUT"); do
  if [ -n "${SCENES:-}" ] && [[ " $SCENES " != *" $scene "* ]]; then continue; fi
  gltf="$OUT/$scene.gltf"
  t0=$(date +%s.%N)
  "$BUILD/photovr" render --mode pt --eyes mono --scene "$gltf" --look-from $CAM_FROM \
    --look-at $CAM_AT --fovy $FOVY --width "$SIZE" --height "$SIZE" --spp 64 \
    --frames $((SPP / 64)) --bounces $BOUNCES --out "$OUT/$scene-photovr" > /dev/null
  t1=$(date +%s.%N)
  blender -b --factory-startup --python "$PEER" -- --gltf "$gltf" --spp "$SPP" \
    --width "$SIZE" --height "$SIZE" --cam "$CAM_FROM,$CAM_AT,$FOVY" \
    --max-bounces $BOUNCES --filter box --out "$OUT/$scene-cycles.exr" > "$OUT/$scene-cycles.log" 2>&1
  t2=$(date +%s.%N)
  p=$(mean "$OUT/$scene-photovr/mono/color.exr")
  c=$(mean "$OUT/$scene-cycles.exr")
  r=$(awk -v p="$p" -v c="$c" 'BEGIN {printf "%.4f", p / c}')
  tp=$(awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.1f", b - a}')
  tc=$(awk -v a="$t1" -v b="$t2" 'BEGIN {printf "%.1f", b - a}')
  echo "$scene,$p,$c,$r,$tp,$tc" >> "$csv"
  printf '%-22s %12.6f %12.6f %8s %10s %10s\n' "$scene" "$p" "$c" "$r" "$tp" "$tc"
done
echo "wrote $csv"
