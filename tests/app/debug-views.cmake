# The report's pictures of the clusters (issue 25, item 3): a run on a path that draws clusters
# writes debug-lod.png and debug-clusters.png (the frame again with debug.view=lod and =clusters,
# under validation like the run) and report.html shows them; they are not the shaded frame (LDR-FLIP
# above 0.2 against frame.png); forward, which draws no clusters, writes neither.
#   cmake -DFGBENCH=... -DSCENE=atrium.json -DOUT=dir -P debug-views.cmake
file(REMOVE_RECURSE "${OUT}")
set(common ${SCENE} --device lavapipe --width 160 --height 90 --warmup 0 --frames 1 --no-isolate --quiet --validation)
foreach(path visbuffer forward)
  execute_process(COMMAND ${FGBENCH} run ${common} --set render.path=${path} --out ${OUT}/${path}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "render.path=${path}: fgbench run exited ${rc}: ${err}${out}")
  endif()
endforeach()
foreach(view lod clusters)
  if(NOT EXISTS ${OUT}/visbuffer/debug-${view}.png)
    message(FATAL_ERROR "render.path=visbuffer wrote no debug-${view}.png")
  endif()
  if(EXISTS ${OUT}/forward/debug-${view}.png)
    message(FATAL_ERROR "render.path=forward draws no clusters but wrote debug-${view}.png")
  endif()
  execute_process(COMMAND ${FGBENCH} compare ${OUT}/visbuffer/frame.png ${OUT}/visbuffer/debug-${view}.png
                          --max-flip-mean 0.2 RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 1)
    message(FATAL_ERROR "debug-${view}.png is within LDR-FLIP 0.2 of the shaded frame (compare exit ${rc}):\n${out}${err}")
  endif()
  file(READ ${OUT}/visbuffer/report.html html)
  string(FIND "${html}" "alt=\"debug.view=${view}\"" at)
  if(at LESS 0)
    message(FATAL_ERROR "report.html does not show debug.view=${view}")
  endif()
endforeach()
