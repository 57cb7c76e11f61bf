# The page's browser test (page_test.js) as ctest runs it: skipped, saying why, only where
# Debian's chromium is not installed (.ci/install-deps installs it, so CI runs it);
# playwright-core installed by `npm ci` from package-lock.json into WORK_DIR when the lock
# changed (npm's playwright-core downloads no browser: it drives the one given).
#   cmake -DKINEMA=... -DSOURCE_DIR=... -DWORK_DIR=... -DCHROMIUM=... -DNODE=... -DNPM=... -P run_page_test.cmake
if(NOT CHROMIUM OR NOT EXISTS "${CHROMIUM}")
  message("SKIPPED: chromium is not installed (Debian's chromium package; .ci/install-deps installs it)")
  return()
endif()
if(NOT NODE OR NOT NPM)
  message(FATAL_ERROR "chromium is installed but node or npm is not (Debian's nodejs and npm; .ci/install-deps installs them)")
endif()
set(browser_dir ${SOURCE_DIR}/tests/browser)
file(MAKE_DIRECTORY ${WORK_DIR})
file(SHA256 ${browser_dir}/package-lock.json lock_hash)
set(installed_hash "")
if(EXISTS ${WORK_DIR}/installed-lock.sha256)
  file(READ ${WORK_DIR}/installed-lock.sha256 installed_hash)
endif()
if(NOT installed_hash STREQUAL lock_hash OR NOT EXISTS ${WORK_DIR}/node_modules/playwright-core)
  configure_file(${browser_dir}/package.json ${WORK_DIR}/package.json COPYONLY)
  configure_file(${browser_dir}/package-lock.json ${WORK_DIR}/package-lock.json COPYONLY)
  execute_process(COMMAND ${NPM} ci --no-audit --no-fund --loglevel=error WORKING_DIRECTORY ${WORK_DIR}
                  RESULT_VARIABLE npm_status)
  if(NOT npm_status EQUAL 0)
    message(FATAL_ERROR "npm ci of tests/browser/package-lock.json failed (${npm_status}): the npm registry is needed once")
  endif()
  file(WRITE ${WORK_DIR}/installed-lock.sha256 "${lock_hash}")
endif()
execute_process(COMMAND ${NODE} ${browser_dir}/page_test.js ${KINEMA} ${SOURCE_DIR}/samples ${WORK_DIR}/pages ${CHROMIUM}
                        ${WORK_DIR}/node_modules
                RESULT_VARIABLE test_status)
if(NOT test_status EQUAL 0)
  message(FATAL_ERROR "tests/browser/page_test.js failed (${test_status})")
endif()
