# The 3D viewer's script: viewer.js bundled with three.js (npm registry, pinned) by esbuild into
# one classic script, at build time, so the report can inline it. three.js and esbuild are
# fetched into build/npm at configure time and never committed. Without npm (or when the fetch
# fails) the build still succeeds: the bundle is empty and the report says so.
set(SEWER3D_THREE_VERSION 0.187.0)
set(SEWER3D_ESBUILD_VERSION 0.25.12)
set(npm_dir ${PROJECT_BINARY_DIR}/npm)
set(npm_stamp ${npm_dir}/three-${SEWER3D_THREE_VERSION}-esbuild-${SEWER3D_ESBUILD_VERSION}.ok)
find_program(SEWER3D_NPM npm)
if(SEWER3D_NPM AND NOT EXISTS ${npm_stamp})
  message(STATUS "report viewer: fetching three@${SEWER3D_THREE_VERSION} and esbuild from npm")
  execute_process(
    COMMAND ${SEWER3D_NPM} install --prefix ${npm_dir} --no-audit --no-fund --loglevel=error
            three@${SEWER3D_THREE_VERSION} esbuild@${SEWER3D_ESBUILD_VERSION}
    RESULT_VARIABLE npm_result OUTPUT_QUIET ERROR_VARIABLE npm_error TIMEOUT 300)
  if(npm_result EQUAL 0 AND EXISTS ${npm_dir}/node_modules/.bin/esbuild)
    file(TOUCH ${npm_stamp})
  else()
    message(WARNING "report viewer unavailable: npm install failed (${npm_result}): ${npm_error}")
  endif()
endif()

set(SEWER3D_VIEWER_BUNDLE ${CMAKE_CURRENT_BINARY_DIR}/viewer.bundle.js)
if(EXISTS ${npm_stamp})
  set(SEWER3D_VIEWER_STATE "three.js ${SEWER3D_THREE_VERSION}")
  add_custom_command(OUTPUT ${SEWER3D_VIEWER_BUNDLE}
    COMMAND ${CMAKE_COMMAND} -E env NODE_PATH=${npm_dir}/node_modules
            ${npm_dir}/node_modules/.bin/esbuild ${CMAKE_CURRENT_SOURCE_DIR}/viewer.js --bundle
            --format=iife --minify --legal-comments=inline --log-level=warning
            --outfile=${SEWER3D_VIEWER_BUNDLE}
    DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/viewer.js ${npm_stamp}
    COMMENT "Bundling the report's 3D viewer with three.js ${SEWER3D_THREE_VERSION}")
else()
  set(SEWER3D_VIEWER_STATE "unavailable")
  file(WRITE ${SEWER3D_VIEWER_BUNDLE} "")
endif()
