#!/usr/bin/env bash
# scripts/experiment-parallel on the local cores runs every job of a --quick study and merges; the
# tables equal a plain serial run's byte for byte (only provenance.json and timings may differ),
# with the jobs of one inputs key grouped (--group 2: one process per two of them) as without. The
# output folder's name is shell syntax that creates a file if anything evaluated it: nothing may.
# A second run resumes: every job is found finished, none runs again, and the merge is repeated.
#   parallel_matches_serial.sh TRNKIT SCRIPTS_DIR STUDY
set -euo pipefail
trnkit=$1 scripts=$2 study=$3
fail() { echo "FAILED: $*" >&2; exit 1; }
command -v parallel >/dev/null || { echo "SKIPPED: GNU parallel is not installed (Debian package parallel; scripts/install-deps.sh)"; exit 77; }

work=$(mktemp -d "$PWD/parallel.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
out="$work/par \$(touch $work/EXECUTED) 'q\"; touch $work/EXECUTED2"

"$scripts/experiment-parallel" --jobs 2 --group 2 --trnkit "$trnkit" "$study" --quick --no-plots --out "$out" >"$work/parallel.log" 2>&1 ||
  { cat "$work/parallel.log"; fail "experiment-parallel failed"; }
"$trnkit" experiment "$study" --quick --no-plots --out "$work/serial" >/dev/null 2>&1 || fail "the serial run failed"
[[ ! -e $work/EXECUTED && ! -e $work/EXECUTED2 ]] || fail "text from --out was executed by a shell"

n=$("$trnkit" experiment "$study" --quick --list-jobs=ids | wc -l)
[[ $(find "$out/jobs" -maxdepth 1 -name '*.json' | wc -l) -eq $n ]] || fail "expected $n job outputs in $out/jobs"
# One process per (up to) two jobs of a key: the joblog has a line per process.
processes=$("$trnkit" experiment "$study" --quick --list-jobs=keys | awk '{ n[$2]++ } END { for (k in n) p += int((n[k] + 1) / 2); print p }')
((processes < n)) || fail "the study's $n jobs share no inputs key: grouping is not tested"
[[ $(wc -l <"$out/dispatch/parallel-joblog.tsv") -eq $processes ]] || fail "the joblog does not list $processes processes"
compared=0
for f in "$work/serial"/*.md "$work/serial"/*.csv; do
  cmp -- "$f" "$out/${f##*/}" || fail "${f##*/} differs from the serial run's"
  compared=$((compared + 1))
done
((compared >= 2)) || fail "the serial run wrote no tables to compare"
! grep -q PARTIAL "$out/results.md" || fail "the merge is partial"

touch -d 2001-01-01 "$out"/jobs/*.json
"$scripts/experiment-parallel" --jobs 2 --group 2 --trnkit "$trnkit" "$study" --quick --no-plots --out "$out" >"$work/resume.log" 2>&1 ||
  { cat "$work/resume.log"; fail "the second run failed"; }
grep -q "$n of $n jobs finished" "$work/resume.log" || fail "the second run did not find every job finished"
[[ -z $(find "$out/jobs" -name '*.json' -newermt 2002-01-01) ]] || fail "the second run ran finished jobs again"
[[ $(wc -l <"$out/dispatch/parallel-joblog.tsv") -eq $((2 * processes)) ]] || fail "the joblog was not appended to"
echo "parallel: $n jobs, $compared tables equal the serial run's; the resumed run re-ran none"
