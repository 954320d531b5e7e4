#!/usr/bin/env bash
# The results store (issue 27): every job appends one line; --resume skips the jobs it holds and the
# merge builds the tables from it (a fresh output folder needs no job files); a line cut off by a
# killed writer is ignored and does not swallow the next one; lines of another configuration are
# ignored with a note naming them; a writer killed mid-job leaves the store readable.
#   results_store.sh TRNKIT
set -uo pipefail
T=$1
fail() { echo "FAILED: $*" >&2; exit 1; }
work=$(mktemp -d "$PWD/store.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
cd "$work" || exit 1
S=$work/store/sampling.jsonl
n=$("$T" experiment sampling --quick --list-jobs=ids | wc -l)
readable() { python3 -c "import json,sys; [json.loads(l) for l in open(sys.argv[1]) if l.strip()]" "$1"; }

# One job, then the default store path under the working folder.
"$T" experiment sampling --quick --job kld-0 --no-merge --no-plots --out o0 >/dev/null 2>&1 || fail "a job run failed"
[[ $(wc -l <results/sampling/ours-quick.jsonl) -eq 1 ]] || fail "no line in the default store results/sampling/ours-quick.jsonl"
[[ -s results/sampling/configs/$(python3 -c "import json; print(json.loads(open('results/sampling/ours-quick.jsonl').readline())['config'])").json ]] ||
  fail "the configuration of the line is not beside the store"

"$T" experiment sampling --quick --job kld-0 --no-merge --no-plots --results "$S" --out o1 >/dev/null 2>&1 || fail "a job run failed"
[[ $(wc -l <"$S") -eq 1 ]] || fail "the store has not one line after one job"
line=$(head -1 "$S")
for key in '"job":"kld-0"' '"config":"' '"commit":"' '"params":{"method":"kld","start":0}' '"result":{' '"wall_s":'; do
  grep -qF -- "$key" <<<"$line" || fail "the line lacks $key: $line"
done
[[ ${#line} -lt 700 ]] || fail "the line is ${#line} bytes"
# A writer killed mid-write: a fragment without its newline at the end of the file.
printf '{"job":"kld-1","config":"' >>"$S"

# --resume: the stored job is skipped (no job file for it in a fresh folder), the others run and
# are appended after the fragment, which is reported and left alone.
"$T" experiment sampling --quick --resume --no-plots --results "$S" --out o2 >o2.log 2>o2.err || { cat o2.err; fail "the resumed run failed"; }
[[ ! -e o2/jobs/kld-0.json && -e o2/jobs/kld-1.json ]] || fail "--resume ran a job the store holds, or skipped one it lacks"
grep -q "1 unreadable line(s) ignored" o2.err || fail "the cut-off line was not reported: $(cat o2.err)"
[[ $(grep -c '^{"job"' "$S") -eq $((n + 1)) ]] || fail "expected $n whole lines and the fragment in the store"
head -1 o2/results.md | grep -q "of $n jobs (1 from the results store" || fail "results.md does not say the store's share: $(head -1 o2/results.md)"

# The merge alone, from the store alone, into a fresh folder: the same Table 3.6 (values rounded to
# 6 digits in the store; the table prints at most 1 decimal).
"$T" experiment sampling --quick --resume --merge --no-plots --results "$S" --out o3 >/dev/null 2>o3.err || { cat o3.err; fail "the merge from the store failed"; }
head -1 o3/results.md | grep -q "$n of $n jobs ($n from the results store" || fail "the merge did not read the store: $(head -1 o3/results.md)"
cmp -s <(tail -n +2 o2/table_3_6.md) <(tail -n +2 o3/table_3_6.md) || diff o2/table_3_6.md o3/table_3_6.md || fail "Table 3.6 from the store differs"

# Another configuration (another seed) ignores every line, says so, and lists every job to run.
[[ $("$T" experiment sampling --quick --seed 2 --resume --results "$S" --list-jobs=ids | wc -l) -eq $n ]] || fail "another seed's job list is not whole"
"$T" experiment sampling --quick --seed 2 --resume --merge --results "$S" --out o4 >/dev/null 2>o4.err && fail "a merge of another configuration succeeded"
grep -q "line(s) of another configuration ignored" o4.err || fail "lines of another configuration not reported: $(cat o4.err)"
# This configuration: nothing left to list.
[[ -z $("$T" experiment sampling --quick --resume --results "$S" --list-jobs=ids) ]] || fail "--resume --list-jobs=ids lists finished jobs"

# A run killed while its jobs fly: the store stays whole lines (plus the old fragment).
before=$(grep -c '^{"job"' "$S")
timeout -s KILL 2 "$T" experiment sampling --no-plots --results "$S" --out o5 >/dev/null 2>&1
readable <(grep -vxF '{"job":"kld-1","config":"' "$S") || fail "the store has a broken line after a killed run"
[[ $(grep -c '^{"job"' "$S") -ge $before ]] || fail "lines were lost"
"$T" experiment sampling --quick --results none --job kld-0 --no-merge --out o6 >/dev/null 2>&1 || fail "--results none failed"
echo "results store: $n jobs, resumed, merged from the store alone; fragment and other configuration ignored with notes"
