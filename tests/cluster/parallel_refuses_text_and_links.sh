#!/usr/bin/env bash
# issue 45: scripts/experiment-parallel hands GNU parallel no text it would run, and appends its
# joblog through no link. Fails on 8fd5cd9.
#   trnkit-path: GNU parallel reads {=perl=} in any word of the command, the program's path too: a
#                trnkit in a folder named "bin{=qx(touch CANARY)=}" ran perl. Now refused, with a
#                message, before any job runs.
#   joblog-link: OUT/dispatch/parallel-joblog.tsv planted as a link to a file elsewhere was appended
#                to. Now refused, the link and its target left as they are.
# Each runs one --quick metrics job at most (a second or two).
#   parallel_refuses_text_and_links.sh TRNKIT SCRIPTS_DIR trnkit-path|joblog-link
set -uo pipefail
trnkit=$1 scripts=$2 what=$3
fail() { echo "FAILED: $*" >&2; exit 1; }
command -v parallel >/dev/null || { echo "SKIPPED: GNU parallel is not installed (Debian package parallel)"; exit 77; }
work=$(mktemp -d "$PWD/refuse-$what.XXXXXX") || exit 1
trap 'rm -rf -- "$work"' EXIT
cd -- "$work" || exit 1
study=(metrics --quick --no-plots --results none)
case $what in
  trnkit-path)
    dir="bin{=qx(touch CANARY)=}"
    mkdir -- "$dir"
    printf '#!/bin/sh\nexec "%s" "$@"\n' "$trnkit" >"$dir/trnkit"
    chmod +x "$dir/trnkit"
    rc=0
    "$scripts/experiment-parallel" --jobs 1 --batch 1 --trnkit "$work/$dir/trnkit" "${study[@]}" --out "$work/out" >log 2>&1 || rc=$?
    [[ ! -e CANARY && ! -e out/CANARY ]] || fail "GNU parallel ran the perl in the trnkit path"
    [[ $rc -ne 0 ]] || fail "a trnkit path GNU parallel would rewrite was accepted"
    grep -q "GNU parallel would replace" log || fail "no clear message: $(cat log)"
    ;;
  joblog-link)
    "$scripts/experiment-parallel" --jobs 1 --batch 1 --trnkit "$trnkit" "${study[@]}" --out "$work/out" >log 2>&1 ||
      { cat log; fail "a first batch into a fresh folder failed"; }
    echo "the user's" >victim.txt
    rm -f out/dispatch/parallel-joblog.tsv
    ln -s ../../victim.txt out/dispatch/parallel-joblog.tsv
    rc=0
    "$scripts/experiment-parallel" --jobs 1 --batch 1 --trnkit "$trnkit" "${study[@]}" --out "$work/out" >log 2>&1 || rc=$?
    [[ $(cat victim.txt) == "the user's" ]] || fail "the joblog was appended through a planted link"
    [[ -L out/dispatch/parallel-joblog.tsv ]] || fail "the planted link was replaced"
    [[ $rc -ne 0 ]] || fail "a joblog planted as a link was accepted"
    grep -q "symbolic link" log || fail "no clear message: $(cat log)"
    ;;
  *) fail "unknown case $what" ;;
esac
echo "ok: $what refused"
