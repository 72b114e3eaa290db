# vt-offset: texture coordinates of an OBJ scene onto an atlas (docs/cli/vt-offset.md).
add_executable(vt-offset ${CMAKE_CURRENT_LIST_DIR}/vt-offset.c)
target_link_libraries(vt-offset PRIVATE tool_common vtformats vtlib)
vt_target_warnings(vt-offset)
install(TARGETS vt-offset RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
