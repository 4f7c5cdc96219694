#!/usr/bin/env bash
# Submits the sharded navigation benchmark and its merge: SHARDS array tasks, then the merge once
# every task has succeeded (afterok). Usage: SHARDS=8 RESULTS=/shared/bench deploy/slurm/submit.sh
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
SHARDS=${SHARDS:-8}
jid=$(sbatch --parsable --array=0-$((SHARDS - 1)) "$here/bench-nav.sbatch")
sbatch --dependency=afterok:"${jid%%;*}" --export=ALL,MODE=merge,SHARDS="$SHARDS" --job-name=makeway-bench-merge \
    "$here/bench-nav.sbatch"
echo "submitted array $jid ($SHARDS shards) and its merge"
