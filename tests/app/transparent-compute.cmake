# The visibility-buffer path's transparent meshes in compute (render.transparent=compute, issue 25)
# against the hardware raster pass: the scene rendered both ways under validation (synchronization
# included; any message fails the run), each must exit 0, and their LDR-FLIP mean must stay below
# LIMIT. The images differ where the two blend orders differ: the raster pass blends instances back
# to front by their centres and an instance's triangles in index order, the compute passes sort
# every pixel's fragments by depth (and keep the nearest FGB_TRANSPARENT_K). The compute run must
# report its fragments (transparent_fragments_inserted > 0), the raster run none, so a knob that
# switched nothing fails; with MIN_LARGE, at least that many triangles took the large-triangle path;
# with MAX_TILES, "Transparent Shade" ran over at least one and at most that many 8x8 tiles
# (stats.transparent_tiles_shaded: the tiles a fragment landed in, not the whole frame).
#   cmake -DFGBENCH=... -DOUT=dir "-DARGS=scene.json|--width|320|..." -DLIMIT=0.01
#         [-DCOMPUTE=--set|render.path=FILE] [-DMIN_LARGE=1] [-DMAX_TILES=100] -P transparent-compute.cmake
string(REPLACE "|" ";" args "${ARGS}")
if(NOT DEFINED COMPUTE)
  set(COMPUTE "--set|render.path=visbuffer|--set|render.transparent=compute")
endif()
string(REPLACE "|" ";" compute "${COMPUTE}")
file(REMOVE_RECURSE "${OUT}")
foreach(side raster compute)
  if(side STREQUAL "raster")
    set(side_args --set render.path=visbuffer --set render.transparent=raster)
  else()
    set(side_args ${compute})
  endif()
  execute_process(COMMAND ${FGBENCH} run ${args} ${side_args} --device lavapipe --warmup 1 --frames 2 --no-isolate
                          --validation --quiet --out ${OUT}/${side}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${side}: fgbench run ${args} ${side_args} exited ${rc}: ${err}${out}")
  endif()
  file(READ ${OUT}/${side}/timings.json json)
  string(JSON inserted_${side} ERROR_VARIABLE missing GET "${json}" stats transparent_fragments_inserted)
  if(NOT missing STREQUAL "NOTFOUND")
    set(inserted_${side} "none")
  endif()
  string(JSON large_${side} ERROR_VARIABLE missing GET "${json}" stats transparent_large_triangles)
  string(JSON tiles_${side} ERROR_VARIABLE missing GET "${json}" stats transparent_tiles_shaded)
endforeach()
message(STATUS "fragments inserted: raster ${inserted_raster}, compute ${inserted_compute}; "
               "large triangles ${large_compute}")
if(NOT inserted_raster STREQUAL "none" OR inserted_compute STREQUAL "none" OR NOT inserted_compute GREATER 0)
  message(FATAL_ERROR "render.transparent did not switch the passes: fragments inserted raster ${inserted_raster}, "
                      "compute ${inserted_compute}")
endif()
if(DEFINED MAX_TILES AND (NOT tiles_compute GREATER 0 OR tiles_compute GREATER MAX_TILES))
  message(FATAL_ERROR "Transparent Shade ran over ${tiles_compute} tiles (1 to ${MAX_TILES} expected)")
endif()
if(DEFINED MIN_LARGE AND large_compute LESS MIN_LARGE)
  message(FATAL_ERROR "${large_compute} large triangles (at least ${MIN_LARGE} expected): the large path is untested")
endif()
execute_process(COMMAND ${FGBENCH} compare ${OUT}/raster/frame.png ${OUT}/compute/frame.png --max-flip-mean ${LIMIT}
                        --diff ${OUT}/diff.png
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "render.transparent=compute differs from raster beyond LDR-FLIP mean ${LIMIT} (${ARGS}):\n${out}${err}")
endif()
