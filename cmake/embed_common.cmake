# Shared by the cmake -P scripts that embed a file into C++ (embed_opencl_source.cmake,
# embed_binary.cmake): argument checks, bytes as a C array initialiser, and writing the output only
# when its content changes (so dependants do not rebuild).

# Fails naming SCRIPT unless every variable in ARGN is defined and NAME is a C++ identifier.
function(trn_embed_require script)
  foreach(var ${ARGN})
    if(NOT DEFINED ${var})
      message(FATAL_ERROR "${script}: -D${var}=... is required")
    endif()
  endforeach()
  if(NOT NAME MATCHES "^[A-Za-z_][A-Za-z0-9_]*$")
    message(FATAL_ERROR "${script}: NAME '${NAME}' is not a C++ identifier")
  endif()
endfunction()

# HEX (lower-case hex digits, as file(READ ... HEX) and string(HEX) give) as "0x..," bytes,
# PER_LINE to a line, each line after the first indented by four spaces; into OUT.
function(trn_hex_as_c_bytes hex per_line out)
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
  string(REPEAT "0x[0-9a-f][0-9a-f]," ${per_line} line_bytes)  # CMake regexes have no {n}
  string(REGEX REPLACE "(${line_bytes})" "\\1\n    " bytes "${bytes}")
  set(${out} "${bytes}" PARENT_SCOPE)
endfunction()

# Writes CONTENT to PATH unless PATH already holds exactly that.
function(trn_write_if_changed path content)
  if(EXISTS "${path}")
    file(READ "${path}" old)
    if(old STREQUAL content)
      return()
    endif()
  endif()
  file(WRITE "${path}" "${content}")
endfunction()
