# Sourced by scripts/test.sh, run-example.sh, sanitize.sh and fuzz.sh: compile through ccache
# when it is installed (scripts/setup.sh installs it), so that a build of
# sources already compiled with the same flags, in any clone or build
# directory, is a cache hit (docs/reliability.md "CI time budget").
# A CMAKE_CXX_COMPILER_LAUNCHER already set is kept; TOWSIM_CCACHE=0: none.
# Only new build directories take it up (CMake reads it when configuring).
if [[ "${TOWSIM_CCACHE:-1}" != 0 ]] && command -v ccache >/dev/null 2>&1; then
  export CMAKE_CXX_COMPILER_LAUNCHER="${CMAKE_CXX_COMPILER_LAUNCHER:-ccache}"
  # One cache for every clone: paths under the source tree hashed relative to it.
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
fi
