# CTest "install_consumer": cmake --install the build tree into a fresh prefix under the build
# directory, configure and build tests/consumer against it (find_package(surfcert)), run it.
# Arguments: -DBUILD_DIR=<surfcert build> -DSOURCE_DIR=<tests/consumer> -DWORK_DIR=<scratch>
# -DSANITIZE=<address,undefined> (the build's sanitizers, comma-separated; may be empty)
# -DPYTHON=<interpreter> -DPYTHON_DIR=<relative install dir> when the Python module is built:
# the installed package is imported and asked the same question.
file(REMOVE_RECURSE ${WORK_DIR})
function(step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()
step(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
set(flags "")
if(SANITIZE)
  set(flags "-DCMAKE_CXX_FLAGS=-fsanitize=${SANITIZE}" "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=${SANITIZE}")
endif()
step(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/build -DCMAKE_BUILD_TYPE=Release
     -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix ${flags})
step(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
step(${WORK_DIR}/build/consumer)
if(PYTHON)
  step(${CMAKE_COMMAND} -E env PYTHONPATH=${WORK_DIR}/prefix/${PYTHON_DIR} ${PYTHON}
       ${SOURCE_DIR}/consumer.py ${WORK_DIR}/prefix)
endif()
