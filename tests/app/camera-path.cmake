# Camera paths (tests/app/CMakeLists.txt, cli.camera_path.*), under validation on lavapipe:
#   MODE=stats: flies SCENE's path and checks timings.json's per-frame stats (each measured frame's
#     path time at e x the time step, warm-up included; p99; the three slowest frames).
#   MODE=time: renders SCENE along its path, then its still view at the last frame's path time
#     (camera.time=T, --warmup 0 --frames 1), and requires frame.exr identical (threshold 0):
#     the particles are simulated to T with the same fixed step however T is reached.
#   cmake -DFGBENCH=... -DOUT=dir -DSCENE=scene.json -DMODE=stats|time [-DEXTRA=a|b] -P camera-path.cmake
string(REPLACE "|" ";" extra "${EXTRA}")
set(step 0.125)  # exact in binary: frame e's time e * step is the same number camera.time parses
if(MODE STREQUAL "stats")
  set(warmup 1)  # frames 1..3: times 0.125 .. 0.375 s
  set(frames 3)
  set(first_time 0.125)
  set(last_time 0.375)
else()
  set(warmup 2)
  set(frames 6)
endif()
# lavapipe runs workgroups on several threads: the particles' alive list (atomic appends) and so
# their blend order vary from run to run, even along the same path. One thread makes a run
# repeatable, so any difference left is the camera.time path's.
if(MODE STREQUAL "time")
  set(ENV{LP_NUM_THREADS} 1)
endif()
file(REMOVE_RECURSE "${OUT}")
function(render name)
  execute_process(COMMAND ${FGBENCH} run ${SCENE} --device lavapipe --width 160 --height 90 --validation --quiet
                          --time-step ${step} ${ARGN} ${extra} --out ${OUT}/${name}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: fgbench run ${SCENE} ${ARGN} exited ${rc}: ${err}${out}")
  endif()
endfunction()

render(path --warmup ${warmup} --frames ${frames})
file(READ ${OUT}/path/timings.json timings)
if(MODE STREQUAL "stats")
  string(JSON measured LENGTH "${timings}" samples path_time_s)
  if(NOT measured EQUAL frames)
    message(FATAL_ERROR "samples.path_time_s has ${measured} entries, expected ${frames}")
  endif()
  string(JSON first GET "${timings}" samples path_time_s 0)
  string(JSON last GET "${timings}" path end_s)
  if(NOT first EQUAL first_time OR NOT last EQUAL last_time)
    message(FATAL_ERROR "path times ${first} .. ${last}, expected ${first_time} .. ${last_time} (frame e at e x ${step} s)")
  endif()
  string(JSON slowest LENGTH "${timings}" path slowest)
  string(JSON worst GET "${timings}" path slowest 0 gpu_ms)
  string(JSON max GET "${timings}" frame_gpu_ms max)
  string(JSON p99 GET "${timings}" frame_gpu_ms p99)
  string(JSON cpuP99 GET "${timings}" frame_cpu_ms p99)
  if(NOT slowest EQUAL 3 OR NOT worst EQUAL max OR p99 GREATER max OR NOT cpuP99 GREATER 0)
    message(FATAL_ERROR "path stats: ${slowest} slowest frames (want 3), worst ${worst} ms vs max ${max}, p99 ${p99}, cpu p99 ${cpuP99}")
  endif()
  # A moving camera re-records nothing in steady state: every per-frame value lives in buffers
  # written by the host (issue 26 item 3). Executions 0 and 1 record each frame in flight's
  # buffers, and execution 2 the few whose barriers changed after the one-time Cluster Bounds;
  # the last measured frame is execution 3.
  string(JSON recorded GET "${timings}" samples nodes_recorded 2)
  if(NOT recorded EQUAL 0)
    message(FATAL_ERROR "the moving camera's execution 3 recorded ${recorded} nodes, expected 0")
  endif()
  file(READ ${OUT}/path/report.md report)
  file(READ ${OUT}/path/report.html html)
  string(REGEX MATCHALL "alt=\"frame [0-9]+\"" thumbnails "${html}")
  list(LENGTH thumbnails thumbnailCount)
  if(NOT report MATCHES "Slowest frames along the camera path" OR NOT thumbnailCount EQUAL 3)
    message(FATAL_ERROR "report.md has no slowest-frames section, or report.html ${thumbnailCount} thumbnails (want 3)")
  endif()
  message(STATUS "path ${first} .. ${last} s: worst frame ${worst} ms, p99 ${p99} ms")
else()
  math(EXPR lastFrame "${warmup} + ${frames} - 1")
  string(JSON time GET "${timings}" path end_s)
  render(still --warmup 0 --frames 1 --set camera.time=${time})
  execute_process(COMMAND ${FGBENCH} compare ${OUT}/path/frame.exr ${OUT}/still/frame.exr --threshold 0 --no-flip
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "camera.time=${time} differs from the path's frame ${lastFrame}:\n${out}${err}")
  endif()
  message(STATUS "camera.time=${time} equals the path's frame ${lastFrame}")
endif()
