# --capture may not change the frame it captures (`cmake -P`, CTest image.capture_unchanged): the
# scene renders on each render path with and without --capture passes (under validation) and
# `fgbench compare --threshold 0` must find frame.exr and frame.png identical. The capture must
# also have written its index and counts.
# Inputs (-D): FGBENCH, SCENE, OUT.
foreach(var FGBENCH SCENE OUT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "expect-capture-unchanged.cmake: -D${var}=... is required")
  endif()
endforeach()

foreach(path forward visbuffer)
  foreach(mode plain captured)
    set(extra "")
    if(mode STREQUAL "captured")
      set(extra --capture passes)
    endif()
    execute_process(COMMAND ${FGBENCH} run ${SCENE} --device lavapipe --width 160 --height 90 --frames 4 --warmup 2
                            --no-isolate --validation --quiet --set render.path=${path} --out ${OUT}/${path}-${mode} ${extra}
                    RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
    if(NOT rc STREQUAL "0")
      message(FATAL_ERROR "${path} ${mode}: exit ${rc}: ${err}")
    endif()
  endforeach()
  foreach(file passes/passes.json passes/stats.json)
    if(NOT EXISTS ${OUT}/${path}-captured/${file})
      message(FATAL_ERROR "${path}: --capture passes wrote no ${file}")
    endif()
  endforeach()
  foreach(frame frame.exr frame.png)
    execute_process(COMMAND ${FGBENCH} compare ${OUT}/${path}-plain/${frame} ${OUT}/${path}-captured/${frame} --threshold 0
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc STREQUAL "0")
      message(FATAL_ERROR "${path}: ${frame} changed when captured (compare exit ${rc}): ${out}${err}")
    endif()
  endforeach()
endforeach()
message(STATUS "capture unchanged: frame.exr and frame.png identical with and without --capture on both paths")
