#!/usr/bin/env bash
# scripts/device-check keeps to its budget and says so: with a 5 s budget every step is recorded as
# skipped in summary.md and the exit status is 1 (not a silent pass); a non-empty --out, an --out
# that is a link and a bad --budget (0, or past 2^63) are usage errors (exit 2). Runs in about a
# second (nothing is built or run).
# usage: device_check_budget.sh REPO_ROOT WORK_DIR
set -uo pipefail
repo=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
fail=0
"$repo/scripts/device-check" --budget 5 --no-bench --out "$work/run" > "$work/run.log" 2>&1
rc=$?
[[ $rc -eq 1 ]] || { echo "FAIL: exit $rc with every step skipped, expected 1"; fail=1; }
grep -q '^| list devices (system) | skipped: budget spent |' "$work/run/summary.md" || { echo "FAIL: summary.md lacks the skipped step"; fail=1; }
grep -q '^| build (' "$work/run/summary.md" || { echo "FAIL: summary.md lacks the build step"; fail=1; }
"$repo/scripts/device-check" --budget 5 --out "$work/run" > "$work/again.log" 2>&1
rc=$?
{ [[ $rc -eq 2 ]] && grep -q "not empty" "$work/again.log"; } || { echo "FAIL: a non-empty --out gave exit $rc"; fail=1; }
"$repo/scripts/device-check" --budget 0 --out "$work/zero" > "$work/zero.log" 2>&1
rc=$?
{ [[ $rc -eq 2 ]] && grep -q -- "--budget" "$work/zero.log"; } || { echo "FAIL: --budget 0 gave exit $rc"; fail=1; }
# issue 45: a budget past 2^63 wrapped to a negative number in bash arithmetic (every step skipped,
# no word said): now a usage error before anything runs.
"$repo/scripts/device-check" --budget 9223372036854775808 --out "$work/huge" > "$work/huge.log" 2>&1
rc=$?
{ [[ $rc -eq 2 && ! -e $work/huge ]] && grep -q -- "--budget" "$work/huge.log"; } || { echo "FAIL: --budget 2^63 gave exit $rc"; fail=1; }
# issue 45: an --out that is a link (to an empty folder elsewhere) is refused, not written through.
mkdir -p "$work/elsewhere" && ln -s elsewhere "$work/link"
"$repo/scripts/device-check" --budget 5 --no-bench --out "$work/link" > "$work/link.log" 2>&1
rc=$?
{ [[ $rc -eq 2 && -z $(ls -A "$work/elsewhere") ]] && grep -q "is a link" "$work/link.log"; } || { echo "FAIL: --out through a link gave exit $rc"; fail=1; }
[[ $fail -eq 0 ]] && echo "ok: device-check budget and usage errors"
exit $fail
