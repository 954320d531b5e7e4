# shellcheck shell=bash
# Sourced by scripts/platform-check: a CMake 3.22 binary, the version Ubuntu 22.04 and so JetPack 6
# ship (the project's floor, cmake_minimum_required(VERSION 3.22)). Debian 12 has only 3.25, so the
# script takes Ubuntu 22.04's own packages (cmake 3.22.1 and its modules), checked against the
# hashes below, and unpacks them into the cache, not onto the system. It runs on Debian 12 (the
# libraries it links, libjsoncpp25, librhash0, libuv1, libarchive13, libcurl4, are the same sonames).

cmake_floor_debs=(
  "cmake_3.22.1-1ubuntu1_amd64.deb 5cda51128ca90f80de48a63f12818f8220bb4cd8fc42853500b8a4e71039b1c9"
  "cmake-data_3.22.1-1ubuntu1_all.deb 3a29e5796d80c3da53f898972e79d8fb23d40d4ffe9bb162b67966394a45b0e9"
)

# cmake_floor DIR: prints the path of a CMake 3.22 executable unpacked under DIR, fetching it once.
cmake_floor() {
  local dir=$1 entry name sum tmp
  local exe="$dir/cmake-3.22.1/usr/bin/cmake"
  if [[ -x $exe ]] && "$exe" --version | grep -q '^cmake version 3\.22\.'; then
    echo "$exe"
    return 0
  fi
  mkdir -p "$dir/cmake-debs"
  tmp=$(mktemp -d "$dir/cmake-3.22.1.partial.XXXXXX")
  for entry in "${cmake_floor_debs[@]}"; do
    name=${entry%% *} sum=${entry##* }
    if ! echo "$sum  $dir/cmake-debs/$name" | sha256sum -c --status 2>/dev/null; then
      curl -sSf --max-time 300 -o "$dir/cmake-debs/$name.part" "http://archive.ubuntu.com/ubuntu/pool/main/c/cmake/$name" || {
        echo "platform-check: cannot fetch CMake 3.22 ($name) from archive.ubuntu.com" >&2
        rm -rf "$tmp"
        return 1
      }
      echo "$sum  $dir/cmake-debs/$name.part" | sha256sum -c --status || {
        echo "platform-check: $name does not have the expected sha256" >&2
        rm -rf "$tmp"
        return 1
      }
      mv "$dir/cmake-debs/$name.part" "$dir/cmake-debs/$name"
    fi
    dpkg-deb -x "$dir/cmake-debs/$name" "$tmp"
  done
  rm -rf "$dir/cmake-3.22.1"
  mv "$tmp" "$dir/cmake-3.22.1"
  echo "$exe"
}
