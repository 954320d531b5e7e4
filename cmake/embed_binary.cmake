# cmake -DINPUT=<file> -DOUTPUT=<file.cpp> -DNAME=<identifier> -DFILE_NAME=<text> -P embed_binary.cmake
#
# Writes OUTPUT defining trn::cuda::embedded_<NAME>() (backends/cuda/embedded_fatbins.hpp): the bytes
# of INPUT (a fat binary) as a 64-byte aligned array, and FILE_NAME, the source it was compiled from.
# OUTPUT is left untouched when its content would not change, so dependants do not rebuild.
foreach(var INPUT OUTPUT NAME FILE_NAME)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "embed_binary.cmake: -D${var}=... is required")
  endif()
endforeach()
if(NOT NAME MATCHES "^[A-Za-z_][A-Za-z0-9_]*$")
  message(FATAL_ERROR "embed_binary.cmake: NAME '${NAME}' is not a C++ identifier")
endif()
file(READ "${INPUT}" hex HEX)
string(LENGTH "${hex}" hex_length)
if(hex_length EQUAL 0)
  message(FATAL_ERROR "embed_binary.cmake: ${INPUT} is empty")
endif()
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
string(REPEAT "0x[0-9a-f][0-9a-f]," 24 line_bytes)  # CMake regexes have no {n}
string(REGEX REPLACE "(${line_bytes})" "\\1\n    " bytes "${bytes}")

set(content "// Generated from ${FILE_NAME} (nvcc -fatbin) by cmake/embed_binary.cmake. Do not edit.
#include \"embedded_fatbins.hpp\"

namespace trn::cuda {
namespace {
alignas(64) const unsigned char kImage[] = {
    ${bytes}};
}  // namespace

EmbeddedFatbin embedded_${NAME}() { return {\"${FILE_NAME}\", std::span<const unsigned char>(kImage, sizeof kImage)}; }

}  // namespace trn::cuda
")
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
  if(old STREQUAL content)
    return()
  endif()
endif()
file(WRITE "${OUTPUT}" "${content}")
