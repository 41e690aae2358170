# Proves that an image test catches a real regression (`cmake -P`, run by the CTest test
# image.regression_proof). The scene is rendered against its lavapipe golden three ways:
#   1. unperturbed: must pass (exit 0);
#   2. each perturbation in PERTURBATIONS (`|`-separated --set key=value): a shader constant nudged
#      by a small amount must make the golden comparison fail: exit 1 (a check failed; no budget is
#      given, so it can only be the golden) and "check failed: golden" on stderr. Exit 0 means the
#      thresholds are too loose to see the regression; any other code means the run itself broke.
# Inputs (-D): FGBENCH, SCENE, GOLDEN, OUT, PERTURBATIONS.
foreach(var FGBENCH SCENE GOLDEN OUT PERTURBATIONS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "expect-golden-failure.cmake: -D${var}=... is required")
  endif()
endforeach()

function(render label out_dir rc_var err_var)
  execute_process(COMMAND ${FGBENCH} run ${SCENE} --device lavapipe --golden ${GOLDEN} --out ${out_dir} --quiet ${ARGN}
                  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  string(STRIP "${err}" err)
  message(STATUS "${label}: exit ${rc} ${err}")
  set(${rc_var} "${rc}" PARENT_SCOPE)
  set(${err_var} "${err}" PARENT_SCOPE)
endfunction()

render("unperturbed" ${OUT}/unperturbed rc err)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "the unperturbed render of ${SCENE} must pass its golden ${GOLDEN} (exit 0), got exit ${rc}: ${err}")
endif()

string(REPLACE "|" ";" perturbations "${PERTURBATIONS}")
set(index 0)
foreach(knob IN LISTS perturbations)
  math(EXPR index "${index} + 1")
  render("perturbed (--set ${knob})" ${OUT}/perturbed-${index} rc err --set ${knob})
  if(rc STREQUAL "0")
    message(FATAL_ERROR "--set ${knob} perturbs a shader constant, yet ${SCENE} still passes its golden: the thresholds in ${GOLDEN} are too loose to catch this regression")
  elseif(NOT rc STREQUAL "1")
    message(FATAL_ERROR "--set ${knob}: expected the golden comparison to fail with exit 1, got exit ${rc} (the run itself failed): ${err}")
  elseif(NOT err MATCHES "check failed: golden")
    message(FATAL_ERROR "--set ${knob}: exit 1, but not from the golden comparison: ${err}")
  endif()
endforeach()
message(STATUS "regression proof: ${SCENE} passes unperturbed and fails its golden under each of: ${PERTURBATIONS}")
