# Cross build for 64-bit ARM Linux (Jetson, Raspberry Pi 5, RK3588 boards) with Debian's
# crossbuild-essential-arm64 (aarch64-linux-gnu-gcc) against an arm64 Debian root:
#   cmake -S . -B build-arm64 -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake -DTRN_AARCH64_SYSROOT=ROOT
# ROOT holds arm64 headers, libraries and CMake package files (scripts/platform-check arm64 makes one
# from Debian's arm64 packages). Programs of the build (glslangValidator, git) stay the host's; tests
# run through qemu-user with ROOT as its library prefix.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)

# try_compile projects read this file again: hand them the root.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES TRN_AARCH64_SYSROOT)
if(NOT TRN_AARCH64_SYSROOT OR NOT EXISTS "${TRN_AARCH64_SYSROOT}/usr/include/aarch64-linux-gnu")
  message(FATAL_ERROR "cmake/aarch64-linux-gnu.cmake: -DTRN_AARCH64_SYSROOT=ROOT must name an arm64 Debian root "
                      "(ROOT/usr/include/aarch64-linux-gnu missing; scripts/platform-check arm64 makes one)")
endif()
set(CMAKE_SYSROOT "${TRN_AARCH64_SYSROOT}")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# pkg-config (exiv2) reads the root's .pc files and prefixes their paths with it.
set(ENV{PKG_CONFIG_SYSROOT_DIR} "${TRN_AARCH64_SYSROOT}")
set(ENV{PKG_CONFIG_LIBDIR} "${TRN_AARCH64_SYSROOT}/usr/lib/aarch64-linux-gnu/pkgconfig:${TRN_AARCH64_SYSROOT}/usr/share/pkgconfig")
# Test programs run (gtest discovery, ctest) under qemu-user with the root's libraries.
find_program(TRN_QEMU_AARCH64 qemu-aarch64-static qemu-aarch64)
if(TRN_QEMU_AARCH64)
  set(CMAKE_CROSSCOMPILING_EMULATOR "${TRN_QEMU_AARCH64};-L;${TRN_AARCH64_SYSROOT}")
endif()
