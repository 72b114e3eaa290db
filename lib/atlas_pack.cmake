# Tile-aware rectangle packing for vt-atlas (pure computation): sub-tile cells and the driver
# (vt_atlas_pack.c), whole-tile skyline packing (vt_atlas_skyline.c).
target_sources(vtlib PRIVATE ${CMAKE_CURRENT_LIST_DIR}/vt_atlas_pack.c
                             ${CMAKE_CURRENT_LIST_DIR}/vt_atlas_skyline.c)
