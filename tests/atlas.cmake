# vt-atlas: the packer's unit tests, the tool end to end, and the packing benchmark program.
vt_add_unit_test(test_vt_atlas_pack atlas/test_vt_atlas_pack.c LIBS vtlib)

# The packing benchmark (scripts/bench/atlas-pack runs it; not a registered test).
add_executable(vt-bench-atlas-pack atlas/bench_atlas_pack.c)
target_link_libraries(vt-bench-atlas-pack PRIVATE vtlib m)
vt_target_warnings(vt-bench-atlas-pack)

# Golden CLI cases: each tests/atlas/cli/<case>.sh runs through tests/cli/run_case.sh with
# vt-atlas, vt-synth-image (textures) and vt-atlas-dump (atlas.json read back by vt_layout_read).
add_executable(vt-atlas-dump atlas/atlas_dump.c)
target_link_libraries(vt-atlas-dump PRIVATE vtlib)
vt_target_warnings(vt-atlas-dump)
file(GLOB VT_ATLAS_CLI_CASES RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}/atlas/cli
     CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/atlas/cli/*.sh)
foreach(case_file ${VT_ATLAS_CLI_CASES})
  string(REGEX REPLACE "\\.sh$" "" case ${case_file})
  add_test(NAME cli_vt-atlas_${case}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/run_case.sh
                   ${CMAKE_CURRENT_SOURCE_DIR}/atlas/cli/${case}.sh
                   ${CMAKE_CURRENT_BINARY_DIR}/atlas/cli/${case}
                   $<TARGET_FILE:vt-atlas> $<TARGET_FILE:vt-synth-image>
                   $<TARGET_FILE:vt-atlas-dump>)
  set_tests_properties(cli_vt-atlas_${case} PROPERTIES LABELS quick TIMEOUT 120)
endforeach()

# End to end with shared entries (materials using the same texture share one cell):
# vt-atlas -> vt-offset -> vt-tiles --layout -> vt-info --extract 0, every corner's texel checked.
if(TARGET vt-offset AND TARGET vt-tiles AND TARGET vt-info)
  add_executable(test_atlas_shared atlas/test_atlas_shared.c pipeline/vt_test_corners.c)
  target_include_directories(test_atlas_shared PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}
                                                       ${CMAKE_CURRENT_SOURCE_DIR}/pipeline)
  target_link_libraries(test_atlas_shared PRIVATE vtformats vtlib m)
  vt_target_warnings(test_atlas_shared)
  add_test(NAME atlas_shared_texels_match
           COMMAND test_atlas_shared ${CMAKE_CURRENT_BINARY_DIR}/atlas_shared
                   $<TARGET_FILE:vt-atlas> $<TARGET_FILE:vt-offset> $<TARGET_FILE:vt-tiles>
                   $<TARGET_FILE:vt-info>)
  set_tests_properties(atlas_shared_texels_match PROPERTIES LABELS quick TIMEOUT 120)
endif()
