# Atlas compositing for vt-tiles --layout: per-texture mip chains (vt_mip_chain) and the tile
# compositor with its chain cache (vt_atlas_build). libc + lib/ only; textures are opened through
# a callback the tool gives.
target_sources(vtlib PRIVATE ${CMAKE_CURRENT_LIST_DIR}/vt_mip_chain.c
                             ${CMAKE_CURRENT_LIST_DIR}/vt_atlas_build.c)
