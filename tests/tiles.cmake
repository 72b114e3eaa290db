# vt-tiles end to end: the real tool on generated images, stores read back texel by texel.
add_executable(test_vt_tiles tiles/test_vt_tiles.c tiles/tiles_check.c)
target_include_directories(test_vt_tiles PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}
                           ${CMAKE_CURRENT_SOURCE_DIR}/tiles)
target_link_libraries(test_vt_tiles PRIVATE vtformats vt_synth_images m)
vt_target_warnings(test_vt_tiles)
add_test(NAME test_vt_tiles COMMAND test_vt_tiles $<TARGET_FILE:vt-tiles> $<TARGET_FILE:vt-info>)
set_tests_properties(test_vt_tiles PROPERTIES LABELS quick TIMEOUT 600)
