# Unit tests of lib/vt_filter.c: kernels, colour conversions and reductions.
# (vt_filter.c calls libm; m is listed until vtlib links it itself.)
vt_add_unit_test(test_vt_filter unit/test_vt_filter.c LIBS vtlib m)
