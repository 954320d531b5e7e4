#!/usr/bin/env bash
# issue 45, class 2: scripts/results-tables rewrites a doc with the doc's own mode (it made every
# rewritten doc 0600), and refuses a doc that is a symbolic link, with a message and before any
# merge, leaving the link and its target as they are (it replaced the link by a plain file). The
# doc here holds one block of the sampling study (a merge of the repository's store: a second).
# Fails on 8fd5cd9.
# usage: results_tables_keeps_docs.sh REPO_ROOT TRNKIT WORK_DIR
set -uo pipefail
repo=$1 trnkit=$2 work=$3
fail() { echo "FAILED: $*" >&2; exit 1; }
rm -rf -- "$work" && mkdir -p -- "$work" || exit 1
block=$'# A doc\n\n<!-- results: sampling ours table_3_6 -->\nstale\n<!-- /results -->\n'
printf '%s' "$block" >"$work/doc.md"
chmod 664 "$work/doc.md"
python3 "$repo/scripts/results-tables" --trnkit "$trnkit" "$work/doc.md" >"$work/log" 2>&1 || { cat "$work/log"; fail "results-tables failed"; }
grep -q 'Table 3.6' "$work/doc.md" || fail "the block was not filled: $(cat "$work/doc.md")"
[[ $(stat -c %a "$work/doc.md") == 664 ]] || fail "the doc's mode became $(stat -c %a "$work/doc.md") (was 664)"
[[ -z $(find "$work" -name '.*.tmp') ]] || fail "temporary files left: $(find "$work" -name '.*.tmp')"

printf '%s' "$block" >"$work/target.md"
ln -s target.md "$work/link.md"
rc=0
python3 "$repo/scripts/results-tables" --trnkit "$trnkit" "$work/link.md" >"$work/link.log" 2>&1 || rc=$?
[[ -L $work/link.md ]] || fail "the linked doc was replaced by a file"
[[ $(cat "$work/target.md") == "${block%$'\n'}" ]] || fail "the link's target was rewritten"
[[ $rc -eq 2 ]] || { cat "$work/link.log"; fail "a linked doc: exit $rc, expected 2"; }
grep -q 'symbolic link' "$work/link.log" || fail "no clear message for a linked doc: $(cat "$work/link.log")"
python3 "$repo/scripts/results-tables" --check --trnkit "$trnkit" "$work/link.md" >"$work/check.log" 2>&1
[[ $? -eq 1 ]] || { cat "$work/check.log"; fail "--check through a link: expected exit 1 (the block is stale)"; }
echo "ok: a doc keeps its mode; a linked doc is refused, link and target untouched"
