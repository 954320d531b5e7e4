# shellcheck shell=bash
# Shared by scripts/experiment-parallel and scripts/experiment-slurm (sourced, not run): reads
# "NAME [trnkit experiment options]", checks them, and prepares the study's output folder.
# Nothing from the options or the job list is ever evaluated as shell text: options travel as
# array elements, job ids as single arguments to --job.

die() { echo "${0##*/}: $*" >&2; exit 1; }

# A path the dispatcher writes (or hands to a program that writes it) must be absent or a plain
# file, never a link or another kind of file: a planted link is refused, not written through.
plain_file_or_absent() {
  [[ ! -L $1 ]] || die "$1 is a symbolic link: not written through (remove it)"
  [[ ! -e $1 || -f $1 ]] || die "$1 exists and is not a plain file"
}

# The trnkit executable: --trnkit PATH, else the build next to these scripts, else PATH.
find_trnkit() {
  local given=$1 here
  here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
  if [[ -n $given ]]; then
    [[ -x $given ]] || die "--trnkit $given: not an executable file"
    trnkit=$(realpath -- "$given")
  elif [[ -x $here/build/apps/trnkit/trnkit ]]; then
    trnkit=$here/build/apps/trnkit/trnkit
  else
    trnkit=$(command -v trnkit) || die "no trnkit: build it (./run build) or pass --trnkit PATH"
  fi
}

# Sets study, out (absolute), results (the results store, absolute), resume (--resume given) and
# experiment_options (the options with --out and --results made absolute, so jobs that run in
# another folder or on another host write to the same place) from "NAME [options]". Without
# --results the store is trnkit's default, results/NAME/PROFILE[-quick].jsonl, under this folder.
parse_study_arguments() {
  [[ $# -ge 1 && $1 != -* ]] || die "give the study name, then trnkit experiment options (--out DIR is required)"
  study=$1
  shift
  out="" results="" resume="" profile=ours quick=""
  experiment_options=()
  while [[ $# -gt 0 ]]; do
    case $1 in
      --out) [[ $# -ge 2 ]] || die "--out needs a folder"; out=$2; shift 2; continue ;;
      --out=*) out=${1#--out=}; shift; continue ;;
      --results) [[ $# -ge 2 ]] || die "--results needs a file (or none)"; results=$2; shift 2; continue ;;
      --results=*) results=${1#--results=}; shift; continue ;;
      --resume) resume=1 ;;
      --quick) quick=-quick ;;
      --profile) [[ $# -ge 2 ]] || die "--profile needs ours or dissertation"; profile=$2 ;;
      --profile=*) profile=${1#--profile=} ;;
      --job | --job=* | --list-jobs | --list-jobs=* | --merge | --no-merge | --shard | --shard=* | --prepare)
        die "$1: set by this script (it runs every job by id, then the merge)" ;;
    esac
    experiment_options+=("$1")
    shift
  done
  [[ -n $out ]] || die "--out DIR is required (one folder every job writes into; shared by all hosts)"
  out=$(realpath -m -- "$out")
  experiment_options+=(--out "$out")
  [[ -n $results ]] || results=results/$study/$profile$quick.jsonl
  [[ $results == none ]] || results=$(realpath -m -- "$results")
  experiment_options+=(--results "$results")
}

# Sets job_ids and job_key (id -> inputs key; both from trnkit itself, --list-jobs=keys; with
# --resume only the jobs the results store does not hold), then creates and marks the output folder
# and checks finished jobs against these options, so jobs started at once find it ready; the
# dispatcher's own files go to $out/dispatch/ (created after the folder is marked, so trnkit owns it).
list_and_prepare() {
  local listing id key rest
  listing=$("$trnkit" experiment "$study" "${experiment_options[@]}" --list-jobs=keys) ||
    die "trnkit experiment $study refused the options (see above)"
  # shellcheck disable=SC2034  # job_ids, job_key and dispatch_dir are for the scripts that source this file
  job_ids=()
  declare -gA job_key=()
  if [[ -n $listing ]]; then
    while read -r id key rest; do
      [[ -n $id && -n $key && -z $rest ]] || die "trnkit experiment $study --list-jobs=keys: unexpected line '$id $key $rest'"
      job_ids+=("$id")
      # shellcheck disable=SC2034
      job_key[$id]=$key
    done <<<"$listing"
  elif [[ -z $resume ]]; then
    die "$study: the job list is empty"
  fi
  "$trnkit" experiment "$study" "${experiment_options[@]}" --prepare || die "cannot prepare $out (see above)"
  dispatch_dir=$out/dispatch
  [[ ! -L $dispatch_dir ]] || die "$dispatch_dir is a symbolic link: not written through (remove it)"
  mkdir -p -- "$dispatch_dir"
}

# Sets job_lines from job_ids and job_key: one line per trnkit process, the comma-joined ids of one
# inputs key, at most $1 of them (in job-list order), lines in the order of their first job, so a
# batch keeps the job list's balance. A process builds the maps its jobs share once.
group_job_lines() {
  local most=$1 id key line
  local -A open_line=() line_size=()
  job_lines=()
  for id in "${job_ids[@]}"; do
    key=${job_key[$id]}
    line=${open_line[$key]:-}
    if [[ -z $line || ${line_size[$line]} -ge $most ]]; then
      line=${#job_lines[@]}
      job_lines+=("$id")
      open_line[$key]=$line
      line_size[$line]=1
    else
      job_lines[line]+=",$id"
      line_size[$line]=$((line_size[$line] + 1))
    fi
  done
}
