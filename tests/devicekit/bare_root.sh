#!/usr/bin/env bash
# Makes (once) and prints the path of a bare Debian 12 root: debootstrap --variant=minbase, none of
# trnkit's packages, cached between runs. Exit 77 with the reason on stderr when it cannot be made
# here (not root, no debootstrap, no Debian mirror configured, the download failed).
#
# usage: tests/devicekit/bare_root.sh CACHE_DIR
# The mirror is the one this machine's apt already uses (its sources), so no host is named here.
set -uo pipefail
cache=${1:?usage: bare_root.sh CACHE_DIR}
root="$cache/bookworm-minbase"

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
log="$cache/debootstrap.log"
if ! debootstrap --variant=minbase bookworm "$tmp" "$mirror" > "$log" 2>&1; then
  tail -n 5 "$log" >&2
  rm -rf "$tmp"
  skip "debootstrap failed (log: $log)"
fi
touch "$tmp/.trnkit-bare-root-complete"
rm -rf "$root"
mv "$tmp" "$root" || skip "cannot move the new root into $root"
echo "$root"
