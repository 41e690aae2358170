# The validation layer the tests load. Each compiled node records into its own command buffer, so
# a missing barrier between two nodes of one submit is a hazard between command buffers. Debian
# 12's layer (vulkan-validationlayers 1.3.239) checks synchronization only inside one command
# buffer; later builds of the same Khronos layer also check across the buffers of a submit, at
# vkQueueSubmit2. Debian's chromium package (installed for the browser tests) ships such a build,
# libVkLayer_khronos_validation.so. Where it is present, a manifest pointing at it is written to
# the build tree and every test runs with VK_LAYER_PATH naming it (a CTest include file sets the
# variable for the ctest process, so the tests inherit it). Without it, the system layer is used
# and tests that drop barriers on purpose between nodes (SameLayout.*) go unnoticed by it.
set(FGBENCH_VALIDATION_LAYER_LIBRARY "/usr/lib/chromium/libVkLayer_khronos_validation.so"
    CACHE FILEPATH "Khronos validation layer with submit-time synchronization validation, for the tests")
set(system_manifest /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json)
set(FGBENCH_TEST_LAYER_PATH "")
if(EXISTS "${FGBENCH_VALIDATION_LAYER_LIBRARY}" AND EXISTS "${system_manifest}")
  file(READ "${system_manifest}" manifest)
  string(REGEX REPLACE "\"library_path\": *\"[^\"]*\"" "\"library_path\": \"${FGBENCH_VALIDATION_LAYER_LIBRARY}\""
                       manifest "${manifest}")
  set(FGBENCH_TEST_LAYER_PATH "${CMAKE_BINARY_DIR}/validation-layer")
  file(WRITE "${FGBENCH_TEST_LAYER_PATH}/VkLayer_khronos_validation.json" "${manifest}")
  file(WRITE "${CMAKE_BINARY_DIR}/validation-layer-env.cmake" "set(ENV{VK_LAYER_PATH} \"${FGBENCH_TEST_LAYER_PATH}\")\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${CMAKE_BINARY_DIR}/validation-layer-env.cmake")
  message(STATUS "Tests validate with ${FGBENCH_VALIDATION_LAYER_LIBRARY} (submit-time synchronization validation)")
else()
  message(STATUS "Tests validate with the system layer: synchronization between command buffers is not checked "
                 "(no ${FGBENCH_VALIDATION_LAYER_LIBRARY})")
endif()
