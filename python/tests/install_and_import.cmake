# Installs the build into a fresh prefix and imports nbar from there, from another folder.
set(prefix ${BUILD_DIR}/python-install-test)
file(REMOVE_RECURSE ${prefix})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix} --component runtime
                RESULT_VARIABLE installed OUTPUT_QUIET)
if(NOT installed EQUAL 0)
  message(FATAL_ERROR "cmake --install failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${prefix}/${PACKAGE_DIR}
                        ${PYTHON} -c "import nbar, sys; r = nbar.load(sys.argv[1]).solve(steps=5); assert nbar.__file__.startswith(sys.argv[2]), nbar.__file__; print(r.rows, 'rows from', nbar.__file__)"
                        ${EXAMPLE} ${prefix}
                WORKING_DIRECTORY ${prefix} RESULT_VARIABLE imported)
if(NOT imported EQUAL 0)
  message(FATAL_ERROR "the installed nbar package does not import")
endif()
