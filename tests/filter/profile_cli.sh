#!/usr/bin/env bash
# --profile and --lock-monitor through real trnkit processes (issue 27): a bad name is refused in one
# line naming the option; options the profile does not take are refused; demo and localize record
# the profile and run with its values (500 particles, no maximum but the safety cap, the text's
# 300 m, no lock monitor); --lock-monitor switches the monitor in both profiles.
#   profile_cli.sh TRNKIT
set -uo pipefail
T=$1
fail() { echo "FAILED: $*" >&2; exit 1; }
work=$(mktemp -d "$PWD/profile.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
cd "$work" || exit 1

refused() {  # refused OPTION ARGS...: non-zero exit, one line, naming OPTION
  local opt=$1 out rc
  shift
  out=$("$T" "$@" 2>&1)
  rc=$?
  [[ $rc -ne 0 ]] || fail "exit 0 for $*"
  [[ $(printf '%s\n' "$out" | wc -l) -eq 1 ]] || fail "not one line for $*: $out"
  grep -q -- "$opt" <<<"$out" || fail "$opt not named for $*: $out"
}
refused --profile demo --profile literal
refused --profile localize --dataset nowhere --profile Dissertation
refused --profile experiment sampling --quick --profile nope
refused --lock-monitor demo --lock-monitor maybe
refused --lock-monitor experiment sampling --quick --lock-monitor 1
refused --motion-along-heading demo --profile dissertation --motion-along-heading --backend cpu --distance-km 0.1 --no-plots --out a
refused --lock-monitor demo --no-lock-monitor --lock-monitor on --backend cpu --distance-km 0.1 --no-plots --out b
refused --lock-monitor experiment metrics --quick --lock-monitor off --out c

states() { cut -d, -f26 "$1/localization.csv" | tail -n +2 | sort -u | tr '\n' ' '; }
run_demo() { "$T" demo --backend cpu --distance-km 0.2 --no-plots "$@" >/dev/null 2>&1 || fail "demo $* failed"; }
run_demo --profile dissertation --out d
grep -q '"profile": "dissertation"' d/summary.json || fail "demo: profile not recorded"
grep -q '"max_particles": 100000' d/summary.json || fail "demo: the dissertation's particle cap not applied"
[[ $(states d) == "none " ]] || fail "demo --profile dissertation: the lock monitor ran ($(states d))"
run_demo --profile dissertation --lock-monitor on --out e
[[ $(states e) != "none " ]] || fail "demo --profile dissertation --lock-monitor on: no lock monitor"
run_demo --lock-monitor off --out f
[[ $(states f) == "none " ]] || fail "demo --lock-monitor off: the lock monitor ran"
grep -q '"profile": "ours"' f/summary.json || fail "demo: profile ours not recorded"

"$T" simulate --scenario FR-200 --frames 150 --size-m 800 --map-year 2010 --out flt >/dev/null 2>&1 || fail "simulate failed"
"$T" localize --dataset flt --backend cpu --profile dissertation --no-plots --out l1 >/dev/null 2>&1 || fail "localize --profile dissertation failed"
for kv in '"profile": "dissertation"' '"particles": 500' '"max_particles": 100000' '"init_radius_m": 300' '"min_particles": 100'; do
  grep -q "$kv" l1/summary.json || fail "localize --profile dissertation: no $kv in summary.json"
done
"$T" localize --dataset flt --backend cpu --profile dissertation --init-radius-m 50 --max-particles 3000 --no-plots --out l2 >/dev/null 2>&1 ||
  fail "localize with options over the profile failed"
{ grep -q '"init_radius_m": 50' l2/summary.json && grep -q '"max_particles": 3000' l2/summary.json; } || fail "localize: given options do not replace the profile's"
"$T" localize --dataset flt --backend cpu --no-plots --out l3 >/dev/null 2>&1 || fail "localize failed"
{ grep -q '"init_radius_m": 50' l3/summary.json && grep -q '"max_particles": 2000' l3/summary.json; } || fail "localize: ours' defaults changed"
echo "profile options: refused with their names; demo and localize run and record both profiles"
