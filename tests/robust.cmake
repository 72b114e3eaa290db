# Robustness of the .vts reader and writer (docs/robustness.md): corrupted files with exact
# statuses, every truncated prefix, seeded mutations, the golden bad files of tests/data/bad/,
# and a writer killed mid-way.
add_library(vts_fixture STATIC robust/vts_fixture.c robust/vts_reseal.c)
target_include_directories(vts_fixture PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
target_link_libraries(vts_fixture PUBLIC vts_static)
vt_target_warnings(vts_fixture)

vt_add_unit_test(test_vts_corrupt robust/test_vts_corrupt.c LIBS vts_fixture)
vt_add_unit_test(test_vts_truncate robust/test_vts_truncate.c LIBS vts_fixture)
vt_add_unit_test(test_vts_mutate robust/test_vts_mutate.c LIBS vts_fixture)
vt_add_unit_test(test_vts_bad_files robust/test_vts_bad_files.c LIBS vts_fixture)
target_compile_definitions(test_vts_bad_files
                           PRIVATE VT_BAD_DIR="${CMAKE_CURRENT_SOURCE_DIR}/data/bad")
vt_add_unit_test(test_kill_writer robust/test_kill_writer.c LIBS vts_fixture)
# Regression for the 256 MiB index buffer: sees every allocation of the reader through --wrap.
vt_add_unit_test(test_vts_open_alloc robust/test_vts_open_alloc.c LIBS vts_fixture)
target_link_options(test_vts_open_alloc PRIVATE
                    "LINKER:--wrap=malloc,--wrap=calloc,--wrap=realloc")

# Faults against the tools that write outputs: SIGINT/SIGTERM/SIGKILL at several points, a full
# disk (file size limit), a directory as input (tests/robust/tool_faults.sh). vt-offset uses
# vt-offset-gen (tests/offset.cmake) for its 60 MB input.
foreach(tool vt-tiles vt-convert vt-merge vt-offset)
  if(TARGET ${tool})
    add_test(NAME faults_${tool}
             COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/robust/tool_faults.sh
                     ${CMAKE_CURRENT_BINARY_DIR}/faults/${tool} ${tool}
                     $<TARGET_FILE_DIR:vt-tiles> $<TARGET_FILE:vt-synth> $<TARGET_FILE:vt-synth-image>)
    set_tests_properties(faults_${tool} PROPERTIES LABELS long TIMEOUT 600)
  endif()
endforeach()
# vt-tiles --layout on the sample scene (vt-atlas first).
if(TARGET vt-sample-scene AND TARGET vt-atlas)
  add_test(NAME faults_vt-tiles-layout
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/robust/tool_faults.sh
                   ${CMAKE_CURRENT_BINARY_DIR}/faults/vt-tiles-layout vt-tiles-layout
                   $<TARGET_FILE_DIR:vt-tiles> $<TARGET_FILE:vt-synth> $<TARGET_FILE:vt-synth-image>
                   $<TARGET_FILE:vt-sample-scene>)
  set_tests_properties(faults_vt-tiles-layout PROPERTIES LABELS long TIMEOUT 600)
endif()
