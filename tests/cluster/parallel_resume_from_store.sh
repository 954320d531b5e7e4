#!/usr/bin/env bash
# scripts/experiment-parallel with the results store (issue 27): --batch runs part of a study and
# merges it as partial; a later --resume run into a fresh output folder dispatches only the jobs the
# store lacks and builds the whole tables from the store; the store holds each job once.
#   parallel_resume_from_store.sh TRNKIT SCRIPTS_DIR STUDY
set -euo pipefail
trnkit=$1 scripts=$2 study=$3
fail() { echo "FAILED: $*" >&2; exit 1; }
command -v parallel >/dev/null || { echo "SKIPPED: GNU parallel is not installed (Debian package parallel; scripts/install-deps.sh)"; exit 77; }
work=$(mktemp -d "$PWD/presume.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
store="$work/store dir/$study.jsonl"
n=$("$trnkit" experiment "$study" --quick --list-jobs=ids | wc -l)
((n >= 3)) || fail "$study --quick has only $n jobs"
"$scripts/experiment-parallel" --jobs 2 --batch 2 --trnkit "$trnkit" "$study" --quick --no-plots --resume --results "$store" --out "$work/a" \
  >"$work/a.log" 2>&1 || { cat "$work/a.log"; fail "the first batch failed"; }
[[ $(wc -l <"$store") -eq 2 ]] || fail "the first batch did not leave 2 lines in the store"
grep -q PARTIAL "$work/a/results.md" || fail "the first batch's merge is not marked partial"
(cd "$work" && "$scripts/experiment-parallel" --jobs 2 --trnkit "$trnkit" "$study" --quick --no-plots --resume --results "store dir/$study.jsonl" --out b) \
  >"$work/b.log" 2>&1 || { cat "$work/b.log"; fail "the resumed run failed"; }
grep -q ": $((n - 2)) jobs into" "$work/b.log" || fail "the resumed run did not dispatch only the $((n - 2)) missing jobs: $(cat "$work/b.log")"
[[ $(wc -l <"$store") -eq $n ]] || fail "the store does not hold each of the $n jobs once"
! grep -q PARTIAL "$work/b/results.md" || fail "the resumed merge is partial"
head -1 "$work/b/results.md" | grep -q "$n of $n jobs ($n from the results store" || fail "the merge did not read the store"
"$trnkit" experiment "$study" --quick --no-plots --results none --out "$work/serial" >/dev/null 2>&1 || fail "the serial run failed"
for f in "$work/serial"/table_*.md; do
  cmp -s -- "$f" "$work/b/${f##*/}" || diff -- "$f" "$work/b/${f##*/}" || fail "${f##*/} differs from the serial run's"
done
echo "parallel + store: a batch of 2, then the other $((n - 2)) resumed from the store; tables equal the serial run's"
