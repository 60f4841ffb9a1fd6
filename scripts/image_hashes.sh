#!/bin/sh
# Hashes every image the user-facing commands write, for one photovr binary, so that a
# refactor can show that it changes no pixel: run it with the binary before and after and
# diff the two lists. Small sizes keep it to a few minutes on 2 cores.
#   scripts/image_hashes.sh BUILD_DIR OUT_DIR > hashes.txt
set -eu
bin="$1/photovr"
out="$2"
rm -rf "$out"
mkdir -p "$out"
poses="$(dirname "$0")/../tests/golden/hmd_poses.csv"
size="--width 48 --height 54 --backend osmesa"
for scene in atrium cornell spheres; do
  d="$out/$scene"
  "$bin" render --scene "$scene" $size --out "$d/hybrid" >/dev/null
  "$bin" render --scene "$scene" $size --denoise full --frames 3 --sampling lens-matched \
    --spp 2 --out "$d/hybrid-denoised" >/dev/null
  "$bin" render --scene "$scene" $size --mode pt --spp 2 --denoise temporal --frames 2 \
    --out "$d/pt" >/dev/null
  "$bin" render --scene "$scene" $size --mode gbuffer --out "$d/gbuffer" >/dev/null
  "$bin" render --scene "$scene" $size --hmd sim "$poses" --frames 3 --panel 192x108 \
    --denoise full --out "$d/hmd" >/dev/null
  "$bin" ab --scene "$scene" $size --reference-spp 8 --out "$d/ab" >/dev/null
done
cd "$out"
# summary.txt and hmd_frames.csv hold times, and EXR headers a DateTime: hash pixels.
find . -type f \( -name '*.png' -o -name '*.exr' \) | sort | while read -r f; do
  printf '%s %s\n' "$(iinfo --hash "$f" | sed -n 's/.*SHA-1: //p')" "$f"
done
