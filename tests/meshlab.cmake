# The optional MeshLab mesh-preparation stage (scripts/mesh-clean, docs/mesh-clean.md).
# vt-obj2ply (scripts/mesh/) is the OBJ <-> PLY side; it is built next to the tools so that
# VT_BIN=<build>/tools finds it like vt-atlas. meshlab_clean skips (77) without meshlabserver.
# (vt-obj2ply is defined in tools/CMakeLists.txt.)

add_executable(test_meshlab_scene meshlab/meshlab_scene.c)
target_include_directories(test_meshlab_scene PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
target_link_libraries(test_meshlab_scene PRIVATE vtlib m)
vt_target_warnings(test_meshlab_scene)

foreach(mode absent meshlab)
  add_test(NAME meshlab_clean_${mode}
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/meshlab/run.sh ${mode} ${PROJECT_SOURCE_DIR}
                   $<TARGET_FILE_DIR:vt-obj2ply> $<TARGET_FILE:test_meshlab_scene>
                   ${CMAKE_CURRENT_BINARY_DIR}/meshlab_${mode})
  set_tests_properties(meshlab_clean_${mode} PROPERTIES LABELS quick TIMEOUT 120
                       SKIP_RETURN_CODE 77)
endforeach()
