#!/usr/bin/env bash
# issue 45, class 2: scripts/bench-report writes only its own files. A report.md it did not write
# is refused (not overwritten), and a link planted at any name it writes (bench.json, report.md,
# chart.gp, chart.png, chart_sobel.tsv, chart_ncc.tsv) is refused, never written through; either
# way before anything is written. An earlier report in the folder is replaced as before, and the
# files get the usual mode (umask 022: 0644). Fails on 8fd5cd9 (it wrote through every link).
# usage: bench_report_foreign_files.sh REPO_ROOT WORK_DIR
set -uo pipefail
repo=$1 work=$2
fail() { echo "FAILED: $*" >&2; exit 1; }
rm -rf -- "$work" && mkdir -p -- "$work" && cd -- "$work" || exit 1
umask 022
json=$repo/tests/bench/data/stream_stable.json
report=$repo/scripts/bench-report

refused() {  # folder, what: bench-report must fail with a message and leave victim.txt alone
  local dir=$1 what=$2
  if "$report" --from-json "$json" --out "$dir" >"$dir.log" 2>&1; then fail "$what: accepted"; fi
  grep -q "bench-report: " "$dir.log" || fail "$what: no message: $(cat "$dir.log")"
  [[ $(cat victim.txt) == "the user's" ]] || fail "$what: written through to victim.txt"
}

echo "the user's" >victim.txt
mkdir mine && echo "my own notes" >mine/report.md
refused mine "a user's report.md"
[[ $(cat mine/report.md) == "my own notes" ]] || fail "a user's report.md was overwritten"
[[ ! -e mine/bench.json ]] || fail "files written before the refusal"

for name in bench.json report.md chart.gp chart.png chart_sobel.tsv chart_ncc.tsv; do
  dir=link-${name//./-}
  mkdir "$dir" && ln -s ../victim.txt "$dir/$name"
  refused "$dir" "a link at $name"
  [[ -L "$dir/$name" ]] || fail "the link at $name was replaced (it must be refused, left as it is)"
done

"$report" --from-json "$json" --out again >again.log 2>&1 || { cat again.log; fail "first report"; }
"$report" --from-json "$json" --out again >again.log 2>&1 || { cat again.log; fail "an earlier report was not replaced"; }
for f in again/report.md again/bench.json again/chart_sobel.tsv again/chart.gp; do
  [[ $(stat -c %a "$f") == 644 ]] || fail "$f has mode $(stat -c %a "$f"), expected 644"
done
[[ -z $(find again -name '.*.tmp') ]] || fail "temporary files left: $(find again -name '.*.tmp')"
echo "ok: a foreign report.md and planted links refused; an earlier report replaced"
