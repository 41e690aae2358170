# Interleaved repetitions through bench/ab-runs.sh (A B A B ...) on lavapipe, then compare-runs'
# verdict: its exit code (RC) and, optionally, stdout matching STDOUT_REGEX. With SAME_IMAGE the two
# sides' frame.exr must be identical (`fgbench compare --threshold 0`).
#   cmake -DBASH=... -DSCRIPT=bench/ab-runs.sh -DFGBENCH=... -DOUT=dir -DROUNDS=3 "-DARGS=scene|--width|160"
#         ["-DB_ARGS=--set|debug.slow_pass=X:200"] -DRC=0|1 [-DSTDOUT_REGEX=...] [-DSAME_IMAGE=1] -P compare-runs-ab.cmake
string(REPLACE "|" ";" args "${ARGS}")
set(b_options "")
if(DEFINED B_ARGS)
  string(REPLACE "|" ";" b_args "${B_ARGS}")
  foreach(arg IN LISTS b_args)
    list(APPEND b_options -b "${arg}")
  endforeach()
endif()
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND ${BASH} ${SCRIPT} -r ${ROUNDS} -o ${OUT} -A ${FGBENCH} -B ${FGBENCH} ${b_options} -- ${args}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "compare-runs:\n${out}")
if(NOT rc EQUAL RC)
  message(FATAL_ERROR "ab-runs.sh: expected exit ${RC}, got ${rc}; stderr: ${err}")
endif()
if(DEFINED STDOUT_REGEX AND NOT out MATCHES "${STDOUT_REGEX}")
  message(FATAL_ERROR "compare-runs output does not match '${STDOUT_REGEX}'")
endif()
if(RC EQUAL 1)
  message(STATUS "stderr: ${err}")
endif()
if(SAME_IMAGE)
  execute_process(COMMAND ${FGBENCH} compare ${OUT}/A/r1/frame.exr ${OUT}/B/r1/frame.exr --threshold 0 --no-flip
                  RESULT_VARIABLE same OUTPUT_VARIABLE compare_out ERROR_VARIABLE compare_err)
  if(NOT same EQUAL 0)
    message(FATAL_ERROR "frame.exr differs between A and B: ${compare_out} ${compare_err}")
  endif()
endif()
