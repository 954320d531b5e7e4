# shellcheck shell=bash
# Sourced by scripts/lib/trixie-check.sh and arm64-check.sh: what a program run with chroot in a
# Debian root needs from the host (proc, sys, dev with its pts and shm: PoCL reads the CPU topology
# from sysfs and aborts without it), and host folders bound at the same path inside, read-only
# unless named writable. chroot_unmount undoes exactly what chroot_mount mounted (the caller traps it).

chroot_mounted=()
# chroot_mount ROOT [ro:DIR | rw:DIR]...
chroot_mount() {
  local root=$1 m mode dir
  shift
  for m in proc sys dev dev/pts dev/shm; do  # dev's own mounts (pts, shm) are not in its bind
    mkdir -p "$root/$m"
    mountpoint -q "$root/$m" && continue
    case $m in
      proc) mount -t proc proc "$root/proc" ;;
      sys) mount -t sysfs sysfs "$root/sys" ;;
      *) mount --bind "/$m" "$root/$m" ;;
    esac
    chroot_mounted=("$root/$m" "${chroot_mounted[@]}")
  done
  for m in "$@"; do
    mode=${m%%:*} dir=$(realpath "${m#*:}")
    mkdir -p "$root$dir"
    mountpoint -q "$root$dir" && continue
    mount --bind "$dir" "$root$dir"
    [[ $mode == rw ]] || mount -o remount,bind,ro "$root$dir"
    chroot_mounted=("$root$dir" "${chroot_mounted[@]}")
  done
}
chroot_unmount() {
  local m
  for m in "${chroot_mounted[@]}"; do umount "$m" 2>/dev/null || umount -l "$m" || true; done
  chroot_mounted=()
}
