# cmake -P: install the build tree to a fresh prefix, then configure, build and run a consumer
# project that finds trnkit with find_package. Variables: BUILD_DIR, SOURCE_DIR, WORK_DIR, and
# CONSUMER_CXX_FLAGS / CONSUMER_LINKER_FLAGS (the library's own build flags; empty but for sanitizers).
file(REMOVE_RECURSE ${WORK_DIR})
foreach(step
    "${CMAKE_COMMAND};--install;${BUILD_DIR};--prefix;${WORK_DIR}/prefix"
    "${CMAKE_COMMAND};-S;${SOURCE_DIR};-B;${WORK_DIR}/consumer-build;-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix;-DCMAKE_BUILD_TYPE=Release;-DCMAKE_CXX_FLAGS=${CONSUMER_CXX_FLAGS};-DCMAKE_EXE_LINKER_FLAGS=${CONSUMER_LINKER_FLAGS}"
    "${CMAKE_COMMAND};--build;${WORK_DIR}/consumer-build"
    "${WORK_DIR}/consumer-build/consumer")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${step}\n${out}\n${err}")
  endif()
endforeach()
message(STATUS "consumer: ${out}")
