# Install rules and the CMake package `towsim` (included by the top-level
# CMakeLists.txt). Installed: the program (bin/towsim), the libraries
# towsim::physics, towsim::scenario, towsim::output with their headers, the
# built-in scenarios (share/towsim/scenarios, also embedded in the program),
# and lib/cmake/towsim/{towsimConfig,towsimConfigVersion,towsim-*-targets}.cmake.
# A user's CMakeLists.txt:
#   find_package(towsim 0.1 REQUIRED)              # or COMPONENTS physics scenario output
#   target_link_libraries(app PRIVATE towsim::physics)
include(CMakePackageConfigHelpers)
set(TOWSIM_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/towsim)

install(TARGETS towsim RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# One export set per library, so that towsim::physics needs nothing but Eigen.
foreach(lib physics scenario output)
  install(TARGETS towsim_${lib} EXPORT towsim-${lib}-targets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(EXPORT towsim-${lib}-targets NAMESPACE towsim:: DESTINATION ${TOWSIM_CMAKE_DIR})
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/towsim DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.hpp")
install(FILES ${PROJECT_BINARY_DIR}/generated/include/towsim/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/towsim)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenarios/ DESTINATION ${CMAKE_INSTALL_DATADIR}/towsim/scenarios)

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/towsimConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/towsimConfig.cmake INSTALL_DESTINATION ${TOWSIM_CMAKE_DIR})
# 0.x: a new minor version may change the API, so only the same minor is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/towsimConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/towsimConfig.cmake ${PROJECT_BINARY_DIR}/towsimConfigVersion.cmake
        DESTINATION ${TOWSIM_CMAKE_DIR})
