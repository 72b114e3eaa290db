# End-to-end tests of the command-line tools: each tests/cli/<tool>/<case>.sh is one CTest test,
# run by tests/cli/run_case.sh, which compares its stdout, stderr and exit status with the golden
# <case>.stdout, <case>.stderr and <case>.exit next to it. To accept new output after a deliberate
# change: VT_UPDATE_GOLDEN=1 ctest -R cli_ (then review the diff). Needs bash and coreutils only.

# Assertions the cases call: decoded PNG texels against the generator, tile offsets, JSON fields.
add_executable(vt-cli-check cli/vt_cli_check.c)
target_link_libraries(vt-cli-check PRIVATE vt_synth vtformats vtlib PkgConfig::JANSSON)
vt_target_warnings(vt-cli-check)

set(VT_CLI_INFO_CASES
    help version
    missing_file not_a_store truncated
    unknown_option missing_store missing_argument bad_usage out_of_range
    summary summary_shared json huge_empty
    verify_ok verify_corrupt verify_undecodable
    extract_level extract_tile extract_empty extract_u16 extract_float extract_output_error
    extract_corrupt)
foreach(case ${VT_CLI_INFO_CASES})
  add_test(NAME cli_vt-info_${case}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/run_case.sh
                   ${CMAKE_CURRENT_SOURCE_DIR}/cli/vt-info/${case}.sh
                   ${CMAKE_CURRENT_BINARY_DIR}/cli/vt-info/${case}
                   $<TARGET_FILE:vt-info> $<TARGET_FILE:vt-synth> $<TARGET_FILE:vt-cli-check>)
  set_tests_properties(cli_vt-info_${case} PROPERTIES LABELS quick TIMEOUT 120)
endforeach()

# Unit tests of the tools' shared helpers.
vt_add_unit_test(test_tool_common cli/test_tool_common.c LIBS tool_common)
