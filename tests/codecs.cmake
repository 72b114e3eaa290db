# Unit tests of the lossy tile codecs: jpeg (formats/vt_codec_jpeg.c), bc1 and bc3
# (formats/vt_codec_bc.c + vt_squish_shim.cpp).
vt_add_unit_test(test_vt_codec_jpeg unit/test_vt_codec_jpeg.c LIBS vtformats vt_synth Threads::Threads m)
vt_add_unit_test(test_vt_codec_bc unit/test_vt_codec_bc.c LIBS vtformats vt_synth Threads::Threads m)
