#!/usr/bin/env bash
# issue 45, class 1: scripts/bench-report pastes no text from bench.json or its options into gnuplot's
# program. bench.json comes back from device machines: its context.date carries commands in every
# gnuplot quoting (backticks run even inside double quotes; a quote closes the string, system()
# runs), and --out names a folder that closes `set output '...'`. Nothing may run; the chart is
# still drawn and its title shows the text as it is. Fails on 8fd5cd9 (CANARY files appear).
# usage: bench_report_text_not_executed.sh REPO_ROOT WORK_DIR
set -uo pipefail
repo=$1 work=$2
command -v gnuplot >/dev/null || { echo "SKIPPED: gnuplot is not installed (scripts/install-deps.sh installs gnuplot-nox)"; exit 77; }
fail() { echo "FAILED: $*" >&2; exit 1; }
rm -rf -- "$work" && mkdir -p -- "$work" && cd -- "$work" || exit 1

python3 - "$repo/tests/bench/data/ncc_issue14_targets.json" in.json <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
doc["context"]["date"] = ("2026-12-05 `touch CANARY-backtick` \"; system('touch CANARY-double'); print \" "
                          "'; system('touch CANARY-single'); print ' @ARG1 $0")
doc["context"]["trn_sweep"] = "quick\"; system('touch CANARY-sweep'); print \""
json.dump(doc, open(sys.argv[2], "w"))
PY
out="out'; system('touch CANARY-out'); print '"
rc=0
"$repo/scripts/bench-report" --from-json in.json --out "$out" >log 2>&1 || rc=$?
canaries=$(find . -name 'CANARY*')
[[ -z $canaries ]] || fail "text from bench.json or --out ran as a command through gnuplot: ${canaries//$'\n'/ }"
[[ $rc -eq 0 ]] || { cat log; fail "bench-report exited $rc"; }
[[ -s "$out/chart.png" ]] || { cat log; fail "no chart drawn"; }
! grep -q CANARY "$out/chart.gp" || fail "chart.gp holds text from bench.json or --out (it must be fixed text)"
echo "ok: nothing ran; chart drawn with the payloads as its title"
