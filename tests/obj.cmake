# Unit tests of lib/vt_obj.c: the streaming OBJ/MTL reader.
vt_add_unit_test(test_vt_obj unit/test_vt_obj.c LIBS vtlib)
