# vt-tiles --layout (atlas compositing): the end-to-end test that reads the built stores back
# texel by texel.
add_executable(test_atlas_build atlas_build/test_atlas_build.c)
target_include_directories(test_atlas_build PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
target_link_libraries(test_atlas_build PRIVATE vtformats vtlib m)
vt_target_warnings(test_atlas_build)
add_test(NAME test_atlas_build
         COMMAND test_atlas_build $<TARGET_FILE:vt-tiles> ${CMAKE_CURRENT_BINARY_DIR}/atlas_build_work)
set_tests_properties(test_atlas_build PROPERTIES LABELS quick TIMEOUT 300)

# Generator of a layout of N textures for timing (docs/atlas-build.md); not a test.
add_executable(gen_atlas_bench atlas_build/gen_atlas_bench.c)
target_link_libraries(gen_atlas_bench PRIVATE vtformats vtlib)
vt_target_warnings(gen_atlas_bench)
