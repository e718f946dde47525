# ctest: the build step of the 3-D view (cmake/build_viewer.cmake) without a
# working npm still succeeds, with an empty bundle and a note saying why, so
# that towsim report writes the page with that note instead of the 3-D view.
# cmake -DSCRIPT=cmake/build_viewer.cmake -DSRC=web -DWORK=dir -P check_viewer_without_npm.cmake
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} -DNPM=/nonexistent/towsim-test/npm -DSRC=${SRC} -DWORK=${WORK}
                        -DOUT=${WORK}/viewer.bundle.js -DNOTE=${WORK}/viewer.note.txt -DWHY= -P ${SCRIPT}
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "build_viewer.cmake failed the build without npm (status ${rc}): ${err}")
endif()
file(READ ${WORK}/viewer.bundle.js js)
file(READ ${WORK}/viewer.note.txt note)
if(NOT js STREQUAL "")
  message(FATAL_ERROR "a bundle was written without npm")
endif()
if(NOT note MATCHES "npm ci")
  message(FATAL_ERROR "the note does not say that npm ci failed: '${note}'")
endif()
message(STATUS "without npm: empty bundle, note: ${note}")
