# The LOD sweep of the atrium on the visibility-buffer path (issue 25): render.lod_error is an
# ordinary sweep knob whose reference draws full detail (render.lod_error=0 in the reference's
# knobs), and the error against that reference grows once LOD is on: thresholds 1 and 4 are each
# further from it than full detail is. (Between 1 and 4 the
# order is not asserted: at 160x90 both are far coarser than a pixel's worth of geometry, and the
# aliasing of the two cuts differs more than their error.)
# Inputs (-D): FGBENCH, SCENE, OUT.
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${FGBENCH}" sweep "${SCENE}" --device lavapipe --width 160 --height 90
                        --set render.path=visbuffer --vary render.lod_error=0,1,4 --frames 2 --warmup 1
                        --out "${OUT}" --quiet
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fgbench sweep exited ${rc}: ${err}")
endif()
file(READ "${OUT}/sweep.json" json)
string(JSON referenceLod GET "${json}" references 0 config knobs render.lod_error)
if(NOT referenceLod STREQUAL "0")
  message(FATAL_ERROR "the reference renders at render.lod_error=${referenceLod}, not 0 (full detail)")
endif()
set(errors "")
foreach(index 0 1 2)
  string(JSON label GET "${json}" configurations ${index} label)
  string(JSON error GET "${json}" configurations ${index} error display flip mean)
  list(APPEND errors "${error}")
  message(STATUS "${label}: LDR-FLIP ${error}")
endforeach()
list(GET errors 0 full)
list(GET errors 1 one)
list(GET errors 2 four)
# CMake compares the decimal strings as doubles.
foreach(coarse one four)
  if(NOT ${coarse} GREATER full)
    message(FATAL_ERROR "render.lod_error's error ${${coarse}} does not exceed full detail's ${full}")
  endif()
endforeach()
