#!/usr/bin/env bash
# Every file the C++ code opens goes through its one home (issue 45): a C++ source outside the
# allow-list (io_home_allowed.txt) that opens a file another way fails this test, and so does an
# allow-list entry that no longer opens anything (the list stays the truth).
#   io_home.sh SOURCE_ROOT ALLOW_LIST
set -uo pipefail
root=$1 allow=$2
cd "$root" || exit 1
# The ways C++ opens a file: streams, C stdio, POSIX open/openat/creat, OpenCV and GDAL by path.
pattern='std::(i|o)?fstream|\b(i|o)fstream\b|\bf(re)?open *\(|(^|::|[^._a-zA-Z0-9])open(at)?\([^)]|\bcreat *\(|cv::(imread|imwrite|VideoCapture|FileStorage)\b|\bGDALOpen(Ex)? *\('
# The pattern itself must catch each way (a grep that matches nothing would pass for ever).
for sample in 'std::ifstream in(p);' 'std::ofstream o(p);' 'FILE* f = fopen(p, "r");' 'int fd = ::open(p, O_RDONLY);' \
              'int fd = open(p, O_RDONLY);' 'openat(d, n, 0);' 'cv::imread(p)' 'GDALOpenEx(p, 0, 0, 0, 0)' 'std::fstream f;'; do
  grep -qE "$pattern" <<<"$sample" || { echo "FAILED: the pattern misses: $sample"; exit 1; }
done
for sample in 'dataset.open_folder(x)' 'reopen_later()' 'is_open()'; do
  ! grep -qE "$pattern" <<<"$sample" || { echo "FAILED: the pattern takes for an open: $sample"; exit 1; }
done
mapfile -t allowed < <(grep -v '^#' "$allow" | sed 's/ #.*//' | grep .)
status=0
# Comment lines are not code.
hits=$(grep -rnE --include=*.c --include=*.cpp --include=*.h --include=*.hpp "$pattern" backends host energy apps capi python 2>/dev/null |
       grep -vE '^[^:]+:[0-9]+: *//')
while IFS= read -r hit; do
  [[ -z $hit ]] && continue
  file=${hit%%:*}
  ok=0
  for a in "${allowed[@]}"; do [[ $file == "$a" ]] && ok=1; done
  if [[ $ok -eq 0 ]]; then
    echo "FAILED: opens a file outside the I/O home (use trn/io/input_file.hpp or atomic_file.hpp): $hit"
    status=1
  fi
done <<<"$hits"
for a in "${allowed[@]}"; do
  [[ -f $a ]] || { echo "FAILED: allow-list entry $a does not exist"; status=1; continue; }
  grep -qF "$a:" <<<"$hits" || { echo "FAILED: allow-list entry $a opens no file any more; remove it"; status=1; }
done
[[ $status -eq 0 ]] && echo "every C++ file open is in the ${#allowed[@]} allowed files"
exit $status
