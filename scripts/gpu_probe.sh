#!/usr/bin/env bash
# The GL passes timed on a GPU machine that has a compiler, CMake and an NVIDIA (or other
# vendor's) EGL driver, but none of photovr's Debian libraries and no network
# (bench/gpu_probe.cpp, built alone by bench/gpu_probe/CMakeLists.txt).
#
#   scripts/gpu_probe.sh prepare   here (Debian 12, after scripts/setup.sh): fills
#                                  .gpu_probe/ (git-ignored, ~4 MiB) with glm and the
#                                  Khronos headers, libEGL.so.1 to link against, and the
#                                  glvnd packages the GPU machine may lack
#   scripts/gpu_probe.sh run [OUT [PROBE OPTIONS]]
#                                  there, from the repository root with .gpu_probe/ copied
#                                  along: builds in /tmp and writes gpu_probe*.csv and
#                                  gpu_probe.log to OUT (default out/gpu_probe); options go
#                                  to the probe (--repeats N, --scene NAME, --width, --height)
set -euo pipefail
cd "$(dirname "$0")/.."
deps=.gpu_probe

prepare() {
  rm -rf "$deps"
  mkdir -p "$deps/include/GL" "$deps/lib" "$deps/debs"
  cp -r /usr/include/glm /usr/include/EGL /usr/include/KHR "$deps/include/"
  cp /usr/include/GL/glcorearb.h "$deps/include/GL/"
  cp -L /usr/lib/x86_64-linux-gnu/libEGL.so.1 "$deps/lib/"
  (cd "$deps/debs" && apt-get download libegl1 libglvnd0 libgles2 libopengl0 libgl1 libglx0)
  du -sh "$deps"
}

run() {
  local out=${1:-out/gpu_probe}
  shift || true
  mkdir -p "$out"
  # glvnd's dispatch libraries, where the machine has none (they only add a loader; the
  # vendor's EGL is found through its glvnd JSON file).
  if ! ldconfig -p | grep -q 'libEGL.so.1 '; then
    for f in "$deps"/debs/*.deb; do dpkg -x "$f" /; done
    ldconfig
  fi
  local vendor=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
  [ -f "$vendor" ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$vendor
  cmake -S bench/gpu_probe -B /tmp/photovr_gpu_probe -DPROBE_DEPS="$PWD/$deps" >/dev/null
  cmake --build /tmp/photovr_gpu_probe -j"$(nproc)" >/dev/null
  /tmp/photovr_gpu_probe/photovr_gpu_probe --out "$out" "$@" 2>&1 | tee "$out/gpu_probe.log"
}

case "${1:-}" in
  prepare) prepare ;;
  run) shift; run "$@" ;;
  *) echo "usage: scripts/gpu_probe.sh prepare | run [OUT [PROBE OPTIONS]]" >&2; exit 2 ;;
esac
