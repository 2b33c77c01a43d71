#!/usr/bin/env bash
# Submits a sweep as a Slurm job array and its merge as a dependent job.
# Usage: submit.sh SPEC.json OUT_DIR [TASKS]   (TASKS: array size, default 16)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
spec=$(readlink -f "$1")
out=$(mkdir -p "$2" && cd "$2" && pwd)
tasks=${3:-16}
rrlab=${RRLAB:-$(command -v rrlab || echo "$here/../../build/cli/rrlab")}
array=$(sbatch --parsable --array=0-$((tasks - 1)) --chdir="$out" \
  --export=ALL,RRLAB="$rrlab",SPEC="$spec",OUT="$out" "$here/sweep.sbatch")
merge=$(sbatch --parsable --dependency=afterok:"$array" --chdir="$out" \
  --export=ALL,RRLAB="$rrlab",OUT="$out" "$here/merge.sbatch")
echo "array job $array ($tasks tasks), merge job $merge; results in $out"
