#!/usr/bin/env bash
# ctest devicekit.bare_root: builds the device kit from this build and runs KIT/run in a bare Debian
# root of the release it was built on (tests/devicekit/bare_root.sh; debootstrap minbase: none of
# trnkit's packages, no compiler, no OpenCV, no ICDs), as a GPU machine without our packages would.
# Checks: the kit is at most 48 MiB and its libraries are its own; run starts, passes cpu-ref and cpu
# conformance, names OpenCL and Vulkan "not available" with the reason, writes at most 8 files, and
# finishes inside its budget.
# Exit 77 (ctest: skipped, with the reason) when the bare root cannot be made here.
#
# Exit 77 too for a build without the benchmarks (BENCH_BUILT 0: TRN_BUILD_BENCH=OFF, as the
# asan-ubsan preset has it), which the kit packs.
#
# ARCH (a Debian architecture; default this machine's): a kit of another one (arm64, from the cross
# build) runs in a bare root of that architecture under qemu-user (scripts/platform-check arm64-kit).
#
# usage: kit_in_bare_root.sh REPO BUILD_DIR CACHE_DIR BUDGET_S [BENCH_BUILT [ARCH]]
set -uo pipefail
repo=$1 build=$2 cache=$3 budget=$4 bench_built=${5:-1} arch=${6:-}
fail() { echo "FAILED: $*"; exit 1; }
if [[ "$bench_built" == 0 ]]; then
  echo "SKIPPED: this build has no benchmarks (TRN_BUILD_BENCH=OFF, e.g. the asan-ubsan preset); the device kit packs trn_bench"
  exit 77
fi

kit="$build/device-kit"
"$repo/scripts/device-kit" ${arch:+--arch "$arch"} --build "$build" --out "$kit" --no-build || fail "scripts/device-kit did not make the kit"
bytes=$(du -sb "$kit" | cut -f1)
echo "kit: $kit, $bytes bytes ($((bytes >> 20)) MiB)"
(( bytes <= 48 << 20 )) || fail "the kit is $((bytes >> 20)) MiB, over 48 MiB"
grep -q "libopencv_imgcodecs\|libgdal" "$kit/MANIFEST.txt" && fail "the kit carries imgcodecs or GDAL (MANIFEST.txt)"

root=$("$repo/tests/devicekit/bare_root.sh" "$cache" ${arch:+"$arch"})
rc=$?
if (( rc == 77 )); then echo "SKIPPED: no bare Debian root here (reason above)"; exit 77; fi
(( rc == 0 )) || fail "bare_root.sh failed ($rc)"
# The root must really be bare: none of what the kit brings is installed there.
for so in 'libopencv_core.so.4*' libOpenCL.so.1 libvulkan.so.1 libstdc++.so.6; do
  [[ -z "$(find "$root/usr/lib" "$root/lib" -name "$so" 2>/dev/null | head -1)" ]] || {
    [[ "$so" == libstdc++.so.6 ]] || fail "the bare root has $so: not bare"; }
done

inside="/trnkit-kit-$$"
rm -rf "$root$inside" "$root/trnkit-out-$$"
cp -a "$kit" "$root$inside" || fail "cannot copy the kit into $root"
trap 'rm -rf "$root$inside" "$root/trnkit-out-$$"' EXIT
t0=$SECONDS
chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root TMPDIR=/tmp \
  "$inside/run" --budget "$budget" --out "/trnkit-out-$$"
run_rc=$?
elapsed=$(( SECONDS - t0 ))
out="$root/trnkit-out-$$"
echo "== run exited $run_rc after $elapsed s (budget $budget s); files:"
ls -la "$out"
echo "== summary.md"
cat "$out/summary.md" 2>/dev/null || fail "no summary.md"

(( run_rc == 0 )) || fail "KIT/run exited $run_rc (a step failed: see the table above)"
(( elapsed <= budget + 15 )) || fail "KIT/run took $elapsed s, over its $budget s budget"
n=$(find "$out" -type f | wc -l)
(( n <= 8 )) || fail "KIT/run wrote $n files, more than 8"
s="$out/summary.md"
grep -qE '^\| conformance cpu-ref .*\| passed \|' "$s" || fail "cpu-ref conformance did not pass"
grep -qE '^\| conformance cpu \| passed \|' "$s" || fail "cpu conformance did not pass"
grep -qE 'CONFORMANCE cpu: [1-9][0-9]* passed, 0 failed' "$s" || fail "cpu conformance ran no case"
for family in opencl vulkan; do
  grep -qE "^\| conformance $family \(every device\) \| not available: NOT AVAILABLE \(no ICD: .+\)" "$s" ||
    fail "$family is not reported 'not available' with its reason"
done
# cuda: "built without CUDA (...)" from a build without nvcc, else the driver library's absence.
grep -qE "^\| conformance cuda \(every device\) \| not available: NOT AVAILABLE \((built without CUDA|the CUDA driver library libcuda.so.1 could not be loaded).+\)" "$s" ||
  fail "cuda is not reported 'not available' with its reason"
grep -qE '^- CUDA: libcuda.so.1 not in ldconfig' "$s" || fail "the CUDA driver search is not reported"
grep -qE '^- OpenCL: no NVIDIA ICD' "$s" || fail "the OpenCL ICD search is not reported"
grep -qE '^- Vulkan: no ICD' "$s" || fail "the Vulkan ICD search is not reported"
[[ -s "$out/bench.json" ]] || fail "no bench.json"
grep -q '"name": "sobel/1920x1080/hot/dev:cpu' "$out/bench.json" || fail "bench.json has no Sobel 1080p row for cpu"
echo "PASSED: kit $((bytes >> 20)) MiB ($(grep -o 'architecture: .*' "$kit/MANIFEST.txt")); run in a bare Debian root" \
     "($(chroot "$root" /usr/bin/uname -m)): $elapsed s of $budget s, $n files"
