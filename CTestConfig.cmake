# CDash submission (`ctest -D Experimental`). Override the server with
#   cmake -DFGBENCH_CDASH_URL=https://my.cdash/submit.php?project=fgbench build
set(CTEST_PROJECT_NAME "fgbench")
set(CTEST_NIGHTLY_START_TIME "01:00:00 UTC")
if(NOT DEFINED FGBENCH_CDASH_URL)
  set(FGBENCH_CDASH_URL "https://my.cdash.org/submit.php?project=fgbench" CACHE STRING "CDash submit URL")
endif()
set(CTEST_SUBMIT_URL "${FGBENCH_CDASH_URL}")
set(CTEST_DROP_SITE_CDASH TRUE)
