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
