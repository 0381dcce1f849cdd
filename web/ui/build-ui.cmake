# Bundles the web UI into OUT, running `npm ci` first when node_modules is missing or older than
# package-lock.json. Any failure (no network for npm, a broken bundle) leaves the placeholder page
# in OUT with a warning, never a failed build:
#   cmake -DNODE=node -DNPM=npm -DSOURCE=web/ui -DOUT=build/web/ui/dist -P build-ui.cmake
set(ok TRUE)
set(stamp ${SOURCE}/node_modules/.package-lock.json)
if(NOT EXISTS ${stamp} OR ${SOURCE}/package-lock.json IS_NEWER_THAN ${stamp})
  message(STATUS "Web UI: npm ci in ${SOURCE}")
  execute_process(COMMAND ${NPM} ci --no-audit --no-fund --loglevel=error
                  WORKING_DIRECTORY ${SOURCE} RESULT_VARIABLE rc TIMEOUT 600)
  if(NOT rc EQUAL 0)
    set(ok FALSE)
    message(WARNING "Web UI: npm ci failed (${rc}); is the npm registry reachable?")
  endif()
endif()
if(ok)
  execute_process(COMMAND ${NODE} ${SOURCE}/build.mjs ${OUT} WORKING_DIRECTORY ${SOURCE} RESULT_VARIABLE rc TIMEOUT 300)
  if(NOT rc EQUAL 0)
    set(ok FALSE)
    message(WARNING "Web UI: the bundle failed (${rc})")
  endif()
endif()
if(NOT ok)
  message(WARNING "Web UI: not built; nbar serve shows the placeholder page (web/ui/placeholder/index.html)")
  file(MAKE_DIRECTORY ${OUT})
  file(COPY_FILE ${SOURCE}/placeholder/index.html ${OUT}/index.html)
  file(WRITE ${OUT}/app.js "")
  file(WRITE ${OUT}/app.css "")
endif()
