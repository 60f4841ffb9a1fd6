#!/usr/bin/env bash
# photovr bench as independent jobs with GNU parallel (local cores, or ssh hosts sharing the
# output folder and the reference cache: PARALLEL_OPTS="--sshloginfile FILE"), then the
# reports collected from whatever finished. Every job uses all cores of its machine (the
# tracer's threads), so on one machine run one job at a time (JOBS=1): the point is the
# split, the isolation and the re-runs, not speed there.
#
# usage: scripts/cluster/bench_parallel.sh JOBS OUT_DIR CACHE_DIR PHOTOVR [bench options]
#   e.g. scripts/cluster/bench_parallel.sh 1 out/bench-jobs ~/.cache/photovr build/photovr --quick
# Re-running runs again only the jobs that failed or never ran (--resume-failed, joblog).
set -euo pipefail
. "$(dirname "$0")/lib.sh"
usage_unless 4 "$@"
require_parallel
jobs=$1 out=$2 cache=$3 photovr=$4
shift 4
mkdir -p "$out/jobs"
"$photovr" bench "$@" --list-jobs | cut -f1 > "$out/jobs/list.txt"
status=0
# shellcheck disable=SC2086
parallel --will-cite -j "$jobs" --joblog "$out/jobs/joblog.txt" --resume-failed ${PARALLEL_OPTS:-} \
  env PHOTOVR_CACHE_DIR="$cache" "$photovr" bench "$@" --out "$out" --job {} \
  :::: "$out/jobs/list.txt" || status=$?
"$photovr" bench "$@" --collect "$out" || status=$?
exit "$status"
