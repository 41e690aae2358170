# render.occlusion is conservative along a camera path too: for each path time T in TIMES, flies
# SCENE's path up to T (frame e at e x STEP, warm-up included, so phase 1 tests each frame against
# the HiZ of the frame STEP seconds before: a moved camera) with render.occlusion=0 and 1, under
# validation, and requires `fgbench compare --threshold 0` to find the last frames identical.
# Each time must also hold clusters back in phase 1 (an occluder-rich path: the test would pass
# vacuously otherwise); the counts are printed.
#   cmake -DFGBENCH=... -DOUT=dir -DSCENE=scene.json -DSTEP=3 "-DTIMES=12|24" [-DEXTRA=a|b] -P occlusion-path.cmake
string(REPLACE "|" ";" times "${TIMES}")
string(REPLACE "|" ";" extra "${EXTRA}")
file(REMOVE_RECURSE "${OUT}")
foreach(time IN LISTS times)
  math(EXPR warmup "${time} / ${STEP}")
  foreach(occlusion 0 1)
    execute_process(COMMAND ${FGBENCH} run ${SCENE} --device lavapipe --width 320 --height 180 --time-step ${STEP}
                            --warmup ${warmup} --frames 1 --no-isolate --validation --quiet
                            --set render.path=visbuffer --set render.occlusion=${occlusion} ${extra}
                            --out ${OUT}/t${time}-occlusion-${occlusion}
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "t=${time} s, render.occlusion=${occlusion}: fgbench run exited ${rc}: ${err}${out}")
    endif()
  endforeach()
  file(READ ${OUT}/t${time}-occlusion-0/timings.json without)
  file(READ ${OUT}/t${time}-occlusion-1/timings.json with)
  string(JSON drawnWithout GET "${without}" stats vis_clusters_visible)
  string(JSON drawnWith GET "${with}" stats vis_clusters_visible)
  string(JSON occluded GET "${with}" stats vis_occlusion_phase1_occluded)
  string(JSON recovered GET "${with}" stats vis_occlusion_phase2_recovered)
  message(STATUS "t=${time} s: clusters drawn ${drawnWithout} without occlusion, ${drawnWith} with "
                 "(phase 1 held back ${occluded}, phase 2 recovered ${recovered})")
  if(NOT occluded GREATER 0)
    message(FATAL_ERROR "t=${time} s: phase 1 held no cluster back")
  endif()
  execute_process(COMMAND ${FGBENCH} compare ${OUT}/t${time}-occlusion-0/frame.exr ${OUT}/t${time}-occlusion-1/frame.exr
                          --threshold 0
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "render.occlusion=1 changed the frame at t=${time} s:\n${out}${err}")
  endif()
endforeach()
