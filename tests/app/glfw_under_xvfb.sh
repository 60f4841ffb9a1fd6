#!/usr/bin/env bash
# Cli.GlfwBackendRendersUnderXvfb: the glfw backend, in a real window on a virtual X server,
# renders the same G-buffer as the headless backend. Fails (never skips) when xvfb-run is
# missing: scripts/setup.sh installs it, so a missing one is a broken set-up.
# usage: glfw_under_xvfb.sh PHOTOVR OUT_DIR
set -euo pipefail
photovr=$1 out=$2
command -v xvfb-run >/dev/null || { echo "FAIL: xvfb-run not found (scripts/setup.sh installs xvfb)"; exit 1; }
command -v idiff >/dev/null || { echo "FAIL: idiff not found (scripts/setup.sh installs openimageio-tools)"; exit 1; }
rm -rf "$out"
args=(render --mode gbuffer --scene cornell --width 32 --height 36)
xvfb-run -a "$photovr" "${args[@]}" --backend glfw --out "$out/glfw"
"$photovr" "${args[@]}" --backend osmesa --out "$out/osmesa"
for f in left/depth.exr right/depth.exr gbuffer.png; do
  [ -s "$out/glfw/$f" ] || { echo "FAIL: the glfw render wrote no $f"; exit 1; }
  # Both backends are Mesa's llvmpipe running the same shaders on the same input: the
  # images must be identical (a window's default framebuffer is not what we read back).
  idiff -fail 0 -warn 0 "$out/glfw/$f" "$out/osmesa/$f" || { echo "FAIL: glfw and osmesa differ in $f"; exit 1; }
done
echo "glfw under Xvfb: the same G-buffer as osmesa"
