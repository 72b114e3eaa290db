# atlas.json: the layout model (vt_layout.c) and its JSON form (vt_layout_json.c, jansson).
target_sources(vtlib PRIVATE ${CMAKE_CURRENT_LIST_DIR}/vt_layout.c ${CMAKE_CURRENT_LIST_DIR}/vt_layout_json.c)
target_link_libraries(vtlib PUBLIC PkgConfig::JANSSON)
