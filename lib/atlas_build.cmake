# Atlas compositing for vt-tiles --layout: per-texture mip chains (vt_mip_chain) and the tile
# compositor (vt_atlas_build: the driver; vt_atlas_tile: per-tile compositing; vt_atlas_cache: the
# shared chain cache). libc + lib/ only; textures are opened through a callback the tool gives.
target_sources(vtlib PRIVATE ${CMAKE_CURRENT_LIST_DIR}/vt_mip_chain.c
                             ${CMAKE_CURRENT_LIST_DIR}/vt_atlas_cache.c
                             ${CMAKE_CURRENT_LIST_DIR}/vt_atlas_tile.c
                             ${CMAKE_CURRENT_LIST_DIR}/vt_atlas_build.c)
