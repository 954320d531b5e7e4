#!/usr/bin/env bash
# issue 45, class 9: KIT/run --budget is a bounded decimal (1 to 999999 s), checked before any
# arithmetic: 2^63 wrapped to a negative number in bash (every step "skipped: budget spent", no
# word about the budget). Now it is a usage error (exit 2) and --out is not created. Fails on 8fd5cd9.
# usage: kit_run_budget_bounded.sh REPO_ROOT WORK_DIR
set -uo pipefail
repo=$1 work=$2
fail() { echo "FAILED: $*" >&2; exit 1; }
rm -rf -- "$work" && mkdir -p -- "$work/tmp" || exit 1
for budget in 9223372036854775808 18446744073709551617 99999999999999999999999 1000000 0 -5 12x; do
  rc=0
  TMPDIR=$work/tmp timeout 20 "$repo/scripts/device-kit-run" --budget "$budget" --out "$work/out" >"$work/log" 2>&1 || rc=$?
  [[ $rc -eq 2 ]] || { cat "$work/log"; fail "--budget $budget: exit $rc, expected 2 (usage error)"; }
  grep -q -- "--budget" "$work/log" || fail "--budget $budget: the message does not name --budget: $(cat "$work/log")"
  [[ ! -e $work/out ]] || fail "--budget $budget: --out was created before the check"
done
[[ -z $(ls -A "$work/tmp") ]] || fail "a refused run left $(ls -A "$work/tmp")"
echo "ok: budgets past the bound are usage errors"
