# vt-tiles --layout atlas.json (tools/vt_tiles_layout.c, called from vt-tiles.c): the atlas build
# and --export-atlas (TIFF through libtiff, PNG through formats/vt_png_file).
find_package(TIFF REQUIRED)
target_sources(vt-tiles PRIVATE ${CMAKE_CURRENT_LIST_DIR}/vt_tiles_layout.c)
target_link_libraries(vt-tiles PRIVATE TIFF::TIFF)
