#!/bin/bash
# Regenerates the golden images in tests/golden/ (tests/golden/README.md), in two steps a
# person takes on purpose:
#
#   scripts/update_goldens.sh            builds and runs the golden tests and lists every
#                                        stored image that changed, with the paths of its
#                                        actual and diff images; stores nothing
#   scripts/update_goldens.sh --accept   stores the actual images of that run (no new
#                                        render: what was looked at is what is stored),
#                                        writes made_with.txt, checks the goldens against
#                                        each of Embree's kernel sets this CPU runs, and
#                                        runs the tests again
#   scripts/update_goldens.sh --check-isas   only that check, storing nothing
#
# Options: --build-dir DIR (default: build). Exit status: 0 nothing changed, or stored;
# 1 images changed and were not stored, or an Embree kernel set fails the goldens; 2 bad
# use, or the tests could not run.
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
build="$repo/build"
mode=look
while [ $# -gt 0 ]; do
  case "$1" in
    --accept) mode=accept ;;
    --check-isas) mode=isas ;;
    --build-dir) build=$(cd "${2:?--build-dir: missing DIR}" && pwd); shift ;;
    -h|--help) sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "update_goldens.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done

tests="$build/tests/photovr_golden_tests"
out="$build/tests/golden-out"
goldens="$repo/tests/golden"

die() { echo "update_goldens.sh: $*" >&2; exit 2; }

build_tests() {
  [ -f "$build/CMakeCache.txt" ] || die "no build in $build (configure it first, or --build-dir)"
  cmake --build "$build" --target photovr_golden_tests -j2 >/dev/null ||
    die "building photovr_golden_tests failed"
}

# The images of the last run's manifests whose verdict matches $1 (an extended regex), one
# a line: stored<TAB>actual<TAB>verdict<TAB>max_diff<TAB>failing<TAB>pixels.
manifest_rows() {
  cat "$out"/*/compared.txt 2>/dev/null | awk -F'\t' -v v="^($1)$" '$3 ~ v' || true
}
count_rows() { manifest_rows "$1" | grep -c . || true; }

# Lists what the last run changed; fails when something did.
report() {
  local n
  n=$(count_rows 'changed|missing')
  echo
  echo "golden images: $(count_rows identical) identical, $(count_rows within) within" \
    "tolerance, $n changed or new"
  while IFS=$'\t' read -r stored actual verdict maxdiff failing pixels; do
    [ -n "$stored" ] || continue
    if [ "$verdict" = missing ]; then
      echo "  NEW      ${stored#"$repo"/}  (actual: $actual)"
      continue
    fi
    echo "  CHANGED  ${stored#"$repo"/}: max difference $maxdiff, $failing of $pixels" \
      "pixels beyond tolerance"
    echo "           actual: $actual"
    local diff
    diff="$build/tests/golden-failures/$(basename "${stored%.*}").diff.png"
    [ -f "$diff" ] && echo "           diff:   $diff"
  done <<<"$(manifest_rows 'changed|missing')"
  [ "$n" = 0 ]
}

# --accept stores the run a person looked at, and only if no binary was rebuilt since.
check_run_is_current() {
  shopt -s nullglob
  local manifests=("$out"/*/compared.txt) m bin
  [ ${#manifests[@]} -gt 0 ] || die "no golden run in $out: run it without --accept first"
  for m in "${manifests[@]}"; do
    for bin in "$tests" "$build/photovr"; do
      [ "$m" -nt "$bin" ] ||
        die "$bin was rebuilt after the run you looked at: run it without --accept again"
    done
  done
}

store_changed() {
  local golden actual stored=0
  while IFS=$'\t' read -r golden actual _; do
    [ -n "$golden" ] || continue
    cp "$actual" "$golden"
    echo "stored ${golden#"$repo"/}"
    stored=$((stored + 1))
  done <<<"$(manifest_rows 'changed|missing')"
  # Which renderer and CPU made them: the test prints this when a golden fails elsewhere.
  {
    grep -h '^photovr: ' "$out"/*/log.txt | sed 's/;.*//' | sort -u | head -1
    echo "CPU: $(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //'), Embree kernels:" \
      "$(native_isa)"
  } >"$goldens/made_with.txt"
  echo "stored $stored image(s); made_with.txt: $(tr '\n' ' ' <"$goldens/made_with.txt")"
}

# Embree's kernel sets this CPU can run, narrowest first (Embree 3 names).
cpu_isas() {
  local flags
  flags=" $(grep -m1 '^flags' /proc/cpuinfo | cut -d: -f2) "
  echo sse2
  [[ $flags == *" sse4_2 "* ]] && echo sse4.2
  [[ $flags == *" avx "* ]] && echo avx
  [[ $flags == *" avx2 "* && $flags == *" fma "* ]] && echo avx2
  [[ $flags == *" avx512f "* && $flags == *" avx512dq "* && $flags == *" avx512cd "* &&
    $flags == *" avx512bw "* && $flags == *" avx512vl "* ]] && echo avx512
  return 0
}
native_isa() { cpu_isas | tail -1; }

# Embree picks its kernels from the CPU at run time and they round differently (README.md,
# "Determinism"): a golden that passes here could fail on a machine with other kernels.
# photovr passes no configuration to rtcNewDevice, so a preloaded shim passes isa=.
check_isas() {
  local shim="$build/tests/golden-embree-isa.so" isa failed=0
  printf '%s\n' '#define _GNU_SOURCE' '#include <dlfcn.h>' '#include <stdlib.h>' \
    'void* rtcNewDevice(const char* config) {' '  (void)config;' \
    '  void* (*real)(const char*) = (void* (*)(const char*))dlsym(RTLD_NEXT, "rtcNewDevice");' \
    '  return real(getenv("GOLDEN_EMBREE_CONFIG"));' '}' >"$shim.c"
  "${CC:-cc}" -shared -fPIC -O2 "$shim.c" -o "$shim" -ldl ||
    { echo "warning: no C compiler: Embree's kernel sets not checked"; return 0; }
  for isa in $(cpu_isas); do
    if GOLDEN_EMBREE_CONFIG="isa=$isa" LD_PRELOAD="$shim" "$tests" --gtest_filter='Golden.*' \
      >"$out/isa-$isa.txt" 2>&1; then
      local n largest
      n=$(count_rows within)
      largest=$(manifest_rows within | cut -f4 | sort -g | tail -1)
      [ -z "$largest" ] || largest=", largest difference $largest"
      echo "  Embree $isa kernels: pass ($n of the images differ within tolerance$largest)"
    else
      echo "  Embree $isa kernels: FAIL, see $out/isa-$isa.txt: a machine whose CPU makes" \
        "Embree pick them would fail these goldens"
      failed=1
    fi
  done
  rm -f "$shim" "$shim.c"
  return $failed
}

# A plain run last: golden-out/ then holds this machine's own images again (never the
# shimmed ones, which a later --accept must not store).
final_check() {
  echo "checking that the goldens pass:"
  local ok=0
  "$tests" --gtest_filter='Golden.*' --gtest_brief=1 | grep -v '^Running main' || ok=1
  du -cb "$goldens"/*.exr "$goldens"/*.png | tail -1 |
    sed 's/\s*total/ bytes of golden images in tests\/golden/'
  return $ok
}

case "$mode" in
  look)
    build_tests
    # Failures are expected here: they are the changes to look at.
    "$tests" --gtest_filter='Golden.*' || true
    if report; then echo "nothing to store"; exit 0; fi
    echo
    echo "Look at the actual and diff images above. If every change is intended, store them:"
    args=$([ "$build" = "$repo/build" ] || echo " --build-dir $build")
    echo "  scripts/update_goldens.sh --accept$args"
    exit 1
    ;;
  accept)
    check_run_is_current
    report || true
    store_changed
    echo "checking the goldens against Embree's kernel sets:"
    status=0
    check_isas || status=1
    final_check || status=1
    exit $status
    ;;
  isas)
    build_tests
    status=0
    check_isas || status=1
    final_check || status=1
    exit $status
    ;;
esac
