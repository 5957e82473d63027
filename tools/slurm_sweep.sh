#!/usr/bin/env bash
# A dataset sweep on a Slurm cluster (issue 31): one job array of shards, then the merge.
#
#   tools/slurm_sweep.sh FILE OUT_DIR SHARDS [sweep options...]
#   e.g. tools/slurm_sweep.sh four-bar.json /shared/data 100 --samples 100000 \
#          --curves coupler_point.x,coupler_point.y
#
# On the login node it submits (sbatch) itself twice: an array of SHARDS tasks, task
# i running `mechkin sweep FILE ... --shard i/SHARDS --out OUT_DIR` on the node's
# cores (SLURM_CPUS_PER_TASK threads) and writing OUT_DIR/sweep-shard-i-of-SHARDS.h5;
# and, after every task succeeded (--dependency=afterok), one merge task writing
# OUT_DIR/sweep.h5 over the shards (HDF5 virtual datasets: nothing copied,
# docs/datasets.md). OUT_DIR must be on a file system the nodes share. A failed task
# can be run again alone (sbatch --array=i ...); the merge names missing shards.
# MECHKIN (default: mechkin on PATH) is the binary; SBATCH_OPTIONS adds sbatch options
# (partition, account, time). The two roles run without sbatch too, for a test:
#   SLURM_ARRAY_TASK_ID=3 tools/slurm_sweep.sh FILE OUT 8 ...    # shard 3/8
#   MECHKIN_SLURM_MERGE=1 tools/slurm_sweep.sh FILE OUT 8 ...    # the merge
#SBATCH --job-name=mechkin-sweep
#SBATCH --cpus-per-task=2
#SBATCH --output=mechkin-sweep-%A_%a.log
set -euo pipefail
if [ $# -lt 3 ]; then
  sed -n '2,20p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
fi
file="$1" out="$2" shards="$3"
shift 3
mechkin="${MECHKIN:-mechkin}"
if [ -n "${MECHKIN_SLURM_MERGE:-}" ]; then
  parts=()
  for ((i = 1; i <= shards; i++)); do
    parts+=("$out/sweep-shard-$(printf "%0${#shards}d" "$i")-of-$shards.h5")
  done
  exec "$mechkin" sweep --merge --out "$out" "${parts[@]}"
fi
if [ -n "${SLURM_ARRAY_TASK_ID:-}" ]; then
  exec "$mechkin" sweep "$file" "$@" --shard "$SLURM_ARRAY_TASK_ID/$shards" --out "$out" \
    --threads "${SLURM_CPUS_PER_TASK:-0}"
fi
mkdir -p "$out"
script="$(readlink -f "$0")"
# shellcheck disable=SC2086
array=$(sbatch --parsable ${SBATCH_OPTIONS:-} --array="1-$shards" "$script" "$file" "$out" "$shards" "$@")
# shellcheck disable=SC2086
merge=$(sbatch --parsable ${SBATCH_OPTIONS:-} --dependency="afterok:${array%%;*}" --cpus-per-task=1 \
  --export=ALL,MECHKIN_SLURM_MERGE=1 --job-name=mechkin-merge "$script" "$file" "$out" "$shards" "$@")
echo "submitted: shards job $array (1-$shards), merge job $merge -> $out/sweep.h5"
