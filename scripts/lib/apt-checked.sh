# shellcheck shell=bash
# Sourced by scripts/platform-check: installs host packages one at a time, each only after a dry run
# (apt-get -s) shows that apt would remove nothing: the machine is shared and its amd64 packages stay
# as they are. Waits for another apt or dpkg to finish instead of failing on its lock.

apt_wait_lock() {
  local locks=(/var/lib/dpkg/lock-frontend /var/lib/dpkg/lock /var/lib/apt/lists/lock)
  while fuser "${locks[@]}" >/dev/null 2>&1; do
    echo "platform-check: waiting for another apt/dpkg to finish"
    sleep 10
  done
}

# apt_install_checked PKG...: each PKG not yet installed, after a dry run that removes nothing.
apt_install_checked() {
  local p sim removed
  for p in "$@"; do
    if [[ $(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true) == "install ok installed" ]]; then
      continue
    fi
    apt_wait_lock
    sim=$(apt-get -s install --no-install-recommends "$p" 2>&1) || {
      echo "platform-check: apt cannot install $p:" >&2
      printf '%s\n' "$sim" | grep -E '^(E|W):' >&2
      return 1
    }
    removed=$(printf '%s\n' "$sim" | grep '^Remv' || true)
    if [[ -n $removed ]]; then
      echo "platform-check: refusing to install $p: apt would remove" >&2
      printf '%s\n' "$removed" >&2
      return 1
    fi
    echo "platform-check: installing $p"
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends --no-remove "$p" >/dev/null
  done
}
