# Unit tests of the streaming OBJ/MTL reader (lib/vt_obj.c, vt_mtl.c, vt_text.c).
vt_add_unit_test(test_vt_obj unit/test_vt_obj.c LIBS vtlib)
