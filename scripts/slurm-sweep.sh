#!/usr/bin/env bash
# Submits a dampbound sweep to Slurm as a job array of N shards (`sweep --shard K/N`) plus a
# merge job that runs once every shard has succeeded (`--dependency=afterok`). The merged CSV
# holds the same bytes as an unsplit run (`dampbound merge` checks that the parts belong to
# one sweep and cover it exactly once).
#
#   scripts/slurm-sweep.sh -n 16 -o upper.csv [options] -- SWEEP-ARGS...
#
#   -n N            shards (array tasks 1..N)
#   -o FILE         the merged CSV; the parts go to FILE.part<K>.csv beside it
#   -d DIR          where the jobs run and write their logs (default: FILE's directory)
#   --dampbound P   the executable (default: build/app/dampbound, made absolute)
#   --wait          block until the merge job ends; exit non-zero if it failed
#   --sbatch ARGS   extra sbatch arguments for every job (e.g. "--partition=long --time=2:00:00")
#   SWEEP-ARGS      what `dampbound sweep` takes, without -o and --shard
#
# Prints the array and merge job ids. Bad usage: one line on stderr, exit 2.
set -euo pipefail

die() { echo "slurm-sweep.sh: $*" >&2; exit 2; }

shards="" output="" dir="" wait=0 extra=""
dampbound="build/app/dampbound"
while [ $# -gt 0 ]; do
  case "$1" in
    -n) shards=${2:-}; shift 2 || die "-n needs a number" ;;
    -o) output=${2:-}; shift 2 || die "-o needs a file" ;;
    -d) dir=${2:-}; shift 2 || die "-d needs a directory" ;;
    --dampbound) dampbound=${2:-}; shift 2 || die "--dampbound needs a path" ;;
    --sbatch) extra=${2:-}; shift 2 || die "--sbatch needs arguments" ;;
    --wait) wait=1; shift ;;
    --) shift; break ;;
    *) die "unknown option '$1' (sweep arguments go after --)" ;;
  esac
done
[[ "$shards" =~ ^[1-9][0-9]*$ ]] || die "-n: '$shards' is not a positive whole number of shards"
[ -n "$output" ] || die "-o: the merged CSV is required"
[ $# -gt 0 ] || die "no sweep arguments after --"
for a in "$@"; do
  case "$a" in -o|--output|--output=*|--shard|--shard=*) die "'$a' is set by this script" ;; esac
done
command -v sbatch >/dev/null || die "sbatch not found (is Slurm's client installed?)"
[ -x "$dampbound" ] || die "--dampbound: '$dampbound' is not an executable"
dampbound=$(cd "$(dirname "$dampbound")" && pwd)/$(basename "$dampbound")
case "$output" in /*) ;; *) output=$PWD/$output ;; esac
[ -n "$dir" ] || dir=$(dirname "$output")
mkdir -p "$dir" || die "-d: cannot create '$dir'"
dir=$(cd "$dir" && pwd)

# The shard job: one array task per part. Arguments are passed quoted, as given.
quoted=$(printf ' %q' "$@")
array_id=$(sbatch --parsable --array=1-"$shards" --job-name=dampbound-sweep \
  --chdir="$dir" --output="$dir/sweep-%A_%a.log" $extra \
  --wrap="exec $(printf %q "$dampbound") sweep$quoted --shard \${SLURM_ARRAY_TASK_ID}/$shards \
-o $(printf %q "$output").part\${SLURM_ARRAY_TASK_ID}.csv --progress lines")
array_id=${array_id%%;*}
parts=""
for k in $(seq 1 "$shards"); do parts+=" $(printf %q "$output.part$k.csv")"; done
merge_id=$(sbatch --parsable --dependency=afterok:"$array_id" --kill-on-invalid-dep=yes \
  --job-name=dampbound-merge --chdir="$dir" --output="$dir/merge-%j.log" $extra \
  --wrap="exec $(printf %q "$dampbound") merge$parts -o $(printf %q "$output")")
merge_id=${merge_id%%;*}
echo "submitted: shards job $array_id (array 1-$shards), merge job $merge_id -> $output"
[ "$wait" -eq 1 ] || exit 0

# --wait: poll until the merge job has left the queue, then ask for its final state.
while squeue -h -j "$merge_id" 2>/dev/null | grep -q .; do sleep 1; done
state=$(sacct -n -X -P -j "$merge_id" -o State 2>/dev/null | head -1 || true)
if [ -z "$state" ]; then  # no accounting storage: the controller still remembers the job
  state=$(scontrol show job "$merge_id" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p')
fi
echo "merge job $merge_id: ${state:-unknown}"
[ "$state" = "COMPLETED" ] && [ -s "$output" ]
