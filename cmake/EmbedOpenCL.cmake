# trn_embed_opencl(<out_var> OUTPUT_DIR <dir> SOURCES <file.cl>...)
#
# Turns each OpenCL C kernel file into a generated C++ source in OUTPUT_DIR that defines
# trn::opencl::embedded_<name>() (declared in backends/opencl/embedded_kernels.hpp): the kernel
# text with its #include "x.clh" lines pasted in, and the text's SHA-256 (the program-cache key).
# Generation runs `cmake -P embed_opencl_source.cmake` at build time, so kernel edits need no
# reconfigure and no Python; the output is rewritten only when its content changes.
set(_TRN_EMBED_OPENCL_SCRIPTS "${CMAKE_CURRENT_LIST_DIR}/embed_opencl_source.cmake" "${CMAKE_CURRENT_LIST_DIR}/embed_common.cmake")

function(trn_embed_opencl out_var)
  cmake_parse_arguments(ARG "" "OUTPUT_DIR" "SOURCES" ${ARGN})
  if(NOT ARG_OUTPUT_DIR OR NOT ARG_SOURCES)
    message(FATAL_ERROR "trn_embed_opencl: OUTPUT_DIR and SOURCES are required")
  endif()
  set(generated)
  foreach(src IN LISTS ARG_SOURCES)
    get_filename_component(src "${src}" ABSOLUTE)
    get_filename_component(name "${src}" NAME_WE)
    get_filename_component(dir "${src}" DIRECTORY)
    file(GLOB headers "${dir}/*.clh")
    set(out "${ARG_OUTPUT_DIR}/opencl_kernel_${name}.cpp")
    add_custom_command(
      OUTPUT "${out}"
      COMMAND "${CMAKE_COMMAND}" "-DSOURCE=${src}" "-DOUTPUT=${out}" "-DNAME=${name}"
              -P "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/embed_opencl_source.cmake"
      DEPENDS "${src}" ${headers} ${_TRN_EMBED_OPENCL_SCRIPTS}
      COMMENT "Embedding OpenCL kernel ${name}.cl"
      VERBATIM)
    list(APPEND generated "${out}")
  endforeach()
  set(${out_var} ${generated} PARENT_SCOPE)
endfunction()
