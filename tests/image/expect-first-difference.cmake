# Proves that per-pass goldens localise a regression (`cmake -P`, CTest tests image.localise.*).
# Each case injects a known fault into one node (a debug knob: debug.inject_bias=PASS adds a small
# constant in that pass's shader, debug.drop_light=K drops a light in "Clustered Light Cull",
# debug.inject_nan=PASS writes one NaN) and renders the scene against its lavapipe golden, which
# has per-pass goldens. The run must fail its golden (exit 1) and name exactly that node as the
# first difference: 'first difference at "NODE"' on stderr, and no other node (one fault, one
# entry point). Runs under validation with synchronization validation.
# Inputs (-D): FGBENCH, SCENE, GOLDEN, OUT, CASES (`|`-separated KNOB=VALUE>NODE).
foreach(var FGBENCH SCENE GOLDEN OUT CASES)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "expect-first-difference.cmake: -D${var}=... is required")
  endif()
endforeach()

string(REPLACE "|" ";" cases "${CASES}")
set(index 0)
foreach(case IN LISTS cases)
  math(EXPR index "${index} + 1")
  string(FIND "${case}" ">" split)
  string(SUBSTRING "${case}" 0 ${split} knob)
  math(EXPR after "${split} + 1")
  string(SUBSTRING "${case}" ${after} -1 node)
  execute_process(COMMAND ${FGBENCH} run ${SCENE} --device lavapipe --golden ${GOLDEN} --out ${OUT}/case-${index}
                          --quiet --no-isolate --validation --set ${knob}
                  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  string(STRIP "${err}" err)
  message(STATUS "--set ${knob}: exit ${rc} ${err}")
  if(NOT rc STREQUAL "1")
    message(FATAL_ERROR "--set ${knob}: expected the golden comparison to fail (exit 1), got exit ${rc}: ${err}")
  endif()
  if(NOT err MATCHES "first difference at \"${node}\" \\(")
    message(FATAL_ERROR "--set ${knob}: the fault is in \"${node}\", but the harness said: ${err}")
  endif()
endforeach()
message(STATUS "localisation proof: ${SCENE} against ${GOLDEN}: each fault named at its node (${CASES})")
