#!/usr/bin/env bash
# The dispatch scripts refuse, with one line naming the problem and before any job runs: a missing
# --out, the options they set themselves, braces GNU parallel would substitute, unknown script
# options and a study trnkit does not know. Nothing is created for a refused call.
#   scripts_refuse_bad_arguments.sh TRNKIT SCRIPTS_DIR
set -euo pipefail
trnkit=$1 scripts=$2
fail() { echo "FAILED: $*" >&2; exit 1; }
work=$(mktemp -d "$PWD/refuse.XXXXXX")
trap 'rm -rf -- "$work"' EXIT

refused() {  # expected text, then the command
  local expected=$1 message
  shift
  if message=$("$@" 2>&1); then fail "accepted: $*"; fi
  [[ $message == *"$expected"* ]] || fail "$*: expected '$expected' in: $message"
}
for script in experiment-parallel experiment-slurm; do
  s=$scripts/$script
  refused "--out DIR is required" "$s" --trnkit "$trnkit" metrics --quick
  refused "--job: set by this script" "$s" --trnkit "$trnkit" metrics --quick --out "$work/a" --job procedural-0
  refused "--merge: set by this script" "$s" --trnkit "$trnkit" metrics --out "$work/a" --merge
  refused "--bogus: unknown option" "$s" --bogus metrics --out "$work/a"
  refused "give the study name" "$s" --trnkit "$trnkit"
  refused "--trnkit $work/none: not an executable" "$s" --trnkit "$work/none" metrics --out "$work/a"
done
if command -v parallel >/dev/null; then
  refused "GNU parallel would replace" "$scripts/experiment-parallel" --trnkit "$trnkit" metrics --quick --out "$work/a{}b"
  refused "refused the options" "$scripts/experiment-parallel" --trnkit "$trnkit" no-such-study --out "$work/a"
  refused "--jobs needs a whole number" "$scripts/experiment-parallel" --jobs 0 metrics --out "$work/a"
  refused "--group needs a whole number" "$scripts/experiment-parallel" --group 0 metrics --out "$work/a"
  # issue 23: ':::' or '::::' in an option would start a GNU parallel input source (the ids were dropped)
  refused "input-source separator" "$scripts/experiment-parallel" --trnkit "$trnkit" --jobs 1 heading --quick --backend ':::' --out "$work/a"
  refused "input-source separator" "$scripts/experiment-parallel" --trnkit "$trnkit" heading --quick --backend '::::' --out "$work/a"
fi
# issue 23: --list-jobs and --prepare (what the dispatchers run first) check --backend too
refused "--backend ':::': unknown backend" "$trnkit" experiment heading --quick --backend ':::' --list-jobs=ids
refused "--backend 'opencl:': after 'opencl:'" "$trnkit" experiment heading --quick --backend 'opencl:' --prepare --out "$work/b"
refused "unknown backend" "$trnkit" experiment heading --quick --backend 'nonsense' --list-jobs
if command -v sbatch >/dev/null; then
  refused "--sbatch needs one sbatch option" "$scripts/experiment-slurm" --sbatch batch metrics --out "$work/a"
  refused "--jobs-per-task needs a whole number" "$scripts/experiment-slurm" --jobs-per-task x metrics --out "$work/a"
fi
[[ -z $(ls -A "$work") ]] || fail "a refused call created $(ls -A "$work")"
echo "refused: every bad call, nothing created"
