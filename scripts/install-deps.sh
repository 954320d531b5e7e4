#!/usr/bin/env bash
# Installs every Debian 12 package trnkit needs to build, test, benchmark and plot, and the MAVLink
# tests' decoder from npm (node-mavlink; no MAVLink library is packaged in Debian 12).
# Idempotent: when everything is already installed it prints nothing and touches nothing.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config git ca-certificates ccache
  # libraries
  libopencv-dev libeigen3-dev libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev nlohmann-json3-dev libboost-dev
  # EXIF of camera photos (trnkit import-photos)
  libexiv2-dev
  # GeoTIFF orthophotos (optional at build time; trnkit localize --map map.tif)
  libgdal-dev
  # OpenCL: headers, ICD loader, PoCL (CPU device)
  opencl-headers ocl-icd-opencl-dev pocl-opencl-icd clinfo
  # Vulkan: loader, lavapipe (CPU device), GLSL -> SPIR-V compiler, validation layer
  libvulkan-dev mesa-vulkan-drivers glslang-tools vulkan-validationlayers vulkan-tools
  # fuzzing (libFuzzer via clang), plots, and the benchmark report script
  clang libclang-rt-dev gnuplot-nox python3  # libclang-rt-dev: the default clang's runtime (14 on Debian 12, 19 on 13)
  # the Python module (pybind11 + NumPy) and its pytest tests
  python3-dev python3-numpy python3-pybind11 pybind11-dev python3-pytest
  # `pip install .` / `pip wheel .` of the package without network (setuptools drives CMake; venvs)
  python3-pip python3-venv python3-setuptools python3-wheel
  # running the studies on a cluster engine (scripts/experiment-*; tests/cluster starts a throwaway
  # single-node Slurm) and checking the scripts
  parallel slurmctld slurmd slurm-client munge shellcheck
  # the device kit (scripts/device-kit): PNG without OpenCV's imgcodecs, RUNPATH rewriting, the bare
  # Debian root its test runs in, and the libraries NVIDIA's Vulkan ICD needs that a GPU image may lack
  libpng-dev patchelf debootstrap libglvnd0 libx11-6 libxext6
  # the MAVLink tests' independent decoder (node-mavlink, from npm below); npm too unless node has its own
  nodejs
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
# A nodejs that bundles npm (NodeSource's) conflicts with Debian's npm package: only without one.
command -v npm >/dev/null || dpkg-query -W -f='${Status}' npm 2>/dev/null | grep -q "install ok installed" || missing+=(npm)

install_packages() {
  echo "install-deps: installing ${missing[*]}"
  SUDO=""
  if [[ $(id -u) -ne 0 ]]; then
    command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install packages" >&2; exit 1; }
    SUDO=sudo
  fi
  export DEBIAN_FRONTEND=noninteractive
  # munge, slurmctld and slurmd start their daemons from their postinst (invoke-rc.d): in a container
  # that fails the install (slurmctld has no slurm.conf) or leaves stray daemons behind. A policy-rc.d
  # that refuses every start (exit 101, as Debian's docker images ship) keeps them stopped while we
  # install; an existing policy is left as it is. tests/cluster starts its own daemons when it needs them.
  policy=/usr/sbin/policy-rc.d
  if [[ ! -e $policy ]]; then
    printf '#!/bin/sh\n# installed by trnkit scripts/install-deps.sh for the duration of one install\nexit 101\n' |
      $SUDO tee "$policy" >/dev/null
    $SUDO chmod 755 "$policy"
    trap '$SUDO rm -f "$policy"' EXIT
  fi
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  echo "install-deps: done"
}
[[ ${#missing[@]} -eq 0 ]] || install_packages

# The MAVLink tests' decoder, exactly as tests/mavlink/decoder/package-lock.json pins it, installed as
# the invoking user (not root) into tests/mavlink/decoder/node_modules; again only when the lock changed.
decoder="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/tests/mavlink/decoder"
if ! cmp -s "$decoder/package-lock.json" "$decoder/node_modules/.trnkit-installed-lock" 2>/dev/null; then
  echo "install-deps: npm ci of the MAVLink test decoder (node-mavlink) in $decoder"
  if ! (cd "$decoder" && npm ci --no-audit --no-fund --loglevel=error >/dev/null); then
    echo "install-deps: npm could not install node-mavlink from the npm registry; the MAVLink decoder tests will SKIP" >&2
    exit 1
  fi
  cp "$decoder/package-lock.json" "$decoder/node_modules/.trnkit-installed-lock"
fi
