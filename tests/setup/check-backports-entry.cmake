# Runs `setup.sh --backports-entry` against a stand-in /etc/apt and compares its one line (stdout or
# stderr) with EXPECTED. Inputs (-D): SETUP, APT_ETC, EXPECTED.
execute_process(COMMAND ${CMAKE_COMMAND} -E env FGBENCH_APT_ETC=${APT_ETC} FGBENCH_DEBIAN_CODENAME=bookworm bash ${SETUP} --backports-entry
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(STRIP "${out}${err}" got)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "setup.sh --backports-entry exited ${rc}: ${got}")
endif()
if(NOT got STREQUAL EXPECTED)
  message(FATAL_ERROR "${APT_ETC}:\n  expected: ${EXPECTED}\n  got:      ${got}")
endif()
message(STATUS "${APT_ETC}: ${got}")
