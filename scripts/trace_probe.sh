#!/usr/bin/env bash
# The CPU tracer timed on another machine (more cores) that has none of photovr's Debian
# libraries: photovr_bench_trace (the tracer against bare rtcIntersect1/rtcOccluded1 on its
# own rays, 1 thread and all) linked without OpenImageIO, which it never calls, and
# carried with the two libraries it needs, Debian's Embree 3 and TBB (~45 MiB).
#
#   scripts/trace_probe.sh prepare [BUILD]   here, after `make build`: fills .trace_probe/
#                                            (git-ignored) with the binary and its libraries
#   scripts/trace_probe.sh run [OUT [BENCH OPTIONS]]
#                                            there, from the repository root with
#                                            .trace_probe/ copied along: writes
#                                            bench_trace.csv and trace_probe.log to OUT
#                                            (default out/trace_probe)
set -euo pipefail
cd "$(dirname "$0")/.."
probe=.trace_probe

prepare() {
  local build=${1:-build}
  cmake --build "$build" --target photovr_bench_trace >/dev/null
  rm -rf "$probe"
  mkdir -p "$probe/lib"
  # Every core object but the ones that read or write files through OpenImageIO or tinygltf.
  local objects
  objects=$(ls "$build"/core/CMakeFiles/photovr_core.dir/*.o |
    grep -v -E '/(image_io|environment_io|gltf_[a-z_]*|exr_header)\.cpp\.o$')
  # shellcheck disable=SC2086
  c++ -O3 -Wl,--as-needed "$build"/bench/CMakeFiles/photovr_bench_trace.dir/*.cpp.o \
    -o "$probe/photovr_bench_trace" "$build"/trace/libphotovr_trace.a $objects \
    "$(readlink -f /usr/lib/x86_64-linux-gnu/libtbb.so.12)" \
    "$(readlink -f /usr/lib/x86_64-linux-gnu/libembree3.so.3)"
  cp -L /usr/lib/x86_64-linux-gnu/libembree3.so.3 /usr/lib/x86_64-linux-gnu/libtbb.so.12 "$probe/lib/"
  du -sh "$probe"
}

run() {
  local out=${1:-out/trace_probe}
  shift || true
  mkdir -p "$out"
  LD_LIBRARY_PATH="$PWD/$probe/lib" "$probe/photovr_bench_trace" --out "$out" "$@" 2>&1 |
    tee "$out/trace_probe.log"
}

case "${1:-}" in
  prepare) shift; prepare "$@" ;;
  run) shift; run "$@" ;;
  *) echo "usage: scripts/trace_probe.sh prepare [BUILD] | run [OUT [BENCH OPTIONS]]" >&2; exit 2 ;;
esac
