# Embed every scenarios/*.yaml into towsim_scenario as a generated C++ source, so
# that `towsim run --example NAME` needs no file at run time. Included by the
# top-level CMakeLists.txt after towsim_scenario is defined.
file(GLOB TOWSIM_SCENARIO_FILES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/scenarios/*.yaml)
set(TOWSIM_EMBED_CPP ${PROJECT_BINARY_DIR}/generated/towsim_embedded_scenarios.cpp)
add_custom_command(
  OUTPUT ${TOWSIM_EMBED_CPP}
  COMMAND ${CMAKE_COMMAND} -DOUT=${TOWSIM_EMBED_CPP} -DSCENARIO_DIR=${PROJECT_SOURCE_DIR}/scenarios
          -P ${CMAKE_CURRENT_LIST_DIR}/embed_scenarios.cmake
  DEPENDS ${TOWSIM_SCENARIO_FILES} ${CMAKE_CURRENT_LIST_DIR}/embed_scenarios.cmake
  COMMENT "Embedding the built-in scenarios"
  VERBATIM)
target_sources(towsim_scenario PRIVATE ${TOWSIM_EMBED_CPP})
