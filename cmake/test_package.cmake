# Script mode (cmake -P), run as the test `package_find_and_link`: install the
# build BINARY_DIR into WORK_DIR/prefix, then configure, build and run the
# user's program SOURCE_DIR (tests/package) against that prefix alone.
# CXX, BUILD_TYPE: compiler and build type of the consumer; FLAGS: extra
# compile and link flags (the sanitizers when the build uses them); VERSION:
# the project's version, which the installed program must report.
function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}")
  endif()
  message(STATUS "${what}: ok")
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
run("install" ${CMAKE_COMMAND} --install ${BINARY_DIR} --prefix ${WORK_DIR}/prefix)
foreach(f lib/cmake/towsim/towsimConfig.cmake lib/cmake/towsim/towsimConfigVersion.cmake bin/towsim
          include/towsim/dynamics/dynamics.hpp)
  if(NOT EXISTS ${WORK_DIR}/prefix/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
run("configure the consumer" ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/build
    -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=${BUILD_TYPE}
    "-DCMAKE_CXX_FLAGS=${FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${FLAGS}")
run("build the consumer" ${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run("run physics_consumer" ${WORK_DIR}/build/physics_consumer)
message(STATUS "${last_output}")
run("run scenario_consumer" ${WORK_DIR}/build/scenario_consumer)
message(STATUS "${last_output}")

# The installed program reports the project's version, also in summary.json.
run("towsim --version" ${WORK_DIR}/prefix/bin/towsim --version)
if(NOT last_output STREQUAL "towsim ${VERSION}\n")
  message(FATAL_ERROR "towsim --version printed '${last_output}', expected 'towsim ${VERSION}'")
endif()
run("towsim run" ${WORK_DIR}/prefix/bin/towsim run --example cable-tow --set simulation.duration=0.2 --quiet
    --out ${WORK_DIR}/run)
file(READ ${WORK_DIR}/run/summary.json summary)
string(JSON written GET "${summary}" version)
if(NOT written STREQUAL VERSION)
  message(FATAL_ERROR "summary.json has version '${written}', expected '${VERSION}'")
endif()
message(STATUS "version ${VERSION}: printed by --version and written in summary.json")
