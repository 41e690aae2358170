# Fixture of the browser test: renders SCENE against its golden into OUT (report.html with the
# reference, test and heat map) and writes OUT/expect.txt, the counts the rendered page must show,
# taken from the run's own timings.json: one bar per measured pass, one timeline box and one row per
# pass with a begin timestamp, one point per frame in each frame-time series, four images.
# Inputs (-D): FGBENCH, SCENE, GOLDEN, OUT.
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND ${FGBENCH} run ${SCENE} --device lavapipe --golden ${GOLDEN} --out ${OUT} --quiet
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
# Exit 1 (golden over threshold) still writes the report; anything else is a broken run.
if(NOT rc MATCHES "^[01]$" OR NOT EXISTS "${OUT}/report.html")
  message(FATAL_ERROR "fgbench run ${SCENE} failed (exit ${rc}): ${err}")
endif()

file(READ "${OUT}/timings.json" timings)
string(JSON pass_count LENGTH "${timings}" passes)
set(bars 0)
set(spans 0)
math(EXPR last "${pass_count} - 1")
foreach(i RANGE ${last})
  string(JSON culled GET "${timings}" passes ${i} culled)
  if(culled)
    continue()
  endif()
  math(EXPR bars "${bars} + 1")
  string(JSON start_type ERROR_VARIABLE no_start TYPE "${timings}" passes ${i} start_ms)
  if(start_type STREQUAL "ARRAY")
    math(EXPR spans "${spans} + 1")
  endif()
endforeach()
string(JSON gpu_frames GET "${timings}" frame_gpu_ms n)
string(JSON cpu_frames GET "${timings}" frame_cpu_ms n)
math(EXPR points "${gpu_frames} + ${cpu_frames}")
if(bars EQUAL 0 OR spans EQUAL 0 OR gpu_frames EQUAL 0)
  message(FATAL_ERROR "${OUT}/timings.json: ${bars} measured passes, ${spans} with begin timestamps, ${gpu_frames} frames: nothing to check")
endif()
file(WRITE "${OUT}/expect.txt"
     "#chart-passes rect.bar=${bars}\n"
     "#chart-timeline rect.span=${spans}\n"
     "#chart-timeline rect.row-bar=${spans}\n"
     "points #chart-frames polyline=${points}\n"
     "img=4\n")
message(STATUS "${OUT}/report.html: ${bars} passes, ${spans} with begin timestamps, ${gpu_frames} frames")
