#!/usr/bin/env bash
# scripts/bench-report on fixed bench.json files (tests/bench/data): a STREAM limit whose passes
# never agreed, or whose repetitions disagree, is marked unreliable (table and "of STREAM"); one
# whose passes and repetitions agree is not. Also: a STREAM-only run makes a report and exits 0.
# usage: report_marks_unreliable.sh REPO_ROOT WORK_DIR
set -uo pipefail
repo=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
fail=0
check() {  # fixture, expect ("unreliable" or "reliable")
  local fixture=$1 expect=$2 out="$work/${1%.json}"
  if ! "$repo/scripts/bench-report" --from-json "$repo/tests/bench/data/$fixture" --out "$out" > "$out.log" 2>&1; then
    echo "FAIL $fixture: bench-report exited non-zero:"; cat "$out.log"; fail=1; return
  fi
  local row; row=$(grep '^| copy/cold |' "$out/report.md")
  if [[ -z "$row" ]]; then echo "FAIL $fixture: no copy/cold row in report.md"; fail=1; return; fi
  if [[ $expect == unreliable ]]; then
    [[ "$row" == *"**unreliable**"* ]] || { echo "FAIL $fixture: copy/cold not marked unreliable: $row"; fail=1; }
  else
    [[ "$row" == *"| reliable |"* && "$row" != *unreliable* ]] || { echo "FAIL $fixture: copy/cold not reliable: $row"; fail=1; }
  fi
  echo "ok   $fixture: $row"
}
check stream_unstable.json unreliable
check stream_repetitions_vary.json unreliable
check stream_stable.json reliable
exit $fail
