#!/bin/sh
# Regenerates README.md's "Performance" section from a real bench run: runs
# `photovr bench --quick` (or the full matrix with --full), copies the plots to docs/images/
# and replaces the text between <!-- bench:begin --> and <!-- bench:end --> with bench.md.
#   bench/readme_performance.sh [--full] [PHOTOVR_BINARY]   (from the source folder)
set -eu
matrix=--quick
if [ "${1:-}" = "--full" ]; then matrix=; shift; fi
photovr=${1:-build/photovr}
out=out/bench
"$photovr" bench $matrix --out "$out"
mkdir -p docs/images
for plot in bench_error_vs_time bench_stages; do
  cp "$out/$plot.png" "docs/images/$plot.png"
done
awk -v md="$out/bench.md" '
  /<!-- bench:end -->/ { skipping = 0 }
  !skipping { print }
  /<!-- bench:begin -->/ { while ((getline line < md) > 0) print line; skipping = 1 }
' README.md > README.md.tmp
grep -q "<!-- bench:end -->" README.md.tmp || { echo "README.md lacks the bench markers" >&2; exit 1; }
mv README.md.tmp README.md
echo "README.md Performance section regenerated from $out/bench.md"
