# Unit tests of formats/: the codec registry and codecs, and PNG file input/output.
vt_add_unit_test(test_vt_codec unit/test_vt_codec.c LIBS vtformats)
vt_add_unit_test(test_vt_png_file unit/test_vt_png_file.c LIBS vtformats)
