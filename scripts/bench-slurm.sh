#!/usr/bin/env bash
# Runs a `kautham bench` campaign on a Slurm cluster: a job array of N shards, then a job that
# merges them and writes the report.
#
# Usage:
#   scripts/bench-slurm.sh [OPTIONS] -o OUT -- [kautham bench ARGUMENTS...]
#
#   Array task i (1..N) runs     $KAUTHAM bench ARGUMENTS --shard i/N -o OUT/shard-i
#   then, once every task ended well (sbatch --dependency=afterok), one job runs
#                                $KAUTHAM bench --merge-only -o OUT OUT/shard-1 ... OUT/shard-N
#                                $PYTHON scripts/bench-report.py OUT -o OUT/report [REPORT ARGS]
#   so OUT/logs/<problem>.log holds every run and OUT/report/index.html shows the figures.
#
# Options:
#   -o, --output OUT        campaign folder; on a cluster it must be on storage that every node
#                           sees (required)
#   -n, --shards N          number of array tasks (default 4)
#   -p, --partition P       Slurm partition (default: the cluster's default partition)
#   -t, --time T            time limit of each array task, in Slurm's format (default 04:00:00);
#                           a shard's runs x planners x --time must fit, with validation
#   -c, --cpus-per-task C   CPUs of each array task (default 1); give kautham bench
#                           --threads K --jobs J with K x J = C
#       --mem M             memory of each array task (sbatch --mem, e.g. 4G; default: the
#                           cluster's default)
#       --max-running M     run at most M array tasks at once (--array=1-N%M)
#       --merge-time T      time limit of the merge-and-report job (default 00:30:00)
#       --sbatch-args "..." more sbatch options for both jobs (e.g. "--account=A --qos=Q")
#       --report-args "..." options of bench-report.py (e.g. "--paper")
#       --no-report         merge only
#       --dry-run           write the batch scripts and print the sbatch commands; submit nothing
#       --force             submit to an OUT that already holds a submitted campaign
#                           (OUT/slurm/jobs.txt)
#   -h, --help              this text
#
# Environment: KAUTHAM (default: build/apps/kautham of this repository), PYTHON for the report
# (default /usr/bin/python3: Debian's, with matplotlib), SBATCH (default sbatch).
# Relative paths in the bench arguments (--file bench.json, problem files) are resolved in the
# directory sbatch is run from, where the jobs start. kautham bench's exit codes 0 (every run
# finished, solved or not) and 1 (some run crashed or failed: the logs record it) count as a
# task that ended well; 2 (bad input), 130 (interrupted), a kill or Slurm's time limit fail it,
# and then the merge job is cancelled (--kill-on-invalid-dep=yes): look at OUT/slurm/*.out,
# resubmit the shard by hand (`sbatch --array=i OUT/slurm/shard.sbatch`), then the merge
# (`sbatch --dependency=afterok:JOBID OUT/slurm/merge.sbatch`).
#
# Example (4 shards of 2 CPUs; 30 runs of every planner on every problem of bench.json):
#   scripts/bench-slurm.sh -n 4 -c 2 -t 06:00:00 -o /shared/campaign1 -- \
#     --file bench.json --runs 30 --seed 1 --time 60 --threads 2 --jobs 1 --validate 100
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
KAUTHAM=${KAUTHAM:-$ROOT/build/apps/kautham}
PYTHON=${PYTHON:-/usr/bin/python3}
SBATCH=${SBATCH:-sbatch}
REPORT=$ROOT/scripts/bench-report.py

die() { echo "bench-slurm: $*" >&2; exit 2; }
usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; }

out="" shards=4 partition="" tasktime=04:00:00 cpus=1 mem="" maxrunning="" mergetime=00:30:00
sbatchargs="" reportargs="" report=1 dryrun=0 force=0
need() { if [ $# -lt 2 ] || [ -z "$2" ]; then die "$1 needs a value (see --help)"; fi; }
while [ $# -gt 0 ]; do
  case $1 in
    -o|--output) need "$@"; out=$2; shift 2 ;;
    -n|--shards) need "$@"; shards=$2; shift 2 ;;
    -p|--partition) need "$@"; partition=$2; shift 2 ;;
    -t|--time) need "$@"; tasktime=$2; shift 2 ;;
    -c|--cpus-per-task) need "$@"; cpus=$2; shift 2 ;;
    --mem) need "$@"; mem=$2; shift 2 ;;
    --max-running) need "$@"; maxrunning=$2; shift 2 ;;
    --merge-time) need "$@"; mergetime=$2; shift 2 ;;
    --sbatch-args) need "$@"; sbatchargs=$2; shift 2 ;;
    --report-args) need "$@"; reportargs=$2; shift 2 ;;
    --no-report) report=0; shift ;;
    --dry-run) dryrun=1; shift ;;
    --force) force=1; shift ;;
    -h|--help) usage; exit 0 ;;
    --) shift; break ;;
    *) die "unknown option '$1': kautham bench's arguments go after '--' (see --help)" ;;
  esac
done
bench=("$@")

[ -n "$out" ] || die "-o OUT is required (see --help)"
[[ $shards =~ ^[1-9][0-9]*$ ]] || die "--shards must be a positive integer, not '$shards'"
[[ $cpus =~ ^[1-9][0-9]*$ ]] || die "--cpus-per-task must be a positive integer, not '$cpus'"
[ -z "$maxrunning" ] || [[ $maxrunning =~ ^[1-9][0-9]*$ ]] ||
  die "--max-running must be a positive integer, not '$maxrunning'"
for a in "${bench[@]}"; do
  case $a in
    --shard|--shard=*|-o|--output|--output=*|--merge-only)
      die "'$a' is set by this script: leave it out of the bench arguments" ;;
  esac
done
# kautham bench's --threads K and --jobs J use K x J CPUs: say so if that is not what Slurm gives.
threads=1 jobs=1
for ((k = 0; k < ${#bench[@]}; k++)); do
  case ${bench[k]} in
    --threads) threads=${bench[k + 1]:-1} ;;
    --threads=*) threads=${bench[k]#*=} ;;
    --jobs) jobs=${bench[k + 1]:-1} ;;
    --jobs=*) jobs=${bench[k]#*=} ;;
  esac
done
if [[ $threads =~ ^[0-9]+$ && $jobs =~ ^[0-9]+$ ]] && [ $((threads * jobs)) -ne "$cpus" ]; then
  echo "bench-slurm: note: --threads $threads x --jobs $jobs = $((threads * jobs)) CPUs, but" \
       "each task gets --cpus-per-task $cpus" >&2
fi
if [ ! -x "$KAUTHAM" ]; then
  if [ $dryrun -eq 1 ]; then
    echo "bench-slurm: note: $KAUTHAM is not an executable (set KAUTHAM)" >&2
  else
    die "$KAUTHAM is not an executable: build it (scripts/build.sh) or set KAUTHAM"
  fi
fi
KAUTHAM=$(cd "$(dirname "$KAUTHAM")" && pwd)/$(basename "$KAUTHAM")
if [ $report -eq 1 ] && [ ! -x "$PYTHON" ]; then
  die "$PYTHON not found for the report: set PYTHON, or give --no-report"
fi
command -v "$SBATCH" >/dev/null 2>&1 || [ $dryrun -eq 1 ] ||
  die "'$SBATCH' not found: is this a Slurm submit host? (scripts/slurm-localhost.sh sets up one)"

mkdir -p "$out/slurm"
out=$(cd "$out" && pwd)
if [ -e "$out/slurm/jobs.txt" ] && [ $force -eq 0 ] && [ $dryrun -eq 0 ]; then
  die "$out already holds a submitted campaign ($out/slurm/jobs.txt): another -o, or --force"
fi

# Resources as #SBATCH lines, so that a batch script resubmitted by hand gets them too
directives() {  # cpus time mem
  [ -n "$partition" ] && echo "#SBATCH --partition=$partition"
  echo "#SBATCH --cpus-per-task=$1"
  echo "#SBATCH --time=$2"
  [ -n "$3" ] && echo "#SBATCH --mem=$3"
  return 0
}
# More options for both jobs, on the command line
common=()
# shellcheck disable=SC2206 # word splitting wanted: several sbatch options
[ -n "$sbatchargs" ] && common+=($sbatchargs)

q() { printf '%q ' "$@"; }

cat >"$out/slurm/shard.sbatch" <<EOF
#!/usr/bin/env bash
# Written by scripts/bench-slurm.sh: one shard of a kautham bench campaign (array task i of $shards).
#SBATCH --job-name=kautham-bench
#SBATCH --output=$out/slurm/shard-%A_%a.out
$(directives "$cpus" "$tasktime" "$mem")
set -uo pipefail
i=\${SLURM_ARRAY_TASK_ID:?run as a Slurm array task: sbatch --array=1-$shards $out/slurm/shard.sbatch}
echo "kautham bench shard \$i/$shards on \$(hostname), job \${SLURM_JOB_ID:-?}, \${SLURM_CPUS_PER_TASK:-?} CPUs, started \$(date -Is)"
set -x
$(q "$KAUTHAM" bench "${bench[@]}")--shard "\$i/$shards" -o "$out/shard-\$i"
rc=\$?
set +x
echo "kautham bench exit code \$rc, ended \$(date -Is)"
# kautham bench: 0 every run finished, 1 some run crashed or failed (in the logs), 2 bad input,
# 130 interrupted; more: killed.
if [ \$rc -gt 1 ]; then exit \$rc; fi
ls "$out/shard-\$i"/logs/*.log >/dev/null 2>&1 || echo "warning: no log in $out/shard-\$i/logs"
exit 0
EOF

what="merges the $shards shards of a kautham bench campaign"
[ $report -eq 1 ] && what+=" and writes the report"
shard_dirs=""
for ((i = 1; i <= shards; i++)); do shard_dirs+=" $(q "$out/shard-$i")"; done
{
  cat <<EOF
#!/usr/bin/env bash
# Written by scripts/bench-slurm.sh: $what.
#SBATCH --job-name=kautham-bench-merge
#SBATCH --output=$out/slurm/merge-%j.out
$(directives 1 "$mergetime" "")
#SBATCH --kill-on-invalid-dep=yes
set -euo pipefail
echo "merging on \$(hostname), started \$(date -Is)"
shards=()
for d in$shard_dirs; do
  if [ -d "\$d" ]; then shards+=("\$d"); else echo "warning: no shard folder \$d"; fi
done
set -x
rc=0
$(q "$KAUTHAM") bench --merge-only -o $(q "$out") "\${shards[@]}" || rc=\$?
if [ \$rc -gt 1 ]; then exit \$rc; fi
EOF
  if [ $report -eq 1 ]; then
    # shellcheck disable=SC2086 # word splitting wanted: several report options
    q "$PYTHON" "$REPORT" "$out" -o "$out/report" $reportargs
    echo
  fi
  echo "set +x"
  echo "echo \"ended \$(date -Is)\""
} >"$out/slurm/merge.sbatch"
chmod +x "$out/slurm/shard.sbatch" "$out/slurm/merge.sbatch"

array="1-$shards${maxrunning:+%$maxrunning}"
shard_cmd=("$SBATCH" --parsable "${common[@]}" --array="$array" "$out/slurm/shard.sbatch")
merge_cmd=("$SBATCH" --parsable "${common[@]}")

if [ $dryrun -eq 1 ]; then
  echo "bench-slurm: dry run; wrote $out/slurm/shard.sbatch and $out/slurm/merge.sbatch; would run:"
  echo "  $(q "${shard_cmd[@]}")"
  echo "  $(q "${merge_cmd[@]}" --dependency=afterok:ARRAYJOBID "$out/slurm/merge.sbatch")"
  exit 0
fi

array_job=$("${shard_cmd[@]}")
array_job=${array_job%%;*}
[[ $array_job =~ ^[0-9]+$ ]] || die "sbatch did not give a job id: '$array_job'"
merge_job=$("${merge_cmd[@]}" --dependency=afterok:"$array_job" "$out/slurm/merge.sbatch")
merge_job=${merge_job%%;*}
printf 'array %s\nmerge %s\nsubmitted %s\n' "$array_job" "$merge_job" "$(date -Is)" \
  >>"$out/slurm/jobs.txt"
cat <<EOF
bench-slurm: submitted array job $array_job ($shards tasks: $out/shard-1 .. $out/shard-$shards)
bench-slurm: submitted merge job $merge_job (after every task of $array_job ended well)
  watch:   squeue -j $array_job,$merge_job
  logs:    $out/slurm/shard-${array_job}_<i>.out, $out/slurm/merge-$merge_job.out
  result:  $out/logs/<problem>.log$([ $report -eq 1 ] && echo ", $out/report/index.html")
  cancel:  scancel $array_job $merge_job
EOF
