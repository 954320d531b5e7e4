# cmake -DINPUT=<file> -DOUTPUT=<file.cpp> -DNAME=<identifier> -DFILE_NAME=<text> -P embed_binary.cmake
#
# Writes OUTPUT defining trn::cuda::embedded_<NAME>() (backends/cuda/embedded_fatbins.hpp): the bytes
# of INPUT (a fat binary) as a 64-byte aligned array, and FILE_NAME, the source it was compiled from.
# OUTPUT is left untouched when its content would not change, so dependants do not rebuild.
include("${CMAKE_CURRENT_LIST_DIR}/embed_common.cmake")
trn_embed_require(embed_binary.cmake INPUT OUTPUT NAME FILE_NAME)
file(READ "${INPUT}" hex HEX)
string(LENGTH "${hex}" hex_length)
if(hex_length EQUAL 0)
  message(FATAL_ERROR "embed_binary.cmake: ${INPUT} is empty")
endif()
trn_hex_as_c_bytes("${hex}" 24 bytes)

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
trn_write_if_changed("${OUTPUT}" "${content}")
