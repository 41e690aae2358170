# render.occlusion is conservative: renders a scene with it off and on (under validation, which
# fails the run on any message) and requires `fgbench compare --threshold 0` to find frame.exr
# identical. Three frames: the first has no history (no HiZ test in phase 1), the later ones test
# against the previous frame's HiZ. EXTRA: more `|`-separated arguments for the occlusion run.
# RENDER_PATH: visbuffer (default) or meshlet, whose statistics are vis_* and meshlet_*.
#   cmake -DFGBENCH=... -DOUT=dir "-DARGS=scene.json|--width|640|..." [-DEXTRA=...] [-DRENDER_PATH=meshlet]
#         -P occlusion-identical.cmake
if(NOT DEFINED RENDER_PATH)
  set(RENDER_PATH visbuffer)
endif()
set(stat_prefix vis)
if(RENDER_PATH STREQUAL "meshlet")
  set(stat_prefix meshlet)
endif()
string(REPLACE "|" ";" args "${ARGS}")
string(REPLACE "|" ";" extra "${EXTRA}")
file(REMOVE_RECURSE "${OUT}")
foreach(occlusion 0 1)
  set(more "")
  if(occlusion)
    set(more ${extra})
  endif()
  execute_process(COMMAND ${FGBENCH} run ${args} --device lavapipe --warmup 1 --frames 2 --validation --quiet
                          --set render.path=${RENDER_PATH} --set render.occlusion=${occlusion} ${more}
                          --out ${OUT}/occlusion-${occlusion}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "render.occlusion=${occlusion}: fgbench run ${args} exited ${rc}: ${err}${out}")
  endif()
endforeach()
file(READ ${OUT}/occlusion-1/timings.json timings)
string(JSON occluded GET "${timings}" stats ${stat_prefix}_occlusion_phase1_occluded)
string(JSON recovered GET "${timings}" stats ${stat_prefix}_occlusion_phase2_recovered)
message(STATUS "phase 1 held back ${occluded} clusters, phase 2 recovered ${recovered}")
execute_process(COMMAND ${FGBENCH} compare ${OUT}/occlusion-0/frame.exr ${OUT}/occlusion-1/frame.exr --threshold 0
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "render.occlusion=1 changed the image (${ARGS}):\n${out}${err}")
endif()
# With debug.occlusion_hold_back phase 2 must recover many clusters and still drop some (those
# hidden behind phase 1's).
if(DEFINED MIN_RECOVERED AND (recovered LESS MIN_RECOVERED OR NOT recovered LESS occluded))
  message(FATAL_ERROR "phase 2 recovered ${recovered} of ${occluded} clusters, expected at least ${MIN_RECOVERED} and not all")
endif()
