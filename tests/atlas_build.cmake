# vt-tiles --layout (atlas compositing): the end-to-end test that reads the built stores back
# texel by texel.
foreach(t test_atlas_build test_atlas_build_cells)
  add_executable(${t} atlas_build/${t}.c atlas_build/atlas_build_fixture.c)
  target_include_directories(${t} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(${t} PRIVATE vtformats vtlib m)
  vt_target_warnings(${t})
  add_test(NAME ${t} COMMAND ${t} $<TARGET_FILE:vt-tiles> ${CMAKE_CURRENT_BINARY_DIR}/${t}_work)
  set_tests_properties(${t} PROPERTIES LABELS quick TIMEOUT 300)
endforeach()

# Generator of a layout of N textures for timing (docs/atlas-build.md); not a test.
add_executable(gen_atlas_bench atlas_build/gen_atlas_bench.c)
target_link_libraries(gen_atlas_bench PRIVATE vtformats vtlib)
vt_target_warnings(gen_atlas_bench)
