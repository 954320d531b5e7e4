# shellcheck shell=bash disable=SC2154  # repo, cache, jobs, start come from scripts/platform-check
# Sourced by scripts/platform-check: `./run test` in a Debian 13 (trixie) root, the newest toolchain
# and libraries Debian ships (GCC 14, CMake 3.31, OpenCV 4.10, PoCL 6, Mesa 25), exactly as the
# README tells a user: a clean clone of this repository's HEAD (committed work only), the two
# commands' set-up included (scripts/install-deps.sh inside the root, so its package list is checked
# on trixie too). The root is made once with debootstrap (minbase, ~150 MB, then ~2 GB of packages)
# in the cache; every run starts from a fresh clone in it. ../shared is bound read-only at its own
# path, and the clone sits beside it as the repository does here, so the tests find the real data.

# shellcheck source=scripts/lib/chroot-mounts.sh
source "$repo/scripts/lib/chroot-mounts.sh"

# debootstrap leaves its own folder (debootstrap/) in the root until the second stage has finished.
trixie_root_ready() { [[ -f $1/etc/debian_version && ! -e $1/debootstrap && $(cut -d. -f1 "$1/etc/debian_version") == 13 ]]; }

trixie_check() {
  [[ $(id -u) -eq 0 ]] || { echo "platform-check: trixie needs root (debootstrap, chroot, mounts)" >&2; exit 1; }
  apt_install_checked debootstrap
  local root=$cache/trixie/root log=$cache/trixie/run-test.log
  if ! trixie_root_ready "$root"; then
    rm -rf "$root"  # a half-made root of an earlier, interrupted run (ours: under the cache)
    mkdir -p "$cache/trixie"
    echo "platform-check: debootstrap of a Debian 13 (trixie) root into $root"
    debootstrap --variant=minbase trixie "$root" http://deb.debian.org/debian > "$cache/trixie/debootstrap.log" 2>&1 ||
      { tail -5 "$cache/trixie/debootstrap.log" >&2; echo "platform-check: debootstrap failed" >&2; exit 1; }
  fi
  cp /etc/resolv.conf "$root/etc/resolv.conf"
  # The root trusts the certificate authorities the host's administrator added (a proxy that
  # inspects TLS has its own: npm in install-deps.sh fails without it); Debian's own come with
  # ca-certificates, which install-deps.sh installs anyway.
  if compgen -G '/usr/local/share/ca-certificates/*.crt' >/dev/null; then
    mkdir -p "$root/usr/local/share/ca-certificates"
    cp /usr/local/share/ca-certificates/*.crt "$root/usr/local/share/ca-certificates/"
  fi
  trap chroot_unmount EXIT
  local bind=()
  [[ -d $repo/../shared ]] && bind=("ro:$repo/../shared")
  chroot_mount "$root" "${bind[@]}"
  # A clean clone of HEAD, as CI takes one; the previous run's clone and build are ours to replace.
  local clone
  clone=$root$(realpath "$repo/..")/trnkit-trixie
  rm -rf "$clone"
  git clone -q --no-hardlinks "$repo" "$clone"
  local commit
  commit=$(git -C "$repo" rev-parse --short HEAD)
  # The root has nothing but apt: bash, git and the rest come from install-deps.sh (`./run test`);
  # ca-certificates first, so the host's authorities above are in its bundle before npm runs.
  local in_root=(chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 JOBS="$jobs")
  # shellcheck disable=SC2016  # expanded by dpkg-query in the root
  "${in_root[@]}" /bin/bash -c 'dpkg-query -W -f="\${Status}" ca-certificates 2>/dev/null | grep -q "ok installed" ||
    { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends ca-certificates; }; update-ca-certificates' \
    > "$cache/trixie/ca.log" 2>&1 || { cat "$cache/trixie/ca.log" >&2; exit 1; }
  set +e
  "${in_root[@]}" /bin/bash -c "cd '${clone#"$root"}' && ./run test" > "$log" 2>&1
  local rc=$?
  set -e
  local tests versions
  tests=$(grep -E 'tests passed|tests failed' "$log" | tail -1)
  # shellcheck disable=SC2016  # expanded by the root's bash
  versions=$(chroot "$root" /bin/bash -c 'echo "$(g++ --version | head -1 | awk "{print \$NF}") CMake $(cmake --version | head -1 | awk "{print \$3}") OpenCV $(pkg-config --modversion opencv4) PoCL $(dpkg-query -W -f="\${Version}" pocl-opencl-icd) Mesa $(dpkg-query -W -f="\${Version}" mesa-vulkan-drivers)"' 2>/dev/null || echo "versions unknown")
  [[ $rc -eq 0 ]] || grep -E '\*\*\*Failed|\*\*\*Exception|Not Run|error:|FAILED' "$log" | head -20 >&2
  echo "trixie: Debian $(cat "$root/etc/debian_version"), GCC $versions; ./run test of $commit: exit $rc; ${tests:-no ctest summary}" \
       "($(grep -c '\*\*\*Skipped' "$log" || true) skipped); $(( $(date +%s) - start )) s; log $log"
  [[ $rc -eq 0 ]]
}
