#!/bin/bash
# Submits a catena sweep to Slurm: an array of SHARDS tasks, then a merge job that runs only if
# every task succeeded (--dependency=afterok). Prints the two job ids.
#   scripts/slurm/submit.sh PLAN.toml OUT_DIR SHARDS [extra sbatch options...]
# CATENA (default: catena on the PATH) names the binary the jobs run.
set -euo pipefail
if [ $# -lt 3 ]; then
  echo "usage: $0 PLAN.toml OUT_DIR SHARDS [sbatch options...]" >&2
  exit 2
fi
plan=$(realpath "$1"); out=$(realpath -m "$2"); shards=$3; shift 3
here=$(dirname "$(realpath "$0")")
mkdir -p "$out"
export PLAN="$plan" OUT="$out" CATENA="${CATENA:-catena}"
array=$(sbatch --parsable --array=0-$((shards - 1)) --chdir="$out" --export=ALL "$@" "$here/sweep-array.sbatch")
merge=$(sbatch --parsable --dependency=afterok:"$array" --chdir="$out" --export=ALL "$@" "$here/sweep-merge.sbatch")
echo "array job $array ($shards tasks), merge job $merge"
