# A knob that must not change the image (e.g. render.async: which queue runs the compute nodes):
# renders the scene with KNOB=0 and KNOB=1 under validation (any message fails the run) and requires
# `fgbench compare --threshold 0` to find frame.exr identical.
#   cmake -DFGBENCH=... -DOUT=dir -DKNOB=render.async "-DARGS=scene.json|--width|320|..." -P knob-identical.cmake
string(REPLACE "|" ";" args "${ARGS}")
file(REMOVE_RECURSE "${OUT}")
foreach(value 0 1)
  execute_process(COMMAND ${FGBENCH} run ${args} --device lavapipe --warmup 1 --frames 2 --validation --quiet
                          --set ${KNOB}=${value} --out ${OUT}/${value}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${KNOB}=${value}: fgbench run ${args} exited ${rc}: ${err}${out}")
  endif()
endforeach()
execute_process(COMMAND ${FGBENCH} compare ${OUT}/0/frame.exr ${OUT}/1/frame.exr --threshold 0
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${KNOB}=1 changed the image (${ARGS}):\n${out}${err}")
endif()
