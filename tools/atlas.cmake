# vt-atlas: scene scanning (vt_atlas_scene), placement (vt_atlas_place) and the tool.
add_executable(vt-atlas vt-atlas.c vt_atlas_scene.c vt_atlas_place.c)
target_link_libraries(vt-atlas PRIVATE tool_common vtformats vtlib m)
vt_target_warnings(vt-atlas)
install(TARGETS vt-atlas RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
