# shellcheck shell=bash disable=SC2154  # repo, cache, build, jobs, cmake_exe ... come from scripts/platform-check
# shellcheck source=scripts/lib/chroot-mounts.sh
source "$repo/scripts/lib/chroot-mounts.sh"
# Sourced by scripts/platform-check (which sets repo, cache, build, jobs, cmake_exe, ctest_exe, start,
# cold and the helpers): the arm64 cross build, its tests under qemu-user, and the byte-for-byte
# comparison of its scores and per-step estimates with the x86-64 build's.

# What the conformance, unit and filter tests run (the rest of the build is not needed for them).
# (trn_fuzz_replay_pose_csv: a fuzz replay labelled unit.) Then the real-flight localization test
# (trn_realflight_localize_tests) on the cpu backend.
arm64_targets=(trnkit_cli trn_conformance trn_unit_tests trn_filter_tests trn_demo_start_cli_tests
               trn_localize_start_cli_tests trn_identical_flights_tests trn_odometry_option_cli_tests
               trn_fuzz_replay_pose_csv trn_realflight_localize_tests)

# qemu-user runs aarch64 programs started by name (tests start trnkit from sh) once binfmt_misc
# knows them: registered from Debian's qemu-user-static entry when missing.
arm64_binfmt() {
  local dir=/proc/sys/fs/binfmt_misc
  [[ -e $dir/qemu-aarch64 ]] && return 0
  [[ -e $dir/register ]] || mount -t binfmt_misc binfmt_misc "$dir" || {
    echo "platform-check: cannot mount binfmt_misc: aarch64 programs run only through the tests' emulator line" >&2
    return 0
  }
  [[ -e $dir/qemu-aarch64 ]] || grep -v '^#' /usr/lib/binfmt.d/qemu-aarch64.conf > "$dir/register"
}

# The cases both architectures score and localize, into DIR, with trnkit TRNKIT. FLIGHT is the
# simulated flight (simulated once, on x86-64, so both read the same frames); REAL the real flight's
# AIR folder (realflight's 16 frames with their committed poses, made once, on x86-64).
compare_cases() {
  local trnkit=$1 dir=$2 flight=$3 real=$4 data=$repo/../shared/data b
  mkdir -p "$dir"
  # 120 poses over the whole map, some over its edges; yaw in whole degrees, scales 0.9 .. 1.1.
  awk 'BEGIN { for (i = 0; i < 120; ++i) printf "%d,%d,%.6f,%.2f\n", (i * 137) % 1800 - 20, (i * 211) % 1560 - 20, ((i * 29) % 360) * 3.14159265 / 180, 0.9 + (i % 5) * 0.05 }' > "$dir/poses.csv"
  awk 'BEGIN { for (i = 0; i < 120; ++i) printf "%d,%d,%.6f,%.2f\n", (i * 97) % 1000 - 10, (i * 61) % 880 - 10, ((i * 31) % 360) * 3.14159265 / 180, 0.9 + (i % 5) * 0.05 }' > "$dir/poses2.csv"
  for b in cpu-ref cpu cpu-portable opencl vulkan; do
    local backend=$b env=()
    [[ $b == cpu-portable ]] && backend=cpu env=(TRN_CPU_SIMD=off)
    env "${env[@]}" "$trnkit" score --backend "$backend" --map "$data/orthophoto.png" --template "$data/realflight/frame_00000.png" \
      --min-valid 0 --poses "$dir/poses.csv" -o "$dir/score-dense-$b.csv" 2>/dev/null || echo "FAILED" > "$dir/score-dense-$b.csv"
    env "${env[@]}" "$trnkit" score --backend "$backend" --map "$data/orthophoto.png" --template "$data/realflight/frame_00003.png" \
      --sampling random:0.25:7 --min-valid 0 --poses "$dir/poses.csv" -o "$dir/score-sparse-$b.csv" 2>/dev/null || echo "FAILED" > "$dir/score-sparse-$b.csv"
    # A map with no-data (transparent): the masked samplers.
    env "${env[@]}" "$trnkit" score --backend "$backend" --map "$data/realflight2/orthomosaic.png" \
      --template "$data/realflight2/frames/frame_00000.png" --min-valid 0 --poses "$dir/poses2.csv" -o "$dir/score-nodata-$b.csv" 2>/dev/null ||
      echo "FAILED" > "$dir/score-nodata-$b.csv"
  done
  local name
  for b in cpu-ref cpu; do
    for name in localize real-localize; do
      rm -rf "${dir:?}/$name-$b"
      if [[ $name == localize ]]; then
        "$trnkit" localize --dataset "$flight" --backend "$b" --seed 3 --max-particles 400 --out "$dir/$name-$b" >/dev/null 2>&1 || true
      else  # the real-flight test's run (seed 1): a 50 m start prior, frames at 0.5 Hz
        "$trnkit" localize --dataset "$real" --map "$data/orthophoto.png" --rate 0.5 --no-plots --init-radius-m 50 --seed 1 \
          --backend "$b" --out "$dir/$name-$b" >/dev/null 2>&1 || true
      fi
      # Every column but the step's times (score_ms, step_ms: wall clock).
      awk -F, -v OFS=, 'NR == 1 { for (i = 1; i <= NF; ++i) keep[i] = $i != "score_ms" && $i != "step_ms" }
                        { line = ""; for (i = 1; i <= NF; ++i) if (keep[i]) line = line (line == "" ? "" : OFS) $i; print line }' \
        "$dir/$name-$b/localization.csv" > "$dir/$name-$b.csv" 2>/dev/null || echo "FAILED" > "$dir/$name-$b.csv"
    done
  done
}

# What both arm64 checks need first: the cross tools and qemu (and the packages named), dpkg's arm64 lists,
# binfmt_misc, the arm64 root, and the cross build configured in $build.
arm64_prepare() {
  apt_install_checked ninja-build crossbuild-essential-arm64 qemu-user-static "$@"
  if ! dpkg --print-foreign-architectures | grep -qx arm64; then
    apt_wait_lock
    echo "platform-check: adding the arm64 architecture to dpkg (package lists only; nothing arm64 is installed)"
    dpkg --add-architecture arm64
    apt-get update -qq
  fi
  arm64_binfmt
  arm64_sysroot "$cache/arm64"
  arm64_configure "$repo" "$build" "$cache/arm64/root" "$cmake_exe" || { cat "$build/platform-check-configure.log" >&2; exit 1; }
}

arm64_check() {
  arm64_prepare
  local root=$cache/arm64/root
  export QEMU_LD_PREFIX=$root
  # Under qemu-user the Vulkan loader's own search finds no ICD: lavapipe named (a path in the root).
  export VK_DRIVER_FILES=/usr/share/vulkan/icd.d/lvp_icd.aarch64.json
  build_checked --target "${arm64_targets[@]}"
  # PoCL under qemu-user with -L (QEMU_LD_PREFIX) aborts before its first kernel: it looks for its
  # kernel library with access(), which qemu-user 7.2 does not redirect into the root (open and stat
  # it does). Inside the root with chroot (binfmt_misc's F flag keeps the emulator) every path is the
  # root's own, and PoCL runs: its tests run there, the repository and ../shared bound at their paths.
  local pocl_tests='^(conformance[.]opencl|LimitFiles[.]MemoryEstimatesAreRightWithin25Percent|FastestBackend[.].*|EveryBackend/IdenticalFlights[.].*/opencl.*)$'
  # Left out under emulation (named in the summary): LimitFiles.MemoryEstimatesAreRightWithin25Percent
  # measures peak RSS after malloc_trim, but qemu-user does not always pass madvise(MADV_DONTNEED)
  # through ("a hint, so ignoring and returning success is ok"), so freed heap pages stay resident
  # and are reused unseen: PoCL's 8 MiB map measured 0.06-0.26 B/px of its 1.
  local not_emulated='LimitFiles.MemoryEstimatesAreRightWithin25Percent (qemu-user keeps freed pages resident)'
  # The chroot runs get the shared data as ctest's runs do.
  export TRN_SHARED_DATA
  TRN_SHARED_DATA=$(realpath "$repo/../shared/data" 2>/dev/null || echo "")
  # Under emulation programs run ~10-30x slower: a test's own timeout (filter.cli_profile's 300 s,
  # sized for native runs) is multiplied by 10 in the generated test files (CMake 3.22 has no
  # multiplier; CMake regenerates them at the next configure), and tests without one get 5400 s.
  find "$build" -name CTestTestfile.cmake -exec perl -pi -e 's/ TIMEOUT "(\d+)"/" TIMEOUT \"" . ($1 * 10) . "\""/ge' {} +
  run_tests -E "$pocl_tests" --timeout 5400
  trap chroot_unmount EXIT
  chroot_mount "$root" "rw:$repo" "ro:$repo/../shared"
  local pocl=passed
  chroot "$root" "$build/tests/conformance/trn_conformance" --backend opencl --require > "$build/platform-check-pocl.log" 2>&1 ||
    pocl="FAILED (exit $?; $build/platform-check-pocl.log)"
  chroot "$root" "$build/tests/unit/trn_unit_tests" --gtest_filter='FastestBackend.*' \
    >> "$build/platform-check-pocl.log" 2>&1 || pocl="FAILED (exit $?; $build/platform-check-pocl.log)"
  chroot "$root" "$build/tests/filter/trn_identical_flights_tests" --gtest_filter='*/opencl' \
    >> "$build/platform-check-pocl.log" 2>&1 || pocl="FAILED (exit $?; $build/platform-check-pocl.log)"
  # The real-flight localization test (issue 12's acceptance: 5 seeds from a 50 m prior) with the
  # NEON loop (its PoCL and lavapipe variants, 10 more emulated localizations, are not run: every
  # backend's scores are compared byte for byte below).
  local realflight=passed
  "$build/tests/realflight/trn_realflight_localize_tests" --gtest_filter='*/cpu' \
    > "$build/platform-check-realflight.log" 2>&1 || realflight="FAILED (exit $?; $build/platform-check-realflight.log)"
  grep -q 'SKIPPED' "$build/platform-check-realflight.log" && realflight="SKIPPED ($(grep -m1 -o 'TRN_SHARED_DATA.*' "$build/platform-check-realflight.log"))"

  # The same cases on x86-64 (build/) and on arm64, compared byte for byte.
  local x86=$repo/build/apps/trnkit/trnkit arm=$build/apps/trnkit/trnkit out=$build/platform-compare arm_in_root=$build/trnkit-in-root
  # trnkit on arm64 started inside the root (PoCL, above); the environment (TRN_CPU_SIMD) goes through.
  printf '#!/bin/sh\nexec chroot %q %q "$@"\n' "$root" "$arm" > "$arm_in_root"
  chmod 755 "$arm_in_root"
  if [[ ! -x $x86 ]]; then
    echo "platform-check: building the x86-64 reference (build/)"
    "$cmake_exe" -S "$repo" -B "$repo/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
    "$cmake_exe" --build "$repo/build" -j "$jobs" --target trnkit_cli >/dev/null
  fi
  # The x86-64 trnkit without the emulation's variables (VK_DRIVER_FILES names the root's lavapipe).
  local x86_plain=$build/trnkit-x86-64
  printf '#!/bin/sh\nexec env -u VK_DRIVER_FILES -u QEMU_LD_PREFIX %q "$@"\n' "$x86" > "$x86_plain"
  chmod 755 "$x86_plain"
  x86=$x86_plain
  rm -rf "$out"
  mkdir -p "$out"
  "$x86" simulate --scenario FR-200 --frames 40 --size-m 800 --map-year 2010 --out "$out/flight" >/dev/null 2>&1
  local data=$repo/../shared/data
  "$x86" register --map "$data/orthophoto.png" --verify "$repo/tests/data/realflight_poses.csv" --air-out "$out/realflight" \
    "$data"/realflight/frame_000*.png >/dev/null 2>&1 || echo "platform-check: the real flight's AIR folder could not be made (../shared/data?)"
  compare_cases "$x86" "$out/x86_64" "$out/flight" "$out/realflight"
  compare_cases "$arm_in_root" "$out/aarch64" "$out/flight" "$out/realflight"
  local f same=0 differ=0 failed=0 not_run=() identical=yes
  for f in "$out"/x86_64/*.csv; do
    f=$(basename "$f")
    if [[ $f == *-opencl.csv && $pocl != passed ]]; then
      not_run+=("$f")  # PoCL does not run under qemu-user (above)
    elif grep -qx FAILED "$out/x86_64/$f" "$out/aarch64/$f"; then
      echo "platform-check: $f: the run FAILED on $(grep -lx FAILED "$out/x86_64/$f" "$out/aarch64/$f" | xargs -n1 dirname | xargs -n1 basename | tr '\n' ' ')"
      failed=$((failed + 1)) identical=no
    elif cmp -s "$out/x86_64/$f" "$out/aarch64/$f"; then
      same=$((same + 1))
    else
      echo "platform-check: $f differs: $(cmp "$out/x86_64/$f" "$out/aarch64/$f" | head -1)"
      differ=$((differ + 1)) identical=no
    fi
  done
  # On arm64 itself: NEON and the portable loop score as cpu-ref does (columns ncc, cc, ssd, valid_samples, flags).
  local kind neon_ref=yes
  for kind in dense sparse nodata; do
    for f in cpu cpu-portable; do
      cmp -s "$out/aarch64/score-$kind-cpu-ref.csv" "$out/aarch64/score-$kind-$f.csv" || neon_ref=no
    done
  done
  local inner
  inner=$("$arm" devices -v 2>/dev/null | grep -o 'inner loop [A-Za-z0-9]*' | head -1 || true)
  echo "arm64: aarch64-linux-gnu-g++ $(aarch64-linux-gnu-g++ -dumpfullversion), CMake $cmake_version, $cold build" \
       "($compiled files compiled, $warnings warnings), under $(qemu-aarch64-static --version | head -1 | awk '{print $1, $2, $3}'):" \
       "$tests_line, tests ok: $tests_ok; left out under emulation: $not_emulated; conformance on PoCL: $pocl; real-flight localization (cpu): $realflight; cpu ${inner:-inner loop ?}," \
       "cpu = cpu-portable = cpu-ref on arm64: $neon_ref; $same of $((same + differ + failed)) output files equal to x86-64's" \
       "($differ differ, $failed failed; not compared: ${not_run[*]:-none}); $(( $(date +%s) - start )) s;" \
       "bit-identical to x86-64: $identical"
  [[ $tests_ok == yes && $identical == yes && $pocl == passed && $realflight == passed ]]
}

# The device kit for arm64 (scripts/device-kit --arch arm64, from this cross build) run in a bare
# arm64 Debian 12 root under qemu-user by tests/devicekit/kit_in_bare_root.sh, the x86-64 kit's own
# check: cpu-ref and cpu conformance pass, OpenCL, Vulkan and CUDA are named not available, at most
# 48 MiB. The emulated run gets a longer budget than the native one's 240 s.
arm64_kit_check() {
  arm64_prepare debootstrap patchelf
  build_checked --target trnkit_cli trn_conformance trn_bench trnkit_io_devicekit
  local log=$build/platform-check-kit.log budget=1800 rc
  set +e
  "$repo/tests/devicekit/kit_in_bare_root.sh" "$repo" "$build" "${XDG_CACHE_HOME:-$HOME/.cache}/trnkit/bare-debian" \
    "$budget" 1 arm64 > "$log" 2>&1
  rc=$?
  set -e
  (( rc == 0 )) || grep -E 'FAILED|SKIPPED|failed' "$log" | head -20 >&2
  echo "arm64-kit: aarch64-linux-gnu-g++ $(aarch64-linux-gnu-g++ -dumpfullversion), $cold build ($compiled files compiled," \
       "$warnings warnings); $(grep -E '^(PASSED|FAILED|SKIPPED)' "$log" | tail -1); $(grep -o 'needs glibc.*' "$build/device-kit/MANIFEST.txt" 2>/dev/null);" \
       "$(( $(date +%s) - start )) s; log $log"
  (( rc == 0 ))
}
