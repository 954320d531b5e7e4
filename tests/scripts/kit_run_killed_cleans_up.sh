#!/usr/bin/env bash
# issue 45, class 9: a KIT/run that is killed (TERM) while a step runs stops that step and removes
# its work folder (TMPDIR/trnkit-device-kit.*), promptly. The kit here is KIT/run beside a bin/trnkit
# that only sleeps, so step 2 (`trnkit devices`) is running when the signal comes. Fails on 8fd5cd9
# (the work folder stayed, the step ran on). Takes about two seconds.
# usage: kit_run_killed_cleans_up.sh REPO_ROOT WORK_DIR
set -uo pipefail
repo=$1 work=$2
fail() { echo "FAILED: $*" >&2; exit 1; }
rm -rf -- "$work" && mkdir -p -- "$work/kit/bin" "$work/tmp" || exit 1
run_pid="" sleeper=""
finish() {  # whatever happened, nothing of this test keeps running
  [[ -n $run_pid ]] && kill -KILL "$run_pid" 2>/dev/null
  sleeper=$(cat "$work/sleeper.pid" 2>/dev/null)
  [[ -n $sleeper ]] && kill -KILL "$sleeper" 2>/dev/null
  return 0
}
trap finish EXIT
cp "$repo/scripts/device-kit-run" "$work/kit/run"
printf '#!/bin/sh\necho $$ > "%s"\nexec sleep 60\n' "$work/sleeper.pid" >"$work/kit/bin/trnkit"
chmod +x "$work/kit/bin/trnkit"
TMPDIR=$work/tmp "$work/kit/run" --budget 600 --out "$work/out" >"$work/run.log" 2>&1 </dev/null &
run_pid=$!
for _ in $(seq 100); do [[ -s $work/sleeper.pid ]] && break; sleep 0.1; done
[[ -s $work/sleeper.pid ]] || { cat "$work/run.log"; fail "step 2 (the sleeping trnkit) never started"; }
[[ -n $(ls -A "$work/tmp") ]] || fail "no work folder while a step runs (TMPDIR not used?)"
kill -TERM "$run_pid"
for _ in $(seq 50); do kill -0 "$run_pid" 2>/dev/null || break; sleep 0.1; done
! kill -0 "$run_pid" 2>/dev/null || fail "KIT/run still runs 5 s after TERM"
wait "$run_pid" 2>/dev/null
run_pid=""
left=$(ls -A "$work/tmp")
[[ -z $left ]] || fail "the killed run left its work folder: $work/tmp/$left"
sleep 0.2
! kill -0 "$(cat "$work/sleeper.pid")" 2>/dev/null || fail "the step's process runs on after the kit was killed"
echo "ok: killed, the run stopped its step and removed its work folder"
