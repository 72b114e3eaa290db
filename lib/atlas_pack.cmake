# Tile-aware rectangle packing for vt-atlas (pure computation).
target_sources(vtlib PRIVATE ${CMAKE_CURRENT_LIST_DIR}/vt_atlas_pack.c)
