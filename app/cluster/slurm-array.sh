#!/bin/bash
# mostyle-cli batch over one JOBS file as a Slurm job array: array task I of N runs shard I/N.
# Submit from the folder the JOBS file's paths are relative to, with the indices 0 to N-1:
#   mkdir -p logs && sbatch --array=0-15 app/cluster/slurm-array.sh jobs.jsonl [batch options]
# mostyle-cli is $MOSTYLE_CLI when set, else build/app/mostyle-cli of the submitting folder.
# Each task writes logs/summary_I.json (its journal, logs/summary_I.json.journal, while it runs).
# --skip-existing: a task requeued or run again after a time limit does only what is missing.
# Each task asks for one CPU and runs one job at a time, so the array runs on any node. To run N
# jobs at once in each task, ask for N CPUs on the submit line, which overrides the line below
# (batch's --jobs follows SLURM_CPUS_PER_TASK); a task asking more CPUs than any node has waits
# for ever (squeue's reason: PartitionConfig), so keep N within a node's (sinfo -o %c):
#   mkdir -p logs && sbatch --array=0-15 --cpus-per-task=8 app/cluster/slurm-array.sh jobs.jsonl
#SBATCH --job-name=mostyle-library
#SBATCH --cpus-per-task=1
#SBATCH --output=logs/%A_%a.out
set -euo pipefail
jobs_file="${1:?usage: sbatch --array=0-(N-1) $0 JOBS.jsonl [batch options]}"
shift
: "${SLURM_ARRAY_TASK_ID:?not an array task: submit this script with sbatch --array=0-(N-1)}"
if [ "${SLURM_ARRAY_TASK_MIN:-0}" != 0 ] || [ "${SLURM_ARRAY_TASK_MAX:-}" != "$((SLURM_ARRAY_TASK_COUNT - 1))" ]; then
  echo "mostyle: the array's indices must run from 0 to N-1 (--array=0-$((SLURM_ARRAY_TASK_COUNT - 1))), found" \
       "${SLURM_ARRAY_TASK_MIN:-?}-${SLURM_ARRAY_TASK_MAX:-?}" >&2
  exit 2
fi
cli="${MOSTYLE_CLI:-${SLURM_SUBMIT_DIR:-.}/build/app/mostyle-cli}"
mkdir -p logs
exec "$cli" batch "$jobs_file" \
    --shard "$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT" --jobs "${SLURM_CPUS_PER_TASK:-1}" \
    --summary "logs/summary_$SLURM_ARRAY_TASK_ID.json" --skip-existing "$@"
