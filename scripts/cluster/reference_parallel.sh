#!/usr/bin/env bash
# A converged reference rendered as N independent shard jobs with GNU parallel: on local
# cores, or on ssh hosts that share the cache folder (PARALLEL_OPTS="--sshloginfile FILE").
# Each job renders frames K, K+N, ... into its own file in the cache; the job that completes
# the set merges it into the reference, bit for bit the one an unsharded run gives.
#
# usage: scripts/cluster/reference_parallel.sh SHARDS JOBS CACHE_DIR PHOTOVR [reference options]
#   e.g. scripts/cluster/reference_parallel.sh 8 2 /shared/cache build/photovr \
#          --scene atrium --width 256 --height 256 --spp 4096
# A killed job re-run (same command) continues from its last saved frames.
set -euo pipefail
. "$(dirname "$0")/lib.sh"
usage_unless 4 "$@"
require_parallel
shards=$1 jobs=$2 cache=$3 photovr=$4
shift 4
# --halt now,fail=1: one failed shard stops the set, and its exit status is the script's.
# shellcheck disable=SC2086
seq 0 $((shards - 1)) | parallel --will-cite --halt now,fail=1 -j "$jobs" ${PARALLEL_OPTS:-} \
  env PHOTOVR_CACHE_DIR="$cache" "$photovr" reference "$@" --shard "{}/$shards"
