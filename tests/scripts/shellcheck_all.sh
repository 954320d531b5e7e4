#!/usr/bin/env bash
# issue 45: shellcheck over every shell script of the project, found by looking, not by a list: every
# file in scripts/ and scripts/lib/ (a "#!...sh" or "#!...bash" line, a .sh name or a "# shellcheck
# shell=" directive) and every tests/**/*.sh. The Python scripts there must at least parse. A file
# in scripts/ that is neither fails the test, so a new kind of script is not skipped unseen.
# usage: shellcheck_all.sh REPO_ROOT
set -uo pipefail
repo=$1
command -v shellcheck >/dev/null || { echo "SKIPPED: shellcheck is not installed (scripts/install-deps.sh installs it)"; exit 77; }
cd -- "$repo" || exit 1
shell=() python=() other=()
for f in scripts/* scripts/lib/*; do
  [[ -f $f ]] || continue
  first=$(head -n 1 -- "$f")
  if [[ $f == *.sh || $first =~ ^#!.*[/\ ](ba)?sh([[:space:]]|$) ]] || grep -q '^# shellcheck shell=' -- "$f"; then
    shell+=("$f")
  elif [[ $f == *.py || $first =~ ^#!.*python3? ]]; then
    python+=("$f")
  else
    other+=("$f")
  fi
done
while IFS= read -r -d '' f; do shell+=("$f"); done < <(find tests -name '*.sh' -print0 | sort -z)
fail=0
if [[ ${#other[@]} -gt 0 ]]; then
  echo "FAILED: neither a shell nor a Python script (check it here): ${other[*]}"; fail=1
fi
[[ ${#shell[@]} -ge 10 ]] || { echo "FAILED: only ${#shell[@]} shell scripts found"; fail=1; }
shellcheck -x -- "${shell[@]}" || fail=1
for f in "${python[@]}"; do
  python3 -c 'import ast, sys; ast.parse(open(sys.argv[1]).read(), sys.argv[1])' "$f" || { echo "FAILED: $f does not parse"; fail=1; }
done
[[ $fail -eq 0 ]] && echo "ok: shellcheck clean: ${#shell[@]} shell scripts; ${#python[@]} Python scripts parse"
exit $fail
