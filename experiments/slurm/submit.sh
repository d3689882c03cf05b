#!/usr/bin/env bash
# Submits a sharded run to Slurm: an array job, one shard per task (SLURM_ARRAY_TASK_ID is the
# shard), and a merge job that depends on it.
#   experiments/slurm/submit.sh study      [sbatch options]   certcyl study, then certcyl merge
#   experiments/slurm/submit.sh crosscheck [sbatch options]   the cross-check, then crosscheck-merge.sh
#   experiments/slurm/submit.sh judge      [sbatch options]   certcyl cases (once), certcyl judge
#                                                             --shard, then judge-merge.sh
# The sbatch options (e.g. --partition=P --time=4:00:00, or --hold) go to every job; so do
# sbatch's own SBATCH_* variables. Settings, from the environment:
#   CERTCYL_BUILD    build folder holding bin/certcyl and experiments/crosscheck (default: build);
#                    CERTCYL_BIN and CERTCYL_CROSSCHECK name the programs themselves
#   CERTCYL_SHARDS   number of shards N (default 8); the array is 0..N-1
#   CERTCYL_TASKS    the array indices to submit (default 0-(N-1)); e.g. 3 or 3,5 re-runs only
#                    those shards once the first array has ended, and a new merge job waits
#                    for them
#   CERTCYL_CPUS     CPUs per task (--cpus-per-task, default 1): the tasks' threads
#   CERTCYL_OUT      results root (default: results); output in CERTCYL_OUT/CERTCYL_NAME, the
#                    jobs' logs in its slurm/ folder
#   CERTCYL_NAME     default: the study's size, or crosscheck-QUERY-CASES
#   CERTCYL_SEED     default 1
#   study:       CERTCYL_SIZE (default large), CERTCYL_STUDY_ARGS (more study options, e.g.
#                "--config FILE"), CERTCYL_PLOTS (1: the merge draws the figures when matplotlib
#                is there, the default; 0: it does not)
#   crosscheck:  CERTCYL_QUERY (line, triangle, cylinder or all; default cylinder), CERTCYL_CASES
#                (default 1000000), CERTCYL_FIRST (default 0)
#   judge:       CERTCYL_EXEC (a command answering query lines) or CERTCYL_PLUGIN (a plugin .so),
#                CERTCYL_QUERY (a study query, e.g. line_cylinder; required), CERTCYL_SIZE
#                (default small), CERTCYL_CASES_ARGS (more `certcyl cases` options, e.g.
#                "--family rim"), CERTCYL_TIMEOUT (judge --timeout, default 60), CERTCYL_LABEL
#                (judge --label), CERTCYL_CASES_FILE (default CERTCYL_OUT/CERTCYL_NAME/cases.jsonl):
#                when it does not exist yet, a cases job (judge-cases.sbatch) writes it and the
#                array runs after it (afterok); else the file is judged as it is (so a re-run of
#                some shards judges the cases of the first run); CERTCYL_NAME default judge-QUERY
# The study's merge job runs afterok: only when every task exited 0 (otherwise Slurm cancels it,
# and `certcyl merge` would refuse the missing shard anyway). The cross-check's runs afterany:
# a task that found a wrong answer exits 1, and the merge reports it with the counts, as it
# reports a shard that is missing. The judge's runs afterok, as the study's: a shard whose
# method crashed, hung past the timeout or answered garbage exits 1 and leaves
# shard-K-of-N.partial, which judge-merge.sh refuses when run by hand. Prints the array job's and
# the merge job's ids on standard output (then the cases job's, when one was submitted), what
# was submitted on standard error.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
usage() {
  echo "usage: experiments/slurm/submit.sh study|crosscheck|judge [sbatch options]" >&2
  exit 2
}
[ $# -ge 1 ] || usage
kind=$1
shift
command -v sbatch > /dev/null || { echo "submit: sbatch not found (not a Slurm submit host?)" >&2; exit 1; }

build=$(realpath -m "${CERTCYL_BUILD:-$repo/build}")
export CERTCYL_SHARDS=${CERTCYL_SHARDS:-8}
export CERTCYL_SEED=${CERTCYL_SEED:-1}
CERTCYL_OUT=$(realpath -m "${CERTCYL_OUT:-results}")
export CERTCYL_OUT
[[ "$CERTCYL_SHARDS" =~ ^[1-9][0-9]*$ ]] || { echo "submit: CERTCYL_SHARDS must be a positive integer, got '$CERTCYL_SHARDS'" >&2; exit 2; }
tasks=${CERTCYL_TASKS:-0-$((CERTCYL_SHARDS - 1))}
cpus=${CERTCYL_CPUS:-1}

case "$kind" in
  study)
    CERTCYL_BIN=$(realpath -m "${CERTCYL_BIN:-$build/bin/certcyl}")
    export CERTCYL_BIN
    export CERTCYL_SIZE=${CERTCYL_SIZE:-large}
    export CERTCYL_NAME=${CERTCYL_NAME:-$CERTCYL_SIZE}
    export CERTCYL_STUDY_ARGS=${CERTCYL_STUDY_ARGS:-}
    export CERTCYL_PLOTS=${CERTCYL_PLOTS:-1}
    program=$CERTCYL_BIN
    array_script=$here/study.sbatch
    merge=("$here/study-merge.sbatch")
    dependency=afterok
    ;;
  crosscheck)
    CERTCYL_CROSSCHECK=$(realpath -m "${CERTCYL_CROSSCHECK:-$build/experiments/crosscheck}")
    export CERTCYL_CROSSCHECK
    export CERTCYL_QUERY=${CERTCYL_QUERY:-cylinder}
    export CERTCYL_CASES=${CERTCYL_CASES:-1000000}
    export CERTCYL_FIRST=${CERTCYL_FIRST:-0}
    export CERTCYL_NAME=${CERTCYL_NAME:-crosscheck-$CERTCYL_QUERY-$CERTCYL_CASES}
    program=$CERTCYL_CROSSCHECK
    array_script=$here/crosscheck.sbatch
    merge=("$here/crosscheck-merge.sh" "$CERTCYL_OUT/$CERTCYL_NAME" "$CERTCYL_SHARDS")
    dependency=afterany
    ;;
  judge)
    CERTCYL_BIN=$(realpath -m "${CERTCYL_BIN:-$build/bin/certcyl}")
    export CERTCYL_BIN
    if [ -n "${CERTCYL_EXEC:-}" ] && [ -n "${CERTCYL_PLUGIN:-}" ] || [ -z "${CERTCYL_EXEC:-}${CERTCYL_PLUGIN:-}" ]; then
      echo "submit: judge needs one of CERTCYL_EXEC and CERTCYL_PLUGIN" >&2
      exit 2
    fi
    [ -z "${CERTCYL_PLUGIN:-}" ] || { CERTCYL_PLUGIN=$(realpath -m "$CERTCYL_PLUGIN"); export CERTCYL_PLUGIN; }
    export CERTCYL_QUERY=${CERTCYL_QUERY:?submit: judge needs CERTCYL_QUERY (line_cylinder, ray_cylinder, ...)}
    export CERTCYL_SIZE=${CERTCYL_SIZE:-small}
    export CERTCYL_NAME=${CERTCYL_NAME:-judge-$CERTCYL_QUERY}
    CERTCYL_CASES_FILE=$(realpath -m "${CERTCYL_CASES_FILE:-$CERTCYL_OUT/$CERTCYL_NAME/cases.jsonl}")
    export CERTCYL_CASES_FILE
    export CERTCYL_CASES_ARGS=${CERTCYL_CASES_ARGS:-}
    export CERTCYL_TIMEOUT=${CERTCYL_TIMEOUT:-60}
    program=$CERTCYL_BIN
    array_script=$here/judge.sbatch
    merge=("$here/judge-merge.sh" "$CERTCYL_OUT/$CERTCYL_NAME" "$CERTCYL_SHARDS" "$CERTCYL_CASES_FILE")
    dependency=afterok
    ;;
  *) usage ;;
esac
[ -x "$program" ] || { echo "submit: $program not found: build it first (cmake --build $build --target certcyl_cli crosscheck)" >&2; exit 1; }

logs=$CERTCYL_OUT/$CERTCYL_NAME/slurm
mkdir -p "$logs"
after_cases=()
cases_id=""
if [ "$kind" = judge ] && [ ! -e "$CERTCYL_CASES_FILE" ]; then
  mkdir -p "$(dirname "$CERTCYL_CASES_FILE")"
  cases_id=$(sbatch --parsable --export=ALL --cpus-per-task="$cpus" --output="$logs/%x-%j.out" "$@" "$here/judge-cases.sbatch")
  cases_id=${cases_id%%;*}
  after_cases=(--dependency="afterok:$cases_id" --kill-on-invalid-dep=yes)
fi
array_id=$(sbatch --parsable --export=ALL --array="$tasks" --cpus-per-task="$cpus" "${after_cases[@]}" \
  --output="$logs/%x-%A_%a.out" "$@" "$array_script")
array_id=${array_id%%;*}
merge_id=$(sbatch --parsable --export=ALL --dependency="$dependency:$array_id" --kill-on-invalid-dep=yes \
  --output="$logs/%x-%j.out" "$@" "${merge[@]}")
merge_id=${merge_id%%;*}
echo "submit: $kind, array job $array_id (tasks $tasks of $CERTCYL_SHARDS shards, $cpus CPU(s) each), merge job $merge_id ($dependency), into $CERTCYL_OUT/$CERTCYL_NAME" >&2
[ -z "$cases_id" ] || echo "submit: cases job $cases_id writes $CERTCYL_CASES_FILE first" >&2
echo "$array_id $merge_id${cases_id:+ $cases_id}"
