#!/bin/sh
# The tracer of two builds side by side, alternating runs so that a busy spell of the
# machine slows both alike (issue 20: "build the old commit beside it; same run,
# alternating"). Builds the old commit's photovr_bench_trace in a worktree if asked.
#   bench/trace_old_vs_new.sh OLD_BUILD NEW_BUILD [PAIRS] > out/bench/trace_old_vs_new.csv
#   (OLD_BUILD from: git worktree add /tmp/old COMMIT && cmake -S /tmp/old -B /tmp/old/build
#    && cmake --build /tmp/old/build --target photovr_bench_trace)
# Prints one CSV row per run: which, pair, scene, threads, photovr Mrays/s, raw Mrays/s,
# ratio, image hash (equal hashes: the two tracers made the same image).
set -eu
old="$1/bench/photovr_bench_trace"
new="$2/bench/photovr_bench_trace"
pairs="${3:-5}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
echo "build,pair,scene,threads,photovr_mrays_s,raw_mrays_s,ratio,image_hash"
i=1
while [ "$i" -le "$pairs" ]; do
  for which in old new; do
    bin="$old"
    [ "$which" = new ] && bin="$new"
    "$bin" --repeats 3 --out "$tmp/$which" >/dev/null
    tail -n +2 "$tmp/$which/bench_trace.csv" | awk -F, -v w="$which" -v p="$i" \
      '{ printf "%s,%s,%s,%s,%s,%s,%s,%s\n", w, p, $1, $2, $6, $7, $11, $15 }'
  done
  i=$((i + 1))
done
