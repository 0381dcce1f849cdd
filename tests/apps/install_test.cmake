# Installs nbar into a fresh prefix, then builds examples/cpp/analyse-model against it with
# find_package(nbar) and runs it: what a C++ user outside the tree does.
# cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DMODEL=... -P install_test.cmake
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "failed (${code}): ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/cpp/analyse-model -B ${WORK_DIR}/build
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/analyse-model ${MODEL})
message("${last_output}")
if(NOT last_output MATCHES "crank = +[0-9.]+ deg: +-?[0-9]+\\.[0-9]+ N m")
  message(FATAL_ERROR "no torque in the output")
endif()
file(REMOVE_RECURSE ${WORK_DIR})
