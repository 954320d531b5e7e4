#!/usr/bin/env bash
# scripts/experiment-parallel with the results store (issue 27): --batch runs part of a study and
# merges it as partial; so does --only ERE (the matching ids); a later --resume run into a fresh output folder dispatches only the jobs the
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
# --only: just the ids matching the expression (here the last job's), merged as partial; a bad
# expression is refused before anything runs.
last=$("$trnkit" experiment "$study" --quick --list-jobs=ids | tail -1)
"$scripts/experiment-parallel" --jobs 2 --only "${last//./\\.}" --trnkit "$trnkit" "$study" --quick --no-plots --resume --results "$store" \
  --out "$work/a" >"$work/only.log" 2>&1 || { cat "$work/only.log"; fail "the --only run failed"; }
grep -q -- "--only .*: 1 of the $((n - 2)) jobs still to run" "$work/only.log" || fail "--only did not select one job: $(cat "$work/only.log")"
[[ $(wc -l <"$store") -eq 3 ]] || fail "--only did not run exactly one job"
grep -q "\"job\":\"$last\"" "$store" || fail "--only did not run $last"
grep -q PARTIAL "$work/a/results.md" || fail "the --only merge is not marked partial"
! "$scripts/experiment-parallel" --only '(' --trnkit "$trnkit" "$study" --quick --resume --results "$store" --out "$work/a" >"$work/bad.log" 2>&1 ||
  fail "--only '(' was accepted"
grep -q "not an extended regular expression" "$work/bad.log" || fail "--only '(' not refused by name: $(cat "$work/bad.log")"
[[ $(wc -l <"$store") -eq 3 ]] || fail "a refused --only ran jobs"
(cd "$work" && "$scripts/experiment-parallel" --jobs 2 --trnkit "$trnkit" "$study" --quick --no-plots --resume --results "store dir/$study.jsonl" --out b) \
  >"$work/b.log" 2>&1 || { cat "$work/b.log"; fail "the resumed run failed"; }
grep -q ": $((n - 3)) jobs in [0-9]* processes into" "$work/b.log" || fail "the resumed run did not dispatch only the $((n - 3)) missing jobs: $(cat "$work/b.log")"
[[ $(wc -l <"$store") -eq $n ]] || fail "the store does not hold each of the $n jobs once"
! grep -q PARTIAL "$work/b/results.md" || fail "the resumed merge is partial"
head -1 "$work/b/results.md" | grep -q "$n of $n jobs ($n from the results store" || fail "the merge did not read the store"
"$trnkit" experiment "$study" --quick --no-plots --results none --out "$work/serial" >/dev/null 2>&1 || fail "the serial run failed"
for f in "$work/serial"/table_*.md; do
  cmp -s -- "$f" "$work/b/${f##*/}" || diff -- "$f" "$work/b/${f##*/}" || fail "${f##*/} differs from the serial run's"
done
echo "parallel + store: a batch of 2, one job by --only, then the other $((n - 3)) resumed from the store; tables equal the serial run's"
