#!/usr/bin/env bash
# The results store read and appended like every other file (issue 45, class 3): a FIFO, a device or
# a link at the store's name is refused at once; a 100 000-deep line and wrong-typed fields are one
# line naming file:line and the field (exit 1), never a hang, a crash or exit 2; a link planted at
# the store's name or at its configuration file is never written through.
#   results_store_hostile.sh TRNKIT
set -uo pipefail
T=$1
fail() { echo "FAILED: $*" >&2; exit 1; }
work=$(mktemp -d "$PWD/store-hostile.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
cd "$work" || exit 1

# A real line to start from: one job of the quick sampling study.
"$T" experiment sampling --quick --job kld-0 --no-merge --no-plots --results good.jsonl --out o0 >/dev/null 2>&1 || fail "a job run failed"
[[ $(wc -l <good.jsonl) -eq 1 ]] || fail "no line in the store after one job"

# A trnkit built with AddressSanitizer cannot start under ulimit -v (its shadow reserves terabytes of
# address space): there the memory limit is left out and 5x the time allowed, as tests/cli's limited().
sanitized=no seconds=20
# (ldd's whole output, not a pipe into grep -q: under pipefail its early exit can fail the test.)
if [[ $(ldd "$T" 2>/dev/null) == *libasan* ]]; then sanitized=yes seconds=100; fi

# merge STORE: the merge from STORE alone, under a time and memory limit; sets rc and err.
merge() {
  rm -rf m
  (if [[ $sanitized == no ]]; then ulimit -v 4000000; fi; timeout "$seconds" "$T" experiment sampling --quick --resume --merge --partial --no-plots --results "$1" --out m) >/dev/null 2>err
  rc=$?
  err=$(cat err)
}
# expect STORE RC TEXT WHAT: the merge exits RC and says TEXT.
expect() {
  merge "$1"
  [[ $rc -eq $2 ]] || fail "$4: exit $rc, expected $2 ($err)"
  grep -qF -- "$3" err || fail "$4: the message lacks '$3': $err"
  [[ $(wc -l <err) -eq 1 ]] || fail "$4: not one line: $err"
}
# edit EXPRESSION: good.jsonl's line with a Python expression applied to it (j) as edited.jsonl.
edit() {
  python3 -c "import json,sys; j=json.loads(open('good.jsonl').read()); $1; print(json.dumps(j))" >edited.jsonl || fail "edit $1"
}

merge good.jsonl
[[ $rc -eq 0 ]] || fail "the merge of a good store failed: $err"

mkfifo fifo.jsonl
expect fifo.jsonl 1 "fifo.jsonl: is a FIFO, not a regular file" "a FIFO store"
ln -s /dev/zero zero.jsonl
expect zero.jsonl 1 "zero.jsonl: is a symbolic link" "a store linked to /dev/zero"
expect /dev/zero 1 "/dev/zero: is a character device" "/dev/zero as the store"
# A line of the store whose result holds a 100 000-deep array (the merge crashed on it: exit 139).
python3 -c "import sys; print(open('good.jsonl').read().strip().replace('\"result\":{', '\"result\":{\"deep\":' + '[' * 100000 + ']' * 100000 + ',', 1))" >deep.jsonl
grep -q '"deep":\[\[' deep.jsonl || fail "no deep field in the line"
expect deep.jsonl 1 "deep.jsonl:1: JSON nested deeper than 64 levels" "a 100000-deep line"

edit 'j["result"]["best_error_m"] = "x"'
expect edited.jsonl 1 "edited.jsonl:1: field result.best_error_m is a string" "a result field of the wrong type"
edit 'j["result"] = [1]'
expect edited.jsonl 1 "edited.jsonl:1: field result is an array, not an object" "a result that is no object"
edit 'j["params"]["method"] = 5'
expect edited.jsonl 1 "edited.jsonl:1: field params is " "params of the wrong type"
edit 'j["params"] = "kld"'
expect edited.jsonl 1 "edited.jsonl:1: field params is a string" "params that are no object"
edit 'j["wall_s"] = "slow"'
expect edited.jsonl 1 "edited.jsonl:1: field wall_s is a string" "wall_s of the wrong type"
edit 'j["job"] = 7'
expect edited.jsonl 1 "edited.jsonl:1: field job is a number, not a string" "a job id of the wrong type"
edit 'j["commit"] = []'
expect edited.jsonl 1 "edited.jsonl:1: field commit is an array" "a commit of the wrong type"
# A second line whose field has another kind than the first line's.
edit 'j["job"] = "kld-1"; j["params"]["start"] = 1; j["result"]["seconds"] = [1, 2]'
cat good.jsonl edited.jsonl >two.jsonl
expect two.jsonl 1 "two.jsonl:2: field result.seconds is an array where line 1 has a number" "a field of another kind than line 1's"
# A field the merge needs, missing: exit 1 with the reason, not exit 2.
edit 'del j["result"]["success"]'
expect edited.jsonl 1 "cannot be merged: a field is missing or of another type" "a missing result field"

# Links planted at the names the store writes: refused, their targets untouched.
mkdir -p results/sampling/configs
echo "not yours" >victim
ln -s "$work/victim" results/sampling/ours-quick.jsonl
"$T" experiment sampling --quick --job kld-0 --no-merge --no-plots --out o1 >/dev/null 2>err && fail "a job appended through a planted link"
grep -qF "ours-quick.jsonl: is a symbolic link" err || fail "the planted store link is not named: $(cat err)"
[[ $(cat victim) == "not yours" ]] || fail "the link's target was written"
[[ ! -e o1/jobs/kld-0.json ]] || fail "the job ran before the store was refused"
rm results/sampling/ours-quick.jsonl
hash=$(python3 -c "import json; print(json.loads(open('good.jsonl').read())['config'])")
ln -s "$work/victim" "results/sampling/configs/$hash.json"
"$T" experiment sampling --quick --job kld-0 --no-merge --no-plots --out o2 >/dev/null 2>err && fail "a configuration was written through a planted link"
grep -qF "$hash.json: is a symbolic link" err || fail "the planted configuration link is not named: $(cat err)"
[[ $(cat victim) == "not yours" ]] || fail "the configuration link's target was written"
echo "results store: FIFO, device, links, deep and wrong-typed lines refused with file:line and field"
