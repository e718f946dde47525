# cmake -DNPM=... -DSRC=web -DWORK=build/web -DOUT=bundle.js -DNOTE=note.txt -DWHY=reason -P build_viewer.cmake
# Install web/package-lock.json's packages (npm ci) and bundle web/viewer.js
# with three.js (esbuild). On any failure: an empty bundle and a note saying
# why (report.html shows the note instead of the 3-D view); never fails the build.
function(no_viewer why)
  message(WARNING "towsim report: no 3-D view: ${why}")
  file(WRITE ${OUT} "")
  file(WRITE ${NOTE} "${why}")
endfunction()
if(NOT "${WHY}" STREQUAL "")
  no_viewer("${WHY}")
  return()
endif()
file(MAKE_DIRECTORY ${WORK})
foreach(f package.json package-lock.json viewer.js)
  file(COPY_FILE ${SRC}/${f} ${WORK}/${f} ONLY_IF_DIFFERENT)
endforeach()
# npm ci only when the lock file changed since the last install.
if(NOT EXISTS ${WORK}/node_modules/.installed-lock.json
   OR ${SRC}/package-lock.json IS_NEWER_THAN ${WORK}/node_modules/.installed-lock.json)
  execute_process(COMMAND ${NPM} ci --no-audit --no-fund --ignore-scripts --loglevel=error
                  WORKING_DIRECTORY ${WORK} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    string(STRIP "${err}" err)
    no_viewer("`npm ci` failed when towsim was built (${rc}; no access to the npm registry?) ${err}")
    return()
  endif()
  file(COPY_FILE ${WORK}/package-lock.json ${WORK}/node_modules/.installed-lock.json)
endif()
execute_process(COMMAND ${NPM} run --silent build -- --outfile=${OUT}.tmp
                WORKING_DIRECTORY ${WORK} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS ${OUT}.tmp)
  string(STRIP "${err}" err)
  no_viewer("bundling the 3-D view with esbuild failed when towsim was built (${rc}): ${err}")
  return()
endif()
file(RENAME ${OUT}.tmp ${OUT})
file(WRITE ${NOTE} "")
