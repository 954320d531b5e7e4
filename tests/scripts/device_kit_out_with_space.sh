#!/usr/bin/env bash
# issue 45, class 9: scripts/device-kit with --out and --build in folders whose names hold spaces.
# ldd's lines were split on blanks, so a library inside "kit dir/" was taken for "/.../kit" (cp of a
# folder: the build failed). The build folder here is a stand-in made in a second: the three
# binaries and libtrnkit_io of a real build, as tiny C programs (so nothing of trnkit is built).
# Checks that the kit is made, its binaries run from inside it, and no RUNPATH leaves it.
# Fails on 8fd5cd9.
# usage: device_kit_out_with_space.sh REPO_ROOT WORK_DIR
set -uo pipefail
repo=$1 work=$2
fail() { echo "FAILED: $*" >&2; exit 1; }
for tool in cc ldd patchelf strip nm; do
  command -v "$tool" >/dev/null || { echo "SKIPPED: $tool not found (scripts/install-deps.sh installs it)"; exit 77; }
done
ldconfig -p 2>/dev/null | grep 'libvulkan.so.1 ' >/dev/null || { echo "SKIPPED: libvulkan.so.1 not installed (the kit carries it)"; exit 77; }
rm -rf -- "$work" && mkdir -p -- "$work" || exit 1
build="$work/fake build"
mkdir -p "$build/apps/trnkit" "$build/tests/conformance" "$build/bench" "$build/device-kit-lib" "$build/host" || exit 1
echo 'int trn_io_version(void) { return 1; }' >"$work/io.c"
printf '%s\n' 'int trn_io_version(void);' 'int main(void) { return trn_io_version() == 1 ? 0 : 1; }' >"$work/main.c"
cc -shared -fPIC -Wl,-soname,libtrnkit_io.so.0 -o "$build/host/libtrnkit_io.so.0" "$work/io.c" || fail "cc (library)"
cp "$build/host/libtrnkit_io.so.0" "$build/device-kit-lib/libtrnkit_io.so.0"
for bin in apps/trnkit/trnkit tests/conformance/trn_conformance bench/trn_bench; do
  cc -o "$build/$bin" "$work/main.c" "$build/host/libtrnkit_io.so.0" -Wl,-rpath,"$build/host" || fail "cc ($bin)"
done
kit="$work/kit dir/the kit"
mkdir -p "$work/kit dir"
"$repo/scripts/device-kit" --no-build --build "$build" --out "$kit" >"$work/log" 2>&1 || { cat "$work/log"; fail "device-kit failed with spaces in --out and --build"; }
for bin in trnkit trn_conformance trn_bench; do
  env -u LD_LIBRARY_PATH "$kit/bin/$bin" || fail "$kit/bin/$bin does not run from the kit"
done
[[ -f "$kit/lib/libtrnkit_io.so.0" && -f "$kit/tools/lib/trn_files.py" ]] || fail "the kit lacks lib/libtrnkit_io.so.0 or tools/lib/trn_files.py"
for f in "$kit"/bin/*; do
  # shellcheck disable=SC2016  # the loader's $ORIGIN, literally
  [[ $(patchelf --print-rpath "$f") == '$ORIGIN/../lib' ]] || fail "$f: RUNPATH $(patchelf --print-rpath "$f")"
done
[[ -z $(find "$work/kit dir" -maxdepth 1 -name '.device-kit-stage.*') ]] || fail "a stage folder was left"
echo "ok: a kit made and run from folders with spaces in their names"
