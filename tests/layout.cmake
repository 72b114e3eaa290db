# Unit tests of the atlas layout model and its JSON form (lib/vt_layout.c, vt_layout_json.c).
vt_add_unit_test(test_vt_layout unit/test_vt_layout.c LIBS vtlib)
