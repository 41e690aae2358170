# Runs fgbench with ARGS (`|`-separated) and checks its exit code (RC), that stderr is exactly one
# line matching STDERR_REGEX, and (when given) that NO_PATH was not created: bad input fails before
# any output is written.
#   cmake -DFGBENCH=... "-DARGS=run|scene.json|--set|foo.bar=1" -DRC=2 -DSTDERR_REGEX=... [-DNO_PATH=...] -P expect-exit-no-output.cmake
string(REPLACE "|" ";" args "${ARGS}")
if(NO_PATH)
  file(REMOVE_RECURSE "${NO_PATH}")
endif()
execute_process(COMMAND ${FGBENCH} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(STRIP "${err}" err)
if(NOT rc EQUAL RC)
  message(FATAL_ERROR "fgbench ${args}: expected exit ${RC}, got ${rc}; stderr: ${err}")
endif()
if(err MATCHES "\n")
  message(FATAL_ERROR "fgbench ${args}: expected one line on stderr, got:\n${err}")
endif()
if(NOT err MATCHES "${STDERR_REGEX}")
  message(FATAL_ERROR "fgbench ${args}: stderr does not match '${STDERR_REGEX}': ${err}")
endif()
if(NO_PATH AND EXISTS "${NO_PATH}")
  message(FATAL_ERROR "fgbench ${args}: wrote ${NO_PATH} although the input was bad")
endif()
message(STATUS "exit ${rc}: ${err}")
