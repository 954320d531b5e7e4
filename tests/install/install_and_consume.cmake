# cmake -P: configure, build and run a consumer project that finds the installed trnkit with
# find_package and nothing else (no CMAKE_CXX_STANDARD: the targets carry C++20).
# Variables: PREFIX (an installed trnkit), SOURCE_DIR, WORK_DIR, and CONSUMER_CXX_FLAGS /
# CONSUMER_LINKER_FLAGS (the library's own build flags; empty but for sanitizers).
file(REMOVE_RECURSE ${WORK_DIR})
foreach(step
    "${CMAKE_COMMAND};-S;${SOURCE_DIR};-B;${WORK_DIR};-DCMAKE_PREFIX_PATH=${PREFIX};-DCMAKE_BUILD_TYPE=Release;-DCMAKE_CXX_FLAGS=${CONSUMER_CXX_FLAGS};-DCMAKE_EXE_LINKER_FLAGS=${CONSUMER_LINKER_FLAGS}"
    "${CMAKE_COMMAND};--build;${WORK_DIR}"
    "${WORK_DIR}/consumer")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${step}\n${out}\n${err}")
  endif()
endforeach()
message(STATUS "consumer: ${out}")
