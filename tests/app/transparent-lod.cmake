# Transparent meshes draw the LOD cut on the visibility-buffer path (issue 25): the
# transparency-only scene rendered against its visbuffer golden at render.lod_error=0 and at a
# coarse error, under validation (which fails a run on any message).
#   - At 0 the transparent pass draws each mesh's index range as before LOD: the frame matches
#     today's golden within LDR-FLIP mean 1e-4 (a cluster-ordered image is ~0.004 away: blending
#     depends on the order of an instance's triangles), and no cluster draw is counted.
#   - At render.lod_error=8 "Mesh Render Transparent" draws clusters of the cut, fewer triangles
#     than at 0 (transparent_triangles_drawn), so a transparent pass ignoring the cut fails.
#   cmake -DFGBENCH=... -DSCENE=transparency-only.json -DGOLDEN=.../visbuffer.json -DOUT=dir -P transparent-lod.cmake
file(REMOVE_RECURSE "${OUT}")
foreach(error 0 8)
  execute_process(COMMAND ${FGBENCH} run ${SCENE} --device lavapipe --golden ${GOLDEN} --set render.lod_error=${error}
                          --warmup 1 --frames 2 --no-isolate --quiet --validation --out ${OUT}/e${error}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  file(READ ${OUT}/e${error}/timings.json json)
  string(JSON triangles_${error} GET "${json}" stats transparent_triangles_drawn)
  string(JSON clusters_${error} ERROR_VARIABLE no_clusters GET "${json}" stats transparent_clusters_drawn)
  if(NOT no_clusters STREQUAL "NOTFOUND")  # string(JSON) sets its ERROR_VARIABLE to NOTFOUND on success
    set(clusters_${error} "no")
  endif()
  message(STATUS "render.lod_error=${error}: exit ${rc}, ${triangles_${error}} transparent triangles, "
                 "${clusters_${error}} cluster draws")
  if(error STREQUAL "0")
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "render.lod_error=0 fails the golden or validation (exit ${rc}): ${err}${out}")
    endif()
    string(JSON flip GET "${json}" golden metrics display flip mean)
    if(flip GREATER 0.0001)
      message(FATAL_ERROR "render.lod_error=0: LDR-FLIP mean ${flip} against the golden: not the full-detail image")
    endif()
    if(NOT clusters_0 STREQUAL "no")
      message(FATAL_ERROR "render.lod_error=0 counted ${clusters_0} transparent cluster draws: it should draw full detail")
    endif()
  elseif(rc GREATER 1)
    message(FATAL_ERROR "render.lod_error=${error}: fgbench run exited ${rc}: ${err}${out}")
  endif()
endforeach()
if(NOT triangles_8 LESS triangles_0 OR NOT clusters_8 GREATER 0)
  message(FATAL_ERROR "render.lod_error=8 drew ${triangles_8} transparent triangles in ${clusters_8} cluster draws, "
                      "render.lod_error=0 ${triangles_0}: the transparent pass ignores the LOD cut")
endif()
