# Script mode (cmake -P), run as the test `physics_library_is_pure`: the
# physics library (src/ but scenario/ and output/, include/towsim/ but
# scenario/ and output/) includes no YAML, JSON, file-stream, filesystem,
# console or command-line header, and no header of the other libraries.
file(GLOB_RECURSE files ${SOURCE_DIR}/src/*.cpp ${SOURCE_DIR}/src/*.hpp ${SOURCE_DIR}/include/towsim/*.hpp)
list(FILTER files EXCLUDE REGEX "/(src|include/towsim)/(scenario|output)/")
set(bad "")
foreach(f IN LISTS files)
  file(STRINGS ${f} lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"](yaml-cpp/|nlohmann/|fstream|filesystem|iostream|CLI/|towsim/scenario/|towsim/output/)")
  foreach(l IN LISTS lines)
    string(APPEND bad "  ${f}: ${l}\n")
  endforeach()
endforeach()
list(LENGTH files n)
if(bad)
  message(FATAL_ERROR "the physics library must not read or write files, YAML or JSON:\n${bad}")
endif()
message(STATUS "physics library: ${n} files, no I/O includes")
