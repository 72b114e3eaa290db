# Kept fuzz findings and hostile inputs (tests/data/fuzz/<target>/) replayed through the normal
# build: each must fail with a status and a message (docs/robustness.md). The fuzz targets' checks
# are compiled in without their libFuzzer entry points.
vt_add_unit_test(test_fuzz_regressions robust/test_fuzz_regressions.c fuzz/fuzz_codec_decode.c
                 fuzz/fuzz_image_input.c LIBS vtformats)
target_compile_definitions(test_fuzz_regressions
                           PRIVATE VT_FUZZ_NO_ENTRY VT_FUZZ_DATA_DIR="${CMAKE_CURRENT_SOURCE_DIR}/data/fuzz")
