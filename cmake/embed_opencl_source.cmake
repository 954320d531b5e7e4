# cmake -DSOURCE=<file.cl> -DOUTPUT=<file.cpp> -DNAME=<identifier> -P embed_opencl_source.cmake
#
# Writes OUTPUT defining trn::opencl::embedded_<NAME>(): the kernel text (with every
# #include "x.clh" replaced by that file, looked up beside SOURCE) as a byte array, and its
# SHA-256. Bytes rather than a raw string literal, so no kernel text can end the literal early.
# OUTPUT is left untouched when its content would not change, so dependants do not rebuild.
include("${CMAKE_CURRENT_LIST_DIR}/embed_common.cmake")
trn_embed_require(embed_opencl_source.cmake SOURCE OUTPUT NAME)

get_filename_component(dir "${SOURCE}" DIRECTORY)
file(READ "${SOURCE}" text)

# Paste included headers in place (nested includes too; a guard macro stops repeats at compile time).
set(include_regex "(^|\n)[ \t]*#[ \t]*include[ \t]*\"([^\"]+)\"")
set(rounds 0)
while(text MATCHES "${include_regex}")
  set(header "${CMAKE_MATCH_2}")
  if(NOT EXISTS "${dir}/${header}")
    message(FATAL_ERROR "${SOURCE}: #include \"${header}\" not found in ${dir}")
  endif()
  file(READ "${dir}/${header}" header_text)
  set(directive "${CMAKE_MATCH_0}")
  string(REPLACE "${directive}" "${CMAKE_MATCH_1}// ---- begin ${header} ----\n${header_text}// ---- end ${header} ----" text "${text}")
  math(EXPR rounds "${rounds} + 1")
  if(rounds GREATER 32)
    message(FATAL_ERROR "${SOURCE}: more than 32 nested #include rounds; is there an include cycle?")
  endif()
endwhile()

string(SHA256 hash "${text}")
string(HEX "${text}" hex)
trn_hex_as_c_bytes("${hex}" 20 bytes)
get_filename_component(source_name "${SOURCE}" NAME)

set(content "// Generated from ${source_name} by cmake/embed_opencl_source.cmake. Do not edit.
#include \"embedded_kernels.hpp\"

namespace trn::opencl {
namespace {
const char kText[] = {
    ${bytes}0x00};
}  // namespace

EmbeddedKernel embedded_${NAME}() {
    return {\"${source_name}\", std::string_view(kText, sizeof kText - 1), \"${hash}\"};
}

}  // namespace trn::opencl
")

trn_write_if_changed("${OUTPUT}" "${content}")
