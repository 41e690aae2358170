# `fgbench sweep --path-times K` on a scene with a camera path (a 1 s path round a showcase,
# without its particles, whose blend order lavapipe's threads vary): each configuration is judged
# at K path times, each against its reference at the same time. With the reference's own
# approximations fixed (SSAA 2, lighting.mode=all), msaa=4 renders exactly its reference at every
# time (error 0: another time's reference would show), msaa=1 does not.
#   cmake -DFGBENCH=... -DSCENE=particles-path.json -DOUT=dir -P check-path-sweep.cmake
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND ${FGBENCH} sweep ${SCENE} --device lavapipe --width 96 --height 54 --set scene.particles=0
                        --set lighting.mode=all --set render.ssaa=2 --reference-ssaa 2
                        --vary msaa=1,4 --frames 2 --path-times 2 --validation --quiet --out ${OUT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fgbench sweep exited ${rc}: ${err}${out}")
endif()
file(READ ${OUT}/sweep.json sweep)
string(JSON times GET "${sweep}" method path_times_s)
string(REGEX REPLACE "[ \n]" "" times "${times}")
if(NOT times STREQUAL "[0.25,0.75]")
  message(FATAL_ERROR "method.path_times_s ${times}, expected [0.25,0.75] (the midpoints of two halves of 1 s)")
endif()
foreach(index 0 1)
  string(JSON label GET "${sweep}" configurations ${index} label)
  string(JSON count LENGTH "${sweep}" configurations ${index} path_error times)
  string(JSON mean GET "${sweep}" configurations ${index} path_error ldr_flip_mean)
  string(JSON worst GET "${sweep}" configurations ${index} path_error ldr_flip_worst)
  string(JSON first GET "${sweep}" configurations ${index} path_error times 0 display flip mean)
  string(JSON second GET "${sweep}" configurations ${index} path_error times 1 display flip mean)
  message(STATUS "${label}: LDR-FLIP ${first} at 0.25 s, ${second} at 0.75 s; mean ${mean}, worst ${worst}")
  if(NOT count EQUAL 2)
    message(FATAL_ERROR "${label}: ${count} path times judged, expected 2")
  endif()
  if(label STREQUAL "msaa=4" AND (NOT worst EQUAL 0 OR NOT mean EQUAL 0))
    message(FATAL_ERROR "msaa=4 renders its reference exactly, yet its error along the path is ${mean} (worst ${worst})")
  endif()
  if(label STREQUAL "msaa=1" AND NOT (first GREATER 0 AND second GREATER 0))
    message(FATAL_ERROR "msaa=1 has no error at some path time: ${first}, ${second}")
  endif()
endforeach()
file(READ ${OUT}/sweep.md md)
if(NOT md MATCHES "## Along the camera path")
  message(FATAL_ERROR "sweep.md has no section on the camera path")
endif()
