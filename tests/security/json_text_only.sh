#!/usr/bin/env bash
# JSON text is made one way (issue 45): io::json_text / json_line (trn/io/outside_text.hpp), which
# make outside text valid UTF-8 first. nlohmann's dump() throws on invalid UTF-8 (exit 2, after the
# work); any other call of it in host/, apps/, capi/, python/ or energy/ fails this test (energy/'s
# writers, run reports, bench.json and compare's summary.json, joined in issue 46's third round).
#   json_text_only.sh SOURCE_ROOT
set -uo pipefail
cd "$1" || exit 1
pattern='\.dump *\('
grep -qE "$pattern" <<<'const std::string t = j.dump(2);' || { echo "FAILED: the pattern misses a dump() call"; exit 1; }
hits=$(grep -rnE --include=*.cpp --include=*.hpp --include=*.h "$pattern" host apps capi python energy |
       grep -v '^host/include/trn/io/outside_text.hpp:' | grep -vE '^[^:]+:[0-9]+: *//')
if [[ -n $hits ]]; then
  echo "FAILED: JSON text made without io::json_text / json_line (trn/io/outside_text.hpp):"
  echo "$hits"
  exit 1
fi
echo "JSON text is made only by trn/io/outside_text.hpp"
