# GLSL compute shaders -> SPIR-V at build time, embedded as C headers (uint32_t arrays).
#
#   trn_compile_shader(OUT_HEADER <var> SOURCE <file.comp> SYMBOL <c-name>
#                      [INCLUDE_DIRS dirs...] [DEFINES NAME=VALUE...])
#
# DEFINES builds variants of one source (e.g. with and without subgroup arithmetic).
#
# One custom command per shader, with a DEPFILE from glslangValidator so that edits to the shader
# or to any #included .glsl file rebuild the header. The header lands in
# ${CMAKE_CURRENT_BINARY_DIR}/shaders/<SYMBOL>.h and declares `const uint32_t <SYMBOL>[]`.
find_program(TRN_GLSLANG_VALIDATOR NAMES glslangValidator DOC "GLSL -> SPIR-V compiler (glslang-tools)")

function(trn_compile_shader)
  cmake_parse_arguments(ARG "" "OUT_HEADER;SOURCE;SYMBOL" "INCLUDE_DIRS;DEFINES" ${ARGN})
  if(NOT TRN_GLSLANG_VALIDATOR)
    message(FATAL_ERROR "trn_compile_shader: glslangValidator not found (install glslang-tools)")
  endif()
  get_filename_component(source "${ARG_SOURCE}" ABSOLUTE)
  set(out_dir "${CMAKE_CURRENT_BINARY_DIR}/shaders")
  set(header "${out_dir}/${ARG_SYMBOL}.h")
  set(depfile "${out_dir}/${ARG_SYMBOL}.d")
  set(include_flags "")
  foreach(dir IN LISTS ARG_INCLUDE_DIRS)
    list(APPEND include_flags "-I${dir}")
  endforeach()
  foreach(def IN LISTS ARG_DEFINES)
    list(APPEND include_flags "-D${def}")
  endforeach()
  add_custom_command(
    OUTPUT "${header}"
    COMMAND ${CMAKE_COMMAND} -E make_directory "${out_dir}"
    COMMAND ${TRN_GLSLANG_VALIDATOR} -V --target-env vulkan1.1 --quiet ${include_flags}
            --vn ${ARG_SYMBOL} --depfile "${depfile}" -o "${header}" "${source}"
    DEPENDS "${source}"
    DEPFILE "${depfile}"
    COMMENT "Compiling ${ARG_SYMBOL} (GLSL -> SPIR-V)"
    VERBATIM)
  set(${ARG_OUT_HEADER} "${header}" PARENT_SCOPE)
endfunction()
