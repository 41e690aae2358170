# Shared compile settings for every fgbench target.
set(FGBENCH_WARNINGS -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast
    -Wcast-align -Woverloaded-virtual -Wnull-dereference -Wimplicit-fallthrough)
if(FGBENCH_WERROR)
  list(APPEND FGBENCH_WARNINGS -Werror)
endif()

if(FGBENCH_SANITIZE)
  # -O1 with line tables: the level ASan's authors recommend, and reports still name file and line.
  # After the build type's flags, so it wins over RelWithDebInfo's -O2 -g, which took three times
  # the compile time (flip_engine.cpp: 82 s -> 28 s of CPU) for nothing the tests use.
  add_compile_options(-O1 -g1)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=address,undefined)
endif()

# fgb_target_defaults(target): warnings and include root for a project target.
function(fgb_target_defaults target)
  target_compile_options(${target} PRIVATE ${FGBENCH_WARNINGS})
endfunction()

# fgb_add_unit_test(name SOURCES... LIBS...): a GoogleTest executable registered with CTest, label "unit".
function(fgb_add_unit_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  fgb_target_defaults(${name})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main GTest::gmock)
  set(labels unit ${ARG_LABELS})
  gtest_discover_tests(${name} PROPERTIES LABELS "${labels}" DISCOVERY_TIMEOUT 60)
endfunction()
