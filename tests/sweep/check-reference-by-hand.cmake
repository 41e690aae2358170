# Issue 30: the sweep's error is measured against a reference with the scene's look. The reference
# is made here by hand from what docs/sweep.md says it is (the scene's own bloom, every light for
# every pixel, SSAA 4, the device's most MSAA: 4 on lavapipe), with `fgbench run`, not with the
# sweep's code; its frame 2 against the configuration's frame 2 must give the sweep's error. The
# sweep must also report the reference's convergence gap (one SSAA step down) and mark a
# configuration within twice that gap as unresolved.
# Inputs (-D): FGBENCH, SCENE, OUT, WIDTH, HEIGHT.
file(REMOVE_RECURSE "${OUT}")
set(size --width ${WIDTH} --height ${HEIGHT})
function(fgbench)
  execute_process(COMMAND "${FGBENCH}" ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "fgbench ${ARGN} exited ${rc}: ${err}")
  endif()
  set(output "${out}" PARENT_SCOPE)
endfunction()

fgbench(sweep "${SCENE}" --device lavapipe ${size} --vary msaa=1,4 --frames 4 --out "${OUT}/sweep" --quiet)
file(READ "${OUT}/sweep/sweep.json" json)

# The two images the sweep compared: frame 2 of each (2 frames, none measured beyond).
fgbench(run "${SCENE}" --device lavapipe ${size} --msaa 4 --set render.ssaa=4 --set lighting.mode=all --warmup 1
        --frames 1 --out "${OUT}/reference" --quiet)
fgbench(run "${SCENE}" --device lavapipe ${size} --msaa 1 --warmup 1 --frames 1 --out "${OUT}/msaa1" --quiet)
fgbench(compare "${OUT}/reference/frame.png" "${OUT}/msaa1/frame.png" --json --fail-percent 100)
string(JSON by_hand GET "${output}" flip mean)

string(JSON swept GET "${json}" configurations 0 error display flip mean)
string(JSON floor GET "${json}" method error_floor)
string(JSON gap GET "${json}" references 0 convergence gap)
string(JSON gap_label GET "${json}" references 0 convergence label)
string(JSON unresolved_below GET "${json}" references 0 unresolved_below)
string(JSON unresolved4 GET "${json}" configurations 1 unresolved)
string(JSON error4 GET "${json}" configurations 1 error display flip mean)
message(STATUS "msaa=1: sweep ${swept}, by hand ${by_hand} (floor ${floor}); convergence gap ${gap} (${gap_label}); "
               "msaa=4 ${error4}, unresolved ${unresolved4}")

# Equal within the floor (lavapipe: both renders are deterministic, the floor 0).
if(NOT floor EQUAL 0)
  message(FATAL_ERROR "the reference's floor is ${floor}; lavapipe renders are bit-identical")
endif()
# The same to 5 decimals (CMake has no float arithmetic: compare the decimal strings).
string(SUBSTRING "${swept}0000000" 0 7 a)
string(SUBSTRING "${by_hand}0000000" 0 7 b)
if(NOT a STREQUAL b)
  message(FATAL_ERROR "the sweep's error for msaa=1 (${swept}) is not the error against a reference made by hand "
                      "with the scene's look (${by_hand})")
endif()
if(NOT gap_label STREQUAL "render.ssaa=3" OR NOT gap GREATER 0)
  message(FATAL_ERROR "no convergence gap reported (${gap_label}: ${gap})")
endif()
# The unresolved flag follows the gap: error <= 2 x gap.
if(error4 GREATER unresolved_below AND unresolved4)
  message(FATAL_ERROR "msaa=4 (${error4}) is marked unresolved above ${unresolved_below}")
endif()
if(NOT error4 GREATER unresolved_below AND NOT unresolved4)
  message(FATAL_ERROR "msaa=4 (${error4}) is within ${unresolved_below} but not marked unresolved")
endif()
file(READ "${OUT}/sweep/sweep.html" html)
string(FIND "${html}" "unresolved-band" at)
if(at LESS 0)
  message(FATAL_ERROR "sweep.html draws no convergence band")
endif()
