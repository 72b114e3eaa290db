# End-to-end proof of the atlas pipeline: vt-atlas -> vt-offset -> vt-tiles --layout, every face
# corner's texel compared with the original texture's (tests/pipeline/test_pipeline.c).
if(TARGET vt-atlas AND TARGET vt-offset)
  add_executable(test_pipeline pipeline/test_pipeline.c pipeline/vt_test_corners.c)
  target_include_directories(test_pipeline PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(test_pipeline PRIVATE vtformats vtlib m)
  vt_target_warnings(test_pipeline)
  add_test(NAME pipeline_texels_match
           COMMAND test_pipeline ${CMAKE_CURRENT_BINARY_DIR}/pipeline $<TARGET_FILE:vt-atlas>
                   $<TARGET_FILE:vt-offset> $<TARGET_FILE:vt-tiles> $<TARGET_FILE:vt-info>)
  set_tests_properties(pipeline_texels_match PROPERTIES LABELS quick TIMEOUT 300)
endif()
