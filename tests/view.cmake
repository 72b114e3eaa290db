# vt-view (tools/view): headless rendering tests through EGL surfaceless on Mesa llvmpipe, the
# window path under xvfb-run, and the streaming benchmark program (not a test).
if(TARGET vt-view)
  add_executable(vtv_make_store view/vtv_make_store.c)
  target_link_libraries(vtv_make_store PRIVATE vtformats vtlib m)
  vt_target_warnings(vtv_make_store)
  add_executable(vtv_check view/vtv_check.c)
  target_link_libraries(vtv_check PRIVATE vtformats vtlib PkgConfig::JANSSON m)
  vt_target_warnings(vtv_check)

  set(_vtv_cases psnr_bilinear psnr_trilinear bad_borders small_cache empty_tiles corrupt_tile sync_stats
      async debug_views cli scene_3d bc_upload window)
  foreach(case ${_vtv_cases})
    add_test(NAME view_${case}
             COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/view/run_view_test.sh ${case}
                     $<TARGET_FILE:vt-view> $<TARGET_FILE:vtv_make_store> $<TARGET_FILE:vtv_check>
                     ${CMAKE_CURRENT_BINARY_DIR}/view_work/${case})
    set_tests_properties(view_${case} PROPERTIES LABELS quick TIMEOUT 120
                         ENVIRONMENT "MESA_SHADER_CACHE_DISABLE=true")
  endforeach()
  if(TARGET vt-tiles AND TARGET vt-synth-image)
    add_test(NAME view_vt_tiles_store
             COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/view/run_view_test.sh vt_tiles_store
                     $<TARGET_FILE:vt-view> $<TARGET_FILE:vtv_make_store> $<TARGET_FILE:vtv_check>
                     ${CMAKE_CURRENT_BINARY_DIR}/view_work/vt_tiles_store $<TARGET_FILE:vt-tiles>
                     $<TARGET_FILE:vt-synth-image>)
    set_tests_properties(view_vt_tiles_store PROPERTIES LABELS quick TIMEOUT 120
                         ENVIRONMENT "MESA_SHADER_CACHE_DISABLE=true")
  endif()
  # --reference-scene: a generated scene through vt-atlas -> vt-offset -> vt-tiles --layout,
  # compared with the original OBJ and its own textures; and the sample scene when it is built.
  if(TARGET vt-atlas AND TARGET vt-offset AND TARGET vt-tiles)
    add_executable(vtv_make_scene view/vtv_make_scene.c)
    target_link_libraries(vtv_make_scene PRIVATE vtformats vtlib m)
    vt_target_warnings(vtv_make_scene)
    set(_vtv_scene_env "MESA_SHADER_CACHE_DISABLE=true" "VT_ATLAS=$<TARGET_FILE:vt-atlas>"
        "VT_OFFSET=$<TARGET_FILE:vt-offset>" "VT_TILES=$<TARGET_FILE:vt-tiles>"
        "VTV_MAKE_SCENE=$<TARGET_FILE:vtv_make_scene>")
    set(_vtv_scene_cases scene_reference reference_scene_cli)
    # samples/ is added by tests/samples.cmake, which comes later: add it here first (same
    # binary dir; samples.cmake skips it when the target exists).
    if(NOT TARGET vt-sample-scene AND EXISTS ${PROJECT_SOURCE_DIR}/samples/CMakeLists.txt)
      add_subdirectory(${PROJECT_SOURCE_DIR}/samples ${PROJECT_BINARY_DIR}/samples)
    endif()
    if(TARGET vt-sample-scene)
      list(APPEND _vtv_scene_env "VT_SAMPLE_SCENE=$<TARGET_FILE:vt-sample-scene>")
      list(APPEND _vtv_scene_cases sample_scene)
    endif()
    foreach(case ${_vtv_scene_cases})
      add_test(NAME view_${case}
               COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/view/run_view_test.sh ${case}
                       $<TARGET_FILE:vt-view> $<TARGET_FILE:vtv_make_store>
                       $<TARGET_FILE:vtv_check> ${CMAKE_CURRENT_BINARY_DIR}/view_work/${case})
      set_tests_properties(view_${case} PROPERTIES LABELS quick TIMEOUT 120
                           ENVIRONMENT "${_vtv_scene_env}")
    endforeach()
  endif()
endif()

# Streaming benchmark program for scripts/bench/view-streaming (not a test).
if(TARGET vtview_gl)
  pkg_check_modules(VTV_TURBOJPEG IMPORTED_TARGET libturbojpeg)
  if(VTV_TURBOJPEG_FOUND)
    add_executable(vtv_bench_stream view/vtv_bench_stream.c)
    target_link_libraries(vtv_bench_stream PRIVATE vtview_gl PkgConfig::VTV_TURBOJPEG)
    vt_target_warnings(vtv_bench_stream)
  endif()
endif()
