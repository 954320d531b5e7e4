# shellcheck shell=bash
# Sourced by scripts/platform-check: an arm64 Debian 12 root made of Debian's own arm64 packages,
# unpacked (dpkg-deb -x), not installed. It is both the cross build's sysroot (headers, libraries,
# CMake package files) and the root qemu-user runs the aarch64 binaries in (QEMU_LD_PREFIX).
# Why not `apt-get install libopencv-dev:arm64` on the host: the -dev packages of OpenCV are not
# co-installable across architectures (apt would remove libopencv-dev:amd64 and 38 others), and the
# host's packages stay as they are. The arm64 package lists come from `dpkg --add-architecture arm64`.

# What trnkit links and tests with on arm64: toolchain runtime, the libraries of scripts/install-deps.sh,
# the OpenCL ICD loader with PoCL, the Vulkan loader with Mesa's lavapipe.
arm64_sysroot_packages=(
  libc6-dev libstdc++-12-dev libgomp1 dash
  libopencv-dev libeigen3-dev nlohmann-json3-dev libcli11-dev libboost-dev libexiv2-dev libpng-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  ocl-icd-opencl-dev opencl-c-headers opencl-clhpp-headers pocl-opencl-icd
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers
)

# The apt options that resolve packages as on an empty arm64 Debian: every dependency is unpacked,
# whatever the host has installed.
arm64_apt_options() {
  local dir=$1
  echo -o "Dir::State::status=$dir/empty-status" -o APT::Architecture=arm64 -o APT::Architectures::=arm64
}

# arm64_sysroot DIR: makes DIR/root once (again when the package list changes); prints nothing.
arm64_sysroot() {
  local dir=$1 root=$1/root want opts
  want=$(printf '%s\n' "${arm64_sysroot_packages[@]}" | sha256sum | cut -c1-16)
  [[ -f $root/.trnkit-sysroot && $(cat "$root/.trnkit-sysroot") == "$want" ]] && return 0
  mkdir -p "$dir/debs"
  : > "$dir/empty-status"
  # shellcheck disable=SC2207  # the options have no spaces
  opts=($(arm64_apt_options "$dir"))
  echo "platform-check: resolving the arm64 packages (${#arm64_sysroot_packages[@]} asked)"
  local sim
  sim=$(apt-get -s "${opts[@]}" --no-install-recommends install "${arm64_sysroot_packages[@]}" 2>&1) || {
    echo "platform-check: apt cannot resolve the arm64 packages (is arm64 added? dpkg --add-architecture arm64 && apt-get update):" >&2
    printf '%s\n' "$sim" | grep -E '^(E|W):' >&2
    return 1
  }
  local wanted=() missing=() entry files version
  mapfile -t wanted < <(printf '%s\n' "$sim" | sed -n 's/^Inst \([^ ]*\) (\([^ ]*\) .*/\1=\2/p')
  for entry in "${wanted[@]}"; do  # apt names the file NAME_VERSION_ARCH.deb, an epoch's ':' as %3a
    version=${entry#*=}
    files=("$dir/debs/${entry%%=*}_${version//:/%3a}"_*.deb)
    [[ -e ${files[0]} ]] || missing+=("$entry")
  done
  if [[ ${#missing[@]} -gt 0 ]]; then
    echo "platform-check: downloading ${#missing[@]} of ${#wanted[@]} arm64 packages into $dir/debs"
    (cd "$dir/debs" && apt-get "${opts[@]}" download "${missing[@]}" >/dev/null 2>"$dir/download.log") || {
      echo "platform-check: apt-get download failed; see $dir/download.log" >&2
      return 1
    }
  fi
  local tmp deb name
  tmp=$(mktemp -d "$dir/root.partial.XXXXXX")
  for entry in "${wanted[@]}"; do
    name=${entry%%=*} entry=${entry#*=}
    for deb in "$dir/debs/${name}_${entry//:/%3a}"_*.deb; do dpkg-deb -x "$deb" "$tmp"; done
  done
  arm64_sysroot_fixups "$tmp"
  echo "$want" > "$tmp/.trnkit-sysroot"
  rm -rf "$root"
  mv "$tmp" "$root"
}

# What the packages' maintainer scripts would have done and a sysroot needs.
arm64_sysroot_fixups() {
  local root=$1 link target lib
  # Absolute symlinks point into the host's / from inside the sysroot: make them relative.
  while IFS= read -r link; do
    target=$(readlink "$link")
    ln -sfn "$(realpath -m --relative-to="$(dirname "$link")" "$root$target")" "$link"
  done < <(find "$root" -type l -lname '/*')
  # dash's maintainer script makes /bin/sh: tests run trnkit through it (popen), in the root too.
  [[ -e $root/bin/sh || ! -e $root/bin/dash ]] || ln -s dash "$root/bin/sh"
  # Programs run in the root (chroot) want a /tmp (std::filesystem::temp_directory_path).
  mkdir -p "$root/tmp"
  chmod 1777 "$root/tmp"
  # update-alternatives' libblas.so.3 and liblapack.so.3 (OpenCV's core links them).
  for lib in "$root"/usr/lib/aarch64-linux-gnu/{blas,lapack}/lib*.so.3; do
    [[ -e $lib ]] && ln -sfn "${lib#"$root"/usr/lib/aarch64-linux-gnu/}" "$root/usr/lib/aarch64-linux-gnu/$(basename "$lib")"
  done
  return 0
}

# arm64_configure REPO BUILD ROOT CMAKE: configures BUILD as the cross build against ROOT, with the
# options platform-check arm64 and device-kit --arch arm64 share (no CUDA; no Python module: the
# host's Python cannot build an aarch64 one; the benchmarks on, for the kit, whatever an older
# configure of the folder cached); the log in BUILD/platform-check-configure.log.
arm64_configure() {
  local repo=$1 build=$2 root=$3 cmake=$4
  mkdir -p "$build"
  "$cmake" -S "$repo" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_TOOLCHAIN_FILE="$repo/cmake/aarch64-linux-gnu.cmake" \
    -DTRN_AARCH64_SYSROOT="$root" -DTRN_WITH_CUDA=OFF -DTRN_BUILD_BENCH=ON -DCMAKE_DISABLE_FIND_PACKAGE_Python3=ON \
    -DTRN_REQUIRE_BACKENDS="opencl;vulkan" > "$build/platform-check-configure.log" 2>&1
}
