#!/bin/sh
# usage: io_exports_match.sh BUILD_IO_LIB KIT_IO_LIB -- fails (listing the difference) when the two
# libraries' dynamic exports differ.
set -eu
exports() { nm -D --defined-only "$1" | awk '{print $3}' | sort; }
a=$(mktemp) b=$(mktemp)
trap 'rm -f "$a" "$b"' EXIT
exports "$1" > "$a"
exports "$2" > "$b"
if ! diff "$a" "$b"; then
  echo "io_exports_match: $1 and $2 export different symbols (< build only, > kit only)" >&2
  exit 1
fi
echo "io_exports_match: $(wc -l < "$a") exports, the same in both"
