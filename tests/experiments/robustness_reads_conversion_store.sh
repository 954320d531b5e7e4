#!/usr/bin/env bash
# Robustness flies a subset of the conversion study's flights (same ids, flown the same way): with
# --resume it counts conversion's default store, so those flights are not flown again; the merge
# says how many came from there; the ids it lacks still run and go to its own store; and with an
# explicit --results file (or another configuration) nothing is borrowed.
#   robustness_reads_conversion_store.sh TRNKIT
set -uo pipefail
T=$1
fail() { echo "FAILED: $*" >&2; exit 1; }
work=$(mktemp -d "$PWD/shared.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
cd "$work" || exit 1
all=$("$T" experiment robustness --quick --list-jobs=ids | sort)
"$T" experiment conversion --quick --no-plots --no-merge --out c >/dev/null 2>&1 || fail "conversion --quick failed"
flown=$(python3 -c "import json; print('\n'.join(json.loads(l)['job'] for l in open('results/conversion/ours-quick.jsonl')))" | sort)
overlap=$(comm -12 <(echo "$all") <(echo "$flown"))
[[ -n $overlap ]] || fail "the quick studies share no flight; this test checks nothing"
left=$("$T" experiment robustness --quick --resume --list-jobs=ids | sort)
[[ $left == "$(comm -23 <(echo "$all") <(echo "$flown"))" ]] || fail "--resume lists ${left//$'\n'/ }, expected the ids conversion has not flown"
# Without --resume, or with another store file, every job is listed.
[[ $("$T" experiment robustness --quick --list-jobs=ids | wc -l) -eq $(echo "$all" | wc -l) ]] || fail "without --resume jobs were dropped"
[[ $("$T" experiment robustness --quick --resume --results own.jsonl --list-jobs=ids | wc -l) -eq $(echo "$all" | wc -l) ]] ||
  fail "an explicit --results file borrowed conversion's flights"
[[ $("$T" experiment robustness --quick --seed 2 --resume --list-jobs=ids | wc -l) -eq $(echo "$all" | wc -l) ]] ||
  fail "another seed borrowed conversion's flights"
# The run flies only the rest, stores only those, and the merge names both sources.
"$T" experiment robustness --quick --resume --no-plots --out r >r.log 2>r.err || { cat r.err; fail "robustness --resume failed"; }
[[ $(sort <(python3 -c "import json; print('\n'.join(json.loads(l)['job'] for l in open('results/robustness/ours-quick.jsonl')))")) == "$left" ]] ||
  fail "robustness stored other flights than the ones it lacked"
for id in $overlap; do [[ ! -e r/jobs/$id.json ]] || fail "$id was flown again"; done
n_overlap=$(echo "$overlap" | wc -l)
head -1 r/results.md | grep -q "($n_overlap flights of conversion from results/conversion/ours-quick.jsonl" ||
  fail "results.md does not name the borrowed flights: $(head -1 r/results.md)"
# The same flights give the same numbers: a borrowed line equals the one robustness would make.
id=$(echo "$overlap" | head -1)
"$T" experiment robustness --quick --job "$id" --no-merge --no-plots --results none --out again >/dev/null 2>&1 || fail "re-flying $id failed"
python3 - "$id" <<'PY' || fail "robustness's own flight of $id differs from conversion's line"
import json, sys
job = sys.argv[1]
stored = next(json.loads(l) for l in open('results/conversion/ours-quick.jsonl') if json.loads(l)['job'] == job)['result']
mine = json.load(open(f'again/jobs/{job}.json'))['result']
def rounded(v):
    if isinstance(v, float): return float(f'{v:.6g}')
    if isinstance(v, dict): return {k: rounded(x) for k, x in v.items()}
    if isinstance(v, list): return [rounded(x) for x in v]
    return v
assert rounded(mine) == stored, (mine, stored)
PY
echo "robustness: $n_overlap of $(echo "$all" | wc -l) quick flights read from conversion's store, the rest flown and stored"
