# vt-offset's texture coordinate rewriter (vt_offset.c: API and driver; vt_offset_src.c: raw lines;
# vt_offset_tok.c: tokens; vt_offset_run.c: shared state and output; vt_offset_scan.c: pass 1;
# vt_offset_write.c: pass 2) and its exact decimal parsing and printing (vt_uv_text.c).
target_sources(vtlib PRIVATE ${CMAKE_CURRENT_LIST_DIR}/vt_offset.c
               ${CMAKE_CURRENT_LIST_DIR}/vt_offset_run.c ${CMAKE_CURRENT_LIST_DIR}/vt_offset_scan.c
               ${CMAKE_CURRENT_LIST_DIR}/vt_offset_src.c ${CMAKE_CURRENT_LIST_DIR}/vt_offset_tok.c
               ${CMAKE_CURRENT_LIST_DIR}/vt_offset_write.c ${CMAKE_CURRENT_LIST_DIR}/vt_uv_text.c)
