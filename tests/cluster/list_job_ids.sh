#!/usr/bin/env bash
# --list-jobs=ids prints exactly the ids the command listing passes to --job, one a line (=keys: with
# their inputs keys); --job A,B runs those two in one process; the command
# listing quotes an output folder holding shell syntax as one word; --prepare creates and marks the
# folder, counts the finished jobs and runs none.
#   list_job_ids.sh TRNKIT
set -euo pipefail
trnkit=$1
fail() { echo "FAILED: $*" >&2; exit 1; }
work=$(mktemp -d "$PWD/ids.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
out="$work/it's \$(touch $work/EXECUTED)"

"$trnkit" experiment sampling --quick --list-jobs=ids >"$work/ids"
"$trnkit" experiment sampling --quick --out "$out" --list-jobs >"$work/commands"
[[ $(wc -l <"$work/ids") -ge 2 ]] || fail "too few ids"
[[ $(wc -l <"$work/commands") -eq $(($(wc -l <"$work/ids") + 1)) ]] || fail "one command per id plus the merge expected"
# Each printed command is read back by a shell as words (the test's own, trusted, output).
while read -r line; do
  eval "set -- $line"
  [[ $* == *--merge* ]] && continue
  for ((i = 1; i < $#; i++)); do
    [[ ${!i} == --out ]] && { j=$((i + 1)); [[ ${!j} == "$out" ]] || fail "--out read back as '${!j}'"; }
    [[ ${!i} == --job ]] && { j=$((i + 1)); echo "${!j}"; }
  done
done <"$work/commands" >"$work/ids_from_commands"
cmp "$work/ids" "$work/ids_from_commands" || fail "--list-jobs=ids differs from the ids in the commands"
[[ ! -e $work/EXECUTED ]] || fail "the listing let the shell run text from --out"

"$trnkit" experiment sampling --quick --out "$out" --prepare 2>"$work/prepare.log"
grep -q "0 of $(wc -l <"$work/ids") jobs finished" "$work/prepare.log" || fail "--prepare: $(cat "$work/prepare.log")"
[[ -f $out/.trnkit-output && -d $out/jobs && -z $(ls -A "$out/jobs") ]] || fail "--prepare did not just create the marked folder"
! "$trnkit" experiment sampling --quick --list-jobs=all >/dev/null 2>&1 || fail "--list-jobs=all accepted"

# --list-jobs=keys: the same ids in the same order, each with one word after it (its inputs key).
"$trnkit" experiment sampling --quick --list-jobs=keys >"$work/keys"
awk 'NF != 2 { exit 1 } { print $1 }' "$work/keys" | cmp - "$work/ids" || fail "--list-jobs=keys: not 'id key' lines of the same ids"
# --job A,B runs just those two, in one process; an unknown id among them is refused before anything runs.
first=$(sed -n 1p "$work/ids") second=$(sed -n 2p "$work/ids")
"$trnkit" experiment sampling --quick --no-plots --results none --out "$work/two" --job "$first,$second" --no-merge 2>/dev/null || fail "--job A,B failed"
[[ $(find "$work/two/jobs" -maxdepth 1 -name '*.json' | wc -l) -eq 2 && -f $work/two/jobs/$first.json && -f $work/two/jobs/$second.json ]] ||
  fail "--job $first,$second did not run exactly those two"
! "$trnkit" experiment sampling --quick --results none --out "$work/three" --job "$first,no-such-job" --no-merge >"$work/bad" 2>&1 || fail "an unknown id in --job accepted"
grep -q -- "--job no-such-job: no such job" "$work/bad" || fail "unknown id: $(cat "$work/bad")"
[[ ! -e $work/three ]] || fail "an unknown id in --job created the output folder"
echo "ids: $(wc -l <"$work/ids") ids equal the commands' --job arguments"
