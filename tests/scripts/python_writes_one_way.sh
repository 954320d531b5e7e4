#!/usr/bin/env bash
# issue 45: the scripts' Python (scripts/*, scripts/lib/*, the Python inside bench-report) writes files
# one way only, scripts/lib/trn_files.py (a fresh file renamed into place, never through a link,
# the replaced file's mode kept). Any other way to write a file there fails this test: open() with
# a write mode, os.open with O_WRONLY/O_RDWR/O_CREAT, Path.write_text/write_bytes, tempfile's
# NamedTemporaryFile/mkstemp, shutil's copies and moves, os.replace/rename/link/symlink. Reading is
# not restricted; a folder from tempfile.TemporaryDirectory is the script's own.
# usage: python_writes_one_way.sh REPO_ROOT
set -uo pipefail
cd -- "$1" || exit 1
pattern="open\(.*['\"][rtb]*[wax+][rwxabt+]*['\"]|O_(WRONLY|RDWR|CREAT|APPEND|TRUNC)|\.write_(text|bytes)\(|NamedTemporaryFile|mkstemp|shutil\.(copy|copyfile|copy2|copytree|move)\(|os\.(replace|rename|renames|link|symlink)\("
files=()
for f in scripts/* scripts/lib/*; do
  [[ -f $f && $f != scripts/lib/trn_files.py ]] && files+=("$f")
done
if hits=$(grep -nE -- "$pattern" "${files[@]}"); then
  echo "FAILED: files written another way than scripts/lib/trn_files.py (replace_file, fresh_name_beside + rename_over):"
  echo "$hits"
  exit 1
fi
grep -q 'def replace_file' scripts/lib/trn_files.py || { echo "FAILED: scripts/lib/trn_files.py has no replace_file"; exit 1; }
echo "ok: ${#files[@]} scripts write files only through scripts/lib/trn_files.py"
