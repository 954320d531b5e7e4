#!/usr/bin/env bash
# Makes (once) and prints the path of a bare Debian root: debootstrap --variant=minbase, none of
# trnkit's packages, cached between runs. Its release is the one the kit was built against, as its
# glibc is the floor the kit needs: this machine's own (bookworm = Debian 12, trixie = Debian 13)
# for this machine's architecture; Debian 12 for another one (the arm64 cross build's libraries
# come from Debian 12: scripts/lib/arm64-sysroot.sh). Exit 77 with the reason on stderr when it cannot be made
# here (not root, no debootstrap, no Debian mirror configured, the download failed).
#
# usage: tests/devicekit/bare_root.sh CACHE_DIR [ARCH]
# The mirror is the one this machine's apt already uses (its sources), so no host is named here.
# ARCH (a Debian architecture, default this machine's): another one (arm64 on x86-64) is made in two
# stages, the second run in the root through qemu-user (binfmt_misc; scripts/platform-check arm64
# registers it).
set -uo pipefail
cache=${1:?usage: bare_root.sh CACHE_DIR [ARCH]}
host_arch=$(dpkg --print-architecture 2>/dev/null || echo amd64)
arch=${2:-$host_arch}
suite=bookworm
if [[ "$arch" == "$host_arch" && -r /etc/os-release ]]; then
  codename=$(sed -n 's/^VERSION_CODENAME=["]\{0,1\}\([a-z]*\)["]\{0,1\}$/\1/p' /etc/os-release)  # read, not sourced
  [[ -n "$codename" ]] && suite=$codename
fi
root="$cache/$suite-minbase"
[[ "$arch" == "$host_arch" ]] || root="$cache/$suite-minbase-$arch"

skip() { echo "bare_root: cannot make a bare Debian root: $*" >&2; exit 77; }

if [[ -f "$root/.trnkit-bare-root-complete" ]]; then echo "$root"; exit 0; fi
[[ $(id -u) -eq 0 ]] || skip "needs root (debootstrap and chroot)"
command -v debootstrap >/dev/null || skip "debootstrap is not installed (scripts/install-deps.sh installs it)"

# The first Debian mirror of apt's own configuration (deb822 .sources or one-line .list).
mirror=""
for f in /etc/apt/sources.list.d/*.sources; do
  [[ -f "$f" ]] || continue
  mirror=$(awk '/^URIs:/ {print $2; exit}' "$f")
  [[ "$mirror" == */debian ]] && break
  mirror=""
done
if [[ -z "$mirror" && -f /etc/apt/sources.list ]]; then
  mirror=$(awk '$1 == "deb" && $2 !~ /^\[/ && $2 ~ /\/debian$/ {print $2; exit}' /etc/apt/sources.list)
fi
[[ -n "$mirror" ]] || skip "no Debian mirror in /etc/apt sources"

mkdir -p "$cache" || skip "cannot create $cache"
tmp="$cache/.partial-$$"
rm -rf "$cache"/.partial-* 2>/dev/null
log="$root.debootstrap.log"  # one per root
made=0
if [[ "$arch" == "$host_arch" ]]; then
  debootstrap --variant=minbase "$suite" "$tmp" "$mirror" > "$log" 2>&1 && made=1
else
  [[ -e /proc/sys/fs/binfmt_misc/qemu-aarch64 || "$arch" != arm64 ]] ||
    skip "aarch64 programs cannot run here (binfmt_misc has no qemu-aarch64: scripts/platform-check arm64 registers it)"
  debootstrap --arch "$arch" --foreign --variant=minbase "$suite" "$tmp" "$mirror" > "$log" 2>&1 &&
    chroot "$tmp" /debootstrap/debootstrap --second-stage >> "$log" 2>&1 && made=1
fi
if (( ! made )); then
  tail -n 5 "$log" >&2
  rm -rf "$tmp"
  skip "debootstrap failed (log: $log)"
fi
touch "$tmp/.trnkit-bare-root-complete"
rm -rf "$root"
mv "$tmp" "$root" || skip "cannot move the new root into $root"
echo "$root"
