# The CUDA toolkit for the CUDA backend: nvcc compiles kernels/cuda/*.cu into fat binaries at build
# time; the host code is plain C++ that needs only cuda.h (the driver is opened at run time), so CMake's
# CUDA language is not enabled and no CUDA runtime is linked.
#
#   TRN_WITH_CUDA  AUTO (built when a working nvcc is found), ON (its absence fails configure), OFF
#   TRN_CUDA_ARCHS the sm_XY to build cubins for; those this nvcc cannot target are left out, by name
#   TRN_CUDA_PTX   the compute_XY of the embedded PTX (JIT on newer GPUs); empty: the oldest nvcc targets
#   TRN_CUDA_HOST_COMPILER  the host compiler nvcc preprocesses the kernels with (an older toolkit may
#                  accept only an older GCC than the C++20 one); empty: the C++ compiler when it is GCC
#
# Sets TRN_CUDA_FOUND, and TRN_CUDA_MISSING (why not) or TRN_NVCC, TRN_CUDA_INCLUDE_DIR,
# TRN_CUDA_VERSION ("13.0"), TRN_CUDA_CUBINS, TRN_CUDA_PTX_ARCH, TRN_CUDA_LEFT_OUT.
set(TRN_WITH_CUDA AUTO CACHE STRING "Build the CUDA backend: AUTO (when nvcc is found), ON (required) or OFF")
set_property(CACHE TRN_WITH_CUDA PROPERTY STRINGS AUTO ON OFF)
set(TRN_CUDA_ARCHS "53;62;72;87;90" CACHE STRING
    "GPU architectures (sm_XY numbers) for cubins: Jetson TX1/Nano 53, TX2 62, Xavier 72, Orin 87, H100/H200 90")
set(TRN_CUDA_PTX "" CACHE STRING "compute_XY number of the embedded PTX; empty: the oldest architecture nvcc targets")
set(TRN_CUDA_HOST_COMPILER "" CACHE FILEPATH "host compiler for nvcc (-ccbin); empty: the C++ compiler when it is GCC")

set(TRN_CUDA_FOUND FALSE)
set(TRN_CUDA_MISSING "")
function(_trn_cuda_missing why)
  set(TRN_CUDA_MISSING "${why}" PARENT_SCOPE)
endfunction()

if(TRN_WITH_CUDA STREQUAL "OFF")
  _trn_cuda_missing("TRN_WITH_CUDA=OFF")
  return()
endif()
if(NOT TRN_WITH_CUDA MATCHES "^(AUTO|ON)$")
  message(FATAL_ERROR "TRN_WITH_CUDA='${TRN_WITH_CUDA}': expected AUTO, ON or OFF")
endif()

find_program(TRN_NVCC nvcc HINTS ${CUDAToolkit_ROOT}/bin $ENV{CUDA_PATH}/bin /usr/local/cuda/bin
             DOC "CUDA compiler for kernels/cuda (empty: no CUDA backend)")
if(NOT TRN_NVCC)
  _trn_cuda_missing("no nvcc was found at configure time")
else()
  get_filename_component(_trn_cuda_root "${TRN_NVCC}" DIRECTORY)
  get_filename_component(_trn_cuda_root "${_trn_cuda_root}" DIRECTORY)
  find_path(TRN_CUDA_INCLUDE_DIR cuda.h HINTS "${_trn_cuda_root}/include" "${_trn_cuda_root}/targets/x86_64-linux/include"
            NO_DEFAULT_PATH)
  execute_process(COMMAND "${TRN_NVCC}" --version OUTPUT_VARIABLE _trn_nvcc_version RESULT_VARIABLE _trn_rc ERROR_QUIET)
  if(NOT _trn_rc EQUAL 0 OR NOT _trn_nvcc_version MATCHES "release ([0-9]+\\.[0-9]+)")
    _trn_cuda_missing("${TRN_NVCC} --version failed")
  elseif(NOT TRN_CUDA_INCLUDE_DIR)
    _trn_cuda_missing("cuda.h was not found beside ${TRN_NVCC}")
  else()
    set(TRN_CUDA_VERSION "${CMAKE_MATCH_1}")
  endif()
endif()

if(TRN_CUDA_VERSION)
  # What this nvcc can target (sm_XY cubins, compute_XY PTX); an nvcc without the listing targets all asked for.
  execute_process(COMMAND "${TRN_NVCC}" --list-gpu-code OUTPUT_VARIABLE _trn_codes RESULT_VARIABLE _trn_rc ERROR_QUIET)
  execute_process(COMMAND "${TRN_NVCC}" --list-gpu-arch OUTPUT_VARIABLE _trn_archs ERROR_QUIET)
  string(REGEX MATCHALL "sm_[0-9]+" _trn_codes "${_trn_codes}")
  string(REGEX MATCHALL "compute_[0-9]+" _trn_archs "${_trn_archs}")
  set(TRN_CUDA_CUBINS "")
  set(TRN_CUDA_LEFT_OUT "")
  foreach(arch IN LISTS TRN_CUDA_ARCHS)
    if(NOT _trn_rc EQUAL 0 OR "sm_${arch}" IN_LIST _trn_codes)
      list(APPEND TRN_CUDA_CUBINS ${arch})
    else()
      list(APPEND TRN_CUDA_LEFT_OUT ${arch})
    endif()
  endforeach()
  set(TRN_CUDA_PTX_ARCH "${TRN_CUDA_PTX}")
  if(NOT TRN_CUDA_PTX_ARCH)
    set(_trn_oldest 1000)
    foreach(a IN LISTS _trn_archs)
      string(REPLACE "compute_" "" a "${a}")
      if(a LESS _trn_oldest)
        set(_trn_oldest ${a})
      endif()
    endforeach()
    if(_trn_oldest EQUAL 1000)
      list(GET TRN_CUDA_CUBINS 0 _trn_oldest)
    endif()
    set(TRN_CUDA_PTX_ARCH ${_trn_oldest})
  endif()

  # One real compile, so that a toolkit that cannot work with this host compiler skips the backend
  # (AUTO) at configure time instead of failing the build.
  set(_trn_probe_dir "${CMAKE_BINARY_DIR}/CMakeFiles/trn_cuda_probe")
  file(MAKE_DIRECTORY "${_trn_probe_dir}")
  file(WRITE "${_trn_probe_dir}/probe.cu" "extern \"C\" __global__ void probe(int* p) { p[threadIdx.x] = 1; }\n")
  set(TRN_NVCC_HOST_FLAGS "")
  if(TRN_CUDA_HOST_COMPILER)
    set(TRN_NVCC_HOST_FLAGS -ccbin "${TRN_CUDA_HOST_COMPILER}")
  elseif(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    set(TRN_NVCC_HOST_FLAGS -ccbin "${CMAKE_CXX_COMPILER}")
  endif()
  execute_process(COMMAND "${TRN_NVCC}" ${TRN_NVCC_HOST_FLAGS} -fatbin -gencode arch=compute_${TRN_CUDA_PTX_ARCH},code=compute_${TRN_CUDA_PTX_ARCH}
                          -o "${_trn_probe_dir}/probe.fatbin" "${_trn_probe_dir}/probe.cu"
                  RESULT_VARIABLE _trn_rc OUTPUT_VARIABLE _trn_out ERROR_VARIABLE _trn_out)
  if(NOT _trn_rc EQUAL 0)
    string(SUBSTRING "${_trn_out}" 0 400 _trn_out)
    _trn_cuda_missing("${TRN_NVCC} could not compile a test kernel: ${_trn_out}")
  elseif(NOT TRN_CUDA_CUBINS)
    _trn_cuda_missing("nvcc ${TRN_CUDA_VERSION} targets none of TRN_CUDA_ARCHS (${TRN_CUDA_ARCHS})")
  else()
    set(TRN_CUDA_FOUND TRUE)
  endif()
endif()

if(NOT TRN_CUDA_FOUND AND TRN_WITH_CUDA STREQUAL "ON")
  message(FATAL_ERROR "TRN_WITH_CUDA=ON, but: ${TRN_CUDA_MISSING} (install the CUDA toolkit, or set TRN_WITH_CUDA=AUTO)")
endif()

# trn_cuda_fatbin(<out_var> SOURCE <file.cu>): a custom command compiling SOURCE into
# <binary dir>/<name>.fatbin (cubins for TRN_CUDA_CUBINS, PTX for TRN_CUDA_PTX_ARCH) and embedding it
# as cuda_fatbin_<name>.cpp; <out_var> is the generated source. Exact float arithmetic: -fmad=false.
# The kernels are C++11, so nvcc's default language level (older toolkits: C++14) is kept.
set(_TRN_EMBED_BINARY_SCRIPTS "${CMAKE_CURRENT_LIST_DIR}/embed_binary.cmake" "${CMAKE_CURRENT_LIST_DIR}/embed_common.cmake")
function(trn_cuda_fatbin out_var)
  cmake_parse_arguments(ARG "" "SOURCE" "" ${ARGN})
  get_filename_component(src "${ARG_SOURCE}" ABSOLUTE)
  get_filename_component(name "${src}" NAME_WE)
  get_filename_component(file_name "${src}" NAME)
  get_filename_component(dir "${src}" DIRECTORY)
  file(GLOB headers "${dir}/*.h" "${dir}/*.cuh")
  set(gencode "")
  foreach(arch IN LISTS TRN_CUDA_CUBINS)
    list(APPEND gencode -gencode arch=compute_${arch},code=sm_${arch})
  endforeach()
  list(APPEND gencode -gencode arch=compute_${TRN_CUDA_PTX_ARCH},code=compute_${TRN_CUDA_PTX_ARCH})
  set(fatbin "${CMAKE_CURRENT_BINARY_DIR}/${name}.fatbin")
  set(out "${CMAKE_CURRENT_BINARY_DIR}/cuda_fatbin_${name}.cpp")
  add_custom_command(
    OUTPUT "${out}" "${fatbin}"
    COMMAND "${TRN_NVCC}" ${TRN_NVCC_HOST_FLAGS} -fatbin -O3 -fmad=false ${gencode} -o "${fatbin}" "${src}"
    COMMAND "${CMAKE_COMMAND}" "-DINPUT=${fatbin}" "-DOUTPUT=${out}" "-DNAME=${name}" "-DFILE_NAME=${file_name}"
            -P "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/embed_binary.cmake"
    DEPENDS "${src}" ${headers} ${_TRN_EMBED_BINARY_SCRIPTS}
    COMMENT "Compiling ${file_name} with nvcc (cubins ${TRN_CUDA_CUBINS}, PTX ${TRN_CUDA_PTX_ARCH}) and embedding it"
    VERBATIM)
  set(${out_var} "${out}" PARENT_SCOPE)
endfunction()
