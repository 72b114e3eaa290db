# End-to-end cases of vt-convert and vt-merge (tests/cli/vt-convert/, tests/cli/vt-merge/), run by
# tests/cli/run_case.sh like vt-info's (golden .stdout/.stderr/.exit next to each case; accept new
# output with VT_UPDATE_GOLDEN=1 ctest -R 'cli_vt-(convert|merge)_' and review the diff).

# Builds inputs for the cases (shards, renamed layers, a smooth image) and checks their outputs
# (index structure, decoded texels, PSNR, payload bytes).
add_executable(vt-store-check cli/vt-convert/vt_store_check.c)
target_link_libraries(vt-store-check PRIVATE tool_common vtformats vtlib m)
vt_target_warnings(vt-store-check)

set(VT_CLI_CONVERT_CASES
    help version bad_usage missing_file
    png_jpeg_png raw_png_exact jpeg_psnr one_layer threads
    jpeg_alpha_refused float_refused u16_to_u8 lossy_twice corrupt_tile store_size_limit)
set(VT_CLI_MERGE_CASES
    help version bad_usage missing_file
    shards shards_plain shards_overlap shards_conflict
    layers geometry_mismatch duplicate_name)
foreach(tool vt-convert vt-merge)
  if(tool STREQUAL "vt-convert")
    set(cases ${VT_CLI_CONVERT_CASES})
  else()
    set(cases ${VT_CLI_MERGE_CASES})
  endif()
  foreach(case ${cases})
    add_test(NAME cli_${tool}_${case}
             COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/run_case.sh
                     ${CMAKE_CURRENT_SOURCE_DIR}/cli/${tool}/${case}.sh
                     ${CMAKE_CURRENT_BINARY_DIR}/cli/${tool}/${case}
                     $<TARGET_FILE:vt-convert> $<TARGET_FILE:vt-merge> $<TARGET_FILE:vt-info>
                     $<TARGET_FILE:vt-synth> $<TARGET_FILE:vt-tiles> $<TARGET_FILE:vt-store-check>
                     $<TARGET_FILE:vt-cli-check>)
    set_tests_properties(cli_${tool}_${case} PROPERTIES LABELS quick TIMEOUT 120)
  endforeach()
endforeach()
