# vt-offset's texture coordinate rewriter (vt_offset.c) and its exact decimal parsing and printing
# (vt_uv_text.c).
target_sources(vtlib PRIVATE ${CMAKE_CURRENT_LIST_DIR}/vt_offset.c ${CMAKE_CURRENT_LIST_DIR}/vt_uv_text.c)
