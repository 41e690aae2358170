# A user's render path file (render.path=FILE.json, bench/paths/) renders on lavapipe with the
# validation layers and synchronization validation silent (any message: exit 3), and `fgbench dot`
# shows its compiled graph: the passes in HAS (`|`-separated) are nodes of it, those in HAS_NOT not
# (names whole: "Mesh Render" is not "Mesh Render Transparent").
# Inputs (-D): FGBENCH, SCENE, PATH_FILE, OUT (folder), HAS, HAS_NOT, EXTRA (`|`-separated arguments).
string(REPLACE "|" ";" extra "${EXTRA}")
set(common ${SCENE} --device lavapipe --width 160 --height 90 --set render.path=${PATH_FILE} ${extra})
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${FGBENCH} run ${common} --frames 2 --warmup 1 --validation --out ${OUT}
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(NOT rc STREQUAL "0" OR NOT EXISTS ${OUT}/frame.exr)
  message(FATAL_ERROR "fgbench run with render.path=${PATH_FILE} failed (exit ${rc}): ${err}")
endif()
execute_process(COMMAND ${FGBENCH} dot ${common} --detail full -o ${OUT}/path.dot
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "fgbench dot with render.path=${PATH_FILE} failed (exit ${rc}): ${err}")
endif()
file(READ ${OUT}/path.dot dot)
string(REPLACE "|" ";" has "${HAS}")
string(REPLACE "|" ";" has_not "${HAS_NOT}")
foreach(pass IN LISTS has)
  string(FIND "${dot}" "label=\"${pass}\\n" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${OUT}/path.dot: no node \"${pass}\" with render.path=${PATH_FILE}")
  endif()
endforeach()
foreach(pass IN LISTS has_not)
  string(FIND "${dot}" "label=\"${pass}\\n" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "${OUT}/path.dot: a node \"${pass}\" with render.path=${PATH_FILE}")
  endif()
endforeach()
message(STATUS "render.path=${PATH_FILE}: renders clean under validation; graph has ${HAS}, not ${HAS_NOT}")
