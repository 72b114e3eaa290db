# vt-offset: the rewriting engine (lib/vt_offset.c), its exact number text (lib/vt_uv_text.c) and
# the tool. See docs/cli/vt-offset.md.
vt_add_unit_test(test_vt_uv_text offset/test_vt_uv_text.c LIBS vtlib)
vt_add_unit_test(test_vt_offset offset/test_vt_offset.c offset/offset_fixture.c LIBS vtlib)
vt_add_unit_test(test_vt_offset_numerics offset/test_vt_offset_numerics.c offset/offset_fixture.c
                 LIBS vtlib)

# Inputs for the CLI cases and the benchmark (scripts/bench/offset-throughput); not a test.
add_executable(vt-offset-gen offset/vt_offset_gen.c)
target_link_libraries(vt-offset-gen PRIVATE vtlib)
vt_target_warnings(vt-offset-gen)

# End-to-end cases of the tool, run like tests/cli.cmake's: tests/offset/cli/<case>.sh against the
# golden <case>.stdout/.stderr/.exit next to it (VT_UPDATE_GOLDEN=1 ctest -R cli_vt-offset_ to
# accept new output after a deliberate change).
set(VT_OFFSET_CLI_CASES help bad_usage rewrite options float32_warning bad_input)
foreach(case ${VT_OFFSET_CLI_CASES})
  add_test(NAME cli_vt-offset_${case}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/run_case.sh
                   ${CMAKE_CURRENT_SOURCE_DIR}/offset/cli/${case}.sh
                   ${CMAKE_CURRENT_BINARY_DIR}/offset/cli/${case}
                   $<TARGET_FILE:vt-offset> $<TARGET_FILE:vt-offset-gen>)
  set_tests_properties(cli_vt-offset_${case} PROPERTIES LABELS quick TIMEOUT 120)
endforeach()
