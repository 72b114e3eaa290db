vt_add_unit_test(test_vts_store unit/test_vts_store.c LIBS vts_static)
vt_add_unit_test(test_vts_geometry unit/test_vts_geometry.c LIBS vts_static)
