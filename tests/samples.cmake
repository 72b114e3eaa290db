# The sample scene (samples/) and the make rules for content builds (scripts/vt.mk).
if(NOT TARGET vt-sample-scene)
  add_subdirectory(${PROJECT_SOURCE_DIR}/samples ${PROJECT_BINARY_DIR}/samples)
endif()

# The generator: writes the scene twice (deterministic output), then a checker reads it back with
# lib/vt_obj.h and formats/vt_png_file.h (texture count, sizes, alpha, normal map, UV ranges).
set(_vt_sample_dir ${CMAKE_CURRENT_BINARY_DIR}/samples_out)
add_executable(test_sample_scene samples/test_sample_scene.c)
target_include_directories(test_sample_scene PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
target_link_libraries(test_sample_scene PRIVATE vtformats vtlib m)
vt_target_warnings(test_sample_scene)
add_test(NAME sample_scene_generate
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/samples/generate_twice.sh $<TARGET_FILE:vt-sample-scene>
                 ${_vt_sample_dir})
set_tests_properties(sample_scene_generate PROPERTIES LABELS quick TIMEOUT 120
                     FIXTURES_SETUP sample_scene)
add_test(NAME sample_scene_check COMMAND test_sample_scene ${_vt_sample_dir}/a)
set_tests_properties(sample_scene_check PROPERTIES LABELS quick TIMEOUT 120
                     FIXTURES_REQUIRED sample_scene)

# The make rules: with stand-in tools (tests/samples/fake/) that obey the CLI contract, always;
# with the real tools once they exist.
find_program(VT_MAKE_PROGRAM NAMES make gmake)
if(VT_MAKE_PROGRAM)
  add_test(NAME sample_make_fake
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/samples/make_rules.sh fake
                   ${CMAKE_CURRENT_BINARY_DIR}/samples_make_fake ${PROJECT_SOURCE_DIR}
                   $<TARGET_FILE:vt-sample-scene> ${VT_MAKE_PROGRAM})
  set_tests_properties(sample_make_fake PROPERTIES LABELS quick TIMEOUT 120)
  if(TARGET vt-atlas AND TARGET vt-offset)
    # the optional MeshLab stage (samples/meshlab/), where meshlab and xvfb are installed
    find_program(VT_MESHLABSERVER meshlabserver)
    find_program(VT_XVFB_RUN xvfb-run)
    if(VT_MESHLABSERVER AND VT_XVFB_RUN)
      add_test(NAME sample_meshlab
               COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/samples/meshlab.sh
                       ${CMAKE_CURRENT_BINARY_DIR}/samples_meshlab ${PROJECT_SOURCE_DIR}
                       $<TARGET_FILE:vt-sample-scene> ${VT_MAKE_PROGRAM} $<TARGET_FILE_DIR:vt-atlas>)
      set_tests_properties(sample_meshlab PROPERTIES LABELS long TIMEOUT 120)
    endif()
    # the real vt-atlas (its --deps file) and vt-offset with stand-ins for the store tools
    add_test(NAME sample_make_hybrid
             COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/samples/make_rules.sh hybrid
                     ${CMAKE_CURRENT_BINARY_DIR}/samples_make_hybrid ${PROJECT_SOURCE_DIR}
                     $<TARGET_FILE:vt-sample-scene> ${VT_MAKE_PROGRAM} $<TARGET_FILE_DIR:vt-atlas>)
    set_tests_properties(sample_make_hybrid PROPERTIES LABELS quick TIMEOUT 120)
    add_test(NAME sample_make_real
             COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/samples/make_rules.sh real
                     ${CMAKE_CURRENT_BINARY_DIR}/samples_make_real ${PROJECT_SOURCE_DIR}
                     $<TARGET_FILE:vt-sample-scene> ${VT_MAKE_PROGRAM}
                     $<TARGET_FILE_DIR:vt-atlas>)
    set_tests_properties(sample_make_real PROPERTIES LABELS long TIMEOUT 300 SKIP_RETURN_CODE 77)
    if(VT_SANITIZE)
      # the full-size scene takes ~50 s through sanitized tools (10 s without): half-size textures
      set_tests_properties(sample_make_real PROPERTIES ENVIRONMENT "VT_SAMPLE_TEST_FLAGS=--shrink 2")
    endif()
  endif()
endif()
