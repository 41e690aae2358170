# `fgbench dot SCENE --detail full` must be DOT that Graphviz accepts, with barriers in words (no
# stage or access masks in hex). Inputs (-D): FGBENCH, DOT, SCENE, OUT (file stem).
execute_process(COMMAND ${FGBENCH} dot ${SCENE} --detail full --device lavapipe -o ${OUT}.dot
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "fgbench dot ${SCENE} failed (exit ${rc}): ${err}")
endif()
execute_process(COMMAND ${DOT} -Tsvg ${OUT}.dot -o ${OUT}.svg RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "dot -Tsvg rejected ${OUT}.dot (exit ${rc}): ${err}")
endif()
file(READ ${OUT}.dot text)
if(text MATCHES "(stages|access) 0x")
  message(FATAL_ERROR "${OUT}.dot still prints masks in hex")
endif()
if(NOT text MATCHES "before: [^\"]* → ")
  message(FATAL_ERROR "${OUT}.dot names no barrier (expected 'before: RESOURCE: STAGES → STAGES, ...')")
endif()
message(STATUS "${SCENE}: valid DOT, barriers in words")
