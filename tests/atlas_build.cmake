# vt-tiles --layout (atlas compositing): a stand-in driver with vt-tiles' options that calls
# vt_tiles_layout_run() (usable before and after vt-tiles.c wires --layout), and the end-to-end
# test that reads the built stores back texel by texel.
find_package(TIFF REQUIRED)
add_executable(vt-tiles-layout atlas_build/atlas_build_driver.c
                               ${CMAKE_SOURCE_DIR}/tools/vt_tiles_layout.c)
target_include_directories(vt-tiles-layout PRIVATE ${CMAKE_SOURCE_DIR}/tools)
target_link_libraries(vt-tiles-layout PRIVATE tool_common vtformats vtlib TIFF::TIFF m)
vt_target_warnings(vt-tiles-layout)

add_executable(test_atlas_build atlas_build/test_atlas_build.c)
target_include_directories(test_atlas_build PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
target_link_libraries(test_atlas_build PRIVATE vtformats vtlib m)
vt_target_warnings(test_atlas_build)
# The real vt-tiles once its main calls vt_tiles_layout_run() (same options), else the stand-in.
file(STRINGS ${CMAKE_SOURCE_DIR}/tools/vt-tiles.c _vt_tiles_layout_call REGEX "vt_tiles_layout_run")
if(_vt_tiles_layout_call)
  set(_atlas_build_tool $<TARGET_FILE:vt-tiles>)
else()
  set(_atlas_build_tool $<TARGET_FILE:vt-tiles-layout>)
endif()
add_test(NAME test_atlas_build
         COMMAND test_atlas_build ${_atlas_build_tool} ${CMAKE_CURRENT_BINARY_DIR}/atlas_build_work)
set_tests_properties(test_atlas_build PROPERTIES LABELS quick TIMEOUT 300)

# Generator of a layout of N textures for timing (docs/atlas-build.md); not a test.
add_executable(gen_atlas_bench atlas_build/gen_atlas_bench.c)
target_link_libraries(gen_atlas_bench PRIVATE vtformats vtlib)
vt_target_warnings(gen_atlas_bench)
