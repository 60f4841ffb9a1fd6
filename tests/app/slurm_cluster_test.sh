#!/usr/bin/env bash
# Cluster.SlurmOneNodeRunsReferenceShardsAndBenchJobs (issue 24): a one-node Slurm cluster
# on this machine (scripts/cluster/slurm_local.sh: munged, slurmctld, slurmd on localhost,
# a generated configuration in a temporary folder) runs a reference as 4 array tasks and a
# small bench matrix as array jobs; both against the local run: the reference pixel for
# pixel, the bench's deterministic columns (rays, relMSE, PSNR, SSIM per frame) exactly.
# The daemons are stopped whatever happens. Fails when Slurm or munge is missing
# (scripts/setup.sh installs them); skips (77) only when not run as root.
# usage: slurm_cluster_test.sh PHOTOVR SOURCE_DIR WORK_DIR
set -euo pipefail
photovr=$1 src=$2 work=$3
cluster_sh=$src/scripts/cluster/slurm_local.sh
rm -rf "$work"
mkdir -p "$work/cluster"
[ "$(id -u)" -eq 0 ] || { echo "skipped: the one-node cluster runs its daemons as root"; exit 77; }
for tool in sbatch slurmctld slurmd munged idiff; do
  command -v "$tool" >/dev/null || { echo "FAIL: $tool not found (scripts/setup.sh installs it)"; exit 1; }
done
trap '"$cluster_sh" stop "$work/cluster"' EXIT
"$cluster_sh" start "$work/cluster"
export SLURM_CONF=$work/cluster/slurm.conf

# A reference: 16 frames of a small view, unsharded here and as 4 array tasks there.
ref=(--scene cornell --width 16 --height 16 --bounces 2 --spp 64 --backend osmesa --eyes mono)
PHOTOVR_CACHE_DIR="$work/ref-local" "$photovr" reference "${ref[@]}"
sbatch --wait --array=0-3 --output="$work/ref-%a.out" \
  "$src/scripts/cluster/reference_slurm.sbatch" "$work/ref-slurm" "$photovr" "${ref[@]}"
idiff -fail 0 -warn 0 "$work"/ref-local/references/*/eye0.exr "$work"/ref-slurm/references/*/eye0.exr ||
  { echo "FAIL: the Slurm reference differs from the local one"; cat "$work"/ref-*.out; exit 1; }

# A bench matrix (cornell, --quick: 6 configurations and the limits): in one process here,
# as array jobs there, sharing the reference cache (rendered by the local run first).
bench=(--quick --scenes cornell --backend osmesa)
PHOTOVR_CACHE_DIR="$work/cache" "$photovr" bench "${bench[@]}" --out "$work/bench-local" >/dev/null
n=$("$photovr" bench "${bench[@]}" --list-jobs | wc -l)
sbatch --wait --array=0-$((n - 1)) --output="$work/bench-%a.out" \
  "$src/scripts/cluster/bench_slurm.sbatch" "$work/bench-slurm" "$work/cache" "$photovr" "${bench[@]}"
"$photovr" bench "${bench[@]}" --collect "$work/bench-slurm" > "$work/collect.txt" ||
  { echo "FAIL: jobs missing"; cat "$work/collect.txt"; exit 1; }
columns() {  # label, frame, rays, relmse, psnr, ssim: what does not depend on timing
  cut -d, -f1,11,13,21,22,23 "$1/bench.csv"
}
if ! diff <(columns "$work/bench-local") <(columns "$work/bench-slurm") > "$work/bench.diff"; then
  echo "FAIL: the Slurm bench differs from the local one:"
  head -20 "$work/bench.diff"
  exit 1
fi
echo "Slurm one-node cluster: reference shards and $n bench jobs match the local runs"
