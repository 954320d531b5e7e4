# cmake -P: installs the build tree to a fresh prefix, then uses only what was installed: the
# doc's C example built by a plain `cc` call against libtrnkit_c, and (when PY_CHECK is given)
# `import trnkit` from the installed Python module.
# Variables: BUILD_DIR, WORK_DIR, LIBDIR, C_COMPILER, C_EXAMPLE; PYTHON, PYDIR, PY_CHECK;
# SANITIZER_PRELOAD (sanitized builds: the runtimes the uninstrumented consumers, the plain-cc C
# program and python3, preload so that the instrumented libraries can load; empty otherwise).
function(run_step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  if(out)
    message(STATUS "${out}")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
run_step(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
run_step(${C_COMPILER} -std=c99 -Wall -Wpedantic -Werror ${C_EXAMPLE} -I${prefix}/include -L${prefix}/${LIBDIR} -ltrnkit_c -lm
         -Wl,-rpath,${prefix}/${LIBDIR} -o ${WORK_DIR}/embed_score)
set(sanitizer_env "")
if(SANITIZER_PRELOAD)
  set(sanitizer_env LD_PRELOAD=${SANITIZER_PRELOAD} ASAN_OPTIONS=detect_leaks=0:abort_on_error=1)
endif()
run_step(${CMAKE_COMMAND} -E env ${sanitizer_env} ${WORK_DIR}/embed_score)
if(PY_CHECK)
  run_step(${CMAKE_COMMAND} -E env PYTHONPATH=${prefix}/${PYDIR} ${sanitizer_env} ${PYTHON} ${PY_CHECK} ${prefix})
endif()
