#!/usr/bin/env bash
# Every numeric parser option (OptionReader::number("KEY"...) in energy/src) has a stated range in
# energy/src/core/option_ranges.hpp (issue 45 class 6 / 46): a key without one is refused at run
# time as a defect, so this finds it first.
#   option_ranges_stated.sh SOURCE_ROOT
set -uo pipefail
cd "$1" || exit 1
table=energy/src/core/option_ranges.hpp
keys=$(grep -rhoE --include=*.cpp --include=*.hpp '\.number\("[a-z_]+"' energy/src | sed -E 's/.*\("([a-z_]+)"/\1/' | sort -u)
[[ -n $keys ]] || { echo "FAILED: no number(\"KEY\") call found: the pattern is stale"; exit 1; }
missing=""
for k in $keys; do
  grep -qE "^ *\{\"$k\"," "$table" || missing+=" $k"
done
if [[ -n $missing ]]; then
  echo "FAILED: numeric options without a stated range in $table:$missing"
  exit 1
fi
echo "every numeric option has a range: $(echo "$keys" | tr '\n' ' ')"
