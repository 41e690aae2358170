# One render path against another: the same scene rendered by both (the tested one under
# validation, which fails the run on any message) must agree within an LDR-FLIP mean of LIMIT
# (frame.png) and an HDR-FLIP mean of LIMIT (frame.exr).
# First use, the mesh-shader path against forward (issue 28; the defaults): at full detail
# (render.lod_error=0) and MSAA they differ where rasterisation rounds differently (the mesh
# shader's transform is forward.vert's) and where the meshlet path culls back faces of
# single-sided materials, which forward draws. At MSAA 4 on the atrium at 320x180, most triangles
# cover samples but no pixel centre: a small-triangle test against pixel centres there drops them
# (HDR-FLIP mean 0.49 against forward, walls see-through; against the sample pattern 0.0006).
# Optional: -DREFERENCE=visbuffer (the path compared with; default forward), -DTESTED=visbuffer (the
# path under test, rendered under validation; default meshlet), -DKNOBS=--set|k=v|...
# (both render with them; default render.lod_error=0) and -DLIMIT=F (both FLIP means; default 0.01),
# e.g. debug.view=lod, whose colours the meshlet path must give its clusters as the visibility buffer does.
#   cmake -DFGBENCH=... -DSCENE=atrium.json -DOUT=dir -DWIDTH=640 -DHEIGHT=360 -DMSAA=1 [-DTESTED=visbuffer] -P path-flip.cmake
file(REMOVE_RECURSE "${OUT}")
if(NOT DEFINED TESTED)
  set(TESTED meshlet)
endif()
if(NOT DEFINED REFERENCE)
  set(REFERENCE forward)
endif()
if(NOT DEFINED KNOBS)
  set(KNOBS --set render.lod_error=0)
endif()
string(REPLACE "|" ";" KNOBS "${KNOBS}")
if(NOT DEFINED LIMIT)
  set(LIMIT 0.01)
endif()
set(common ${SCENE} --device lavapipe --width ${WIDTH} --height ${HEIGHT} --msaa ${MSAA} --warmup 0 --frames 1
           --no-isolate --quiet ${KNOBS})
foreach(path ${REFERENCE} ${TESTED})
  set(more "")
  if(path STREQUAL TESTED)
    set(more --validation)
  endif()
  execute_process(COMMAND ${FGBENCH} run ${common} --set render.path=${path} ${more} --out ${OUT}/${path}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "render.path=${path}: fgbench run exited ${rc}: ${err}${out}")
  endif()
endforeach()
foreach(image frame.png frame.exr)
  execute_process(COMMAND ${FGBENCH} compare ${OUT}/${REFERENCE}/${image} ${OUT}/${TESTED}/${image} --max-flip-mean ${LIMIT}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${image}, ${REFERENCE} against ${TESTED}:\n${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${TESTED} differs from ${REFERENCE} in ${image} (exit ${rc}):\n${out}${err}")
  endif()
endforeach()
