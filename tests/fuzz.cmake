# libFuzzer targets, built only with -DVT_BUILD_FUZZERS=ON and clang (scripts/fuzz drives them).
# The sanitizer and fuzzer flags apply to the fuzz targets alone: each compiles the library
# sources it exercises directly, so that they are instrumented for coverage too.
if(NOT VT_BUILD_FUZZERS)
  return()
endif()
if(NOT CMAKE_C_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "VT_BUILD_FUZZERS=ON needs clang (configure with CC=clang)")
endif()

set(VT_FUZZ_FLAGS -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all
    -fno-omit-frame-pointer -g)
set(VT_FUZZ_LIST ${CMAKE_BINARY_DIR}/fuzz/targets.txt)
file(WRITE ${VT_FUZZ_LIST} "")
add_custom_target(fuzz_seeds)

# vt_add_fuzzer(name SOURCES src... [SEED_COMMAND cmd... (run with the seed dir appended; creates it)]
#               [SEED_DIRS dir...] [LIBS lib...]): a libFuzzer executable; scripts/fuzz runs it with
# the corpus build-fuzz/fuzz/corpus/<name>, seeded from build-fuzz/fuzz/seeds/<name> (made by
# SEED_COMMAND at `ninja fuzz_seeds`) and SEED_DIRS. A CTest test (label fuzz) runs every seed once.
function(vt_add_fuzzer name)
  cmake_parse_arguments(F "" "" "SOURCES;SEED_COMMAND;SEED_DIRS;LIBS" ${ARGN})
  add_executable(${name} ${F_SOURCES})
  target_include_directories(${name} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR} ${PROJECT_SOURCE_DIR}/lib)
  target_compile_options(${name} PRIVATE ${VT_FUZZ_FLAGS})
  target_link_options(${name} PRIVATE -fsanitize=fuzzer,address,undefined)
  target_link_libraries(${name} PRIVATE ${F_LIBS})
  vt_target_warnings(${name})
  set(seeds ${CMAKE_BINARY_DIR}/fuzz/seeds/${name})
  file(MAKE_DIRECTORY ${seeds})
  if(F_SEED_COMMAND)
    add_custom_target(${name}_make_seeds COMMAND ${F_SEED_COMMAND} ${seeds} VERBATIM)
    add_dependencies(fuzz_seeds ${name}_make_seeds)
  endif()
  file(APPEND ${VT_FUZZ_LIST} "${name} ${seeds} ${F_SEED_DIRS}\n")
  # Regression: every seed and every kept finding once, no fuzzing (-runs=0 runs the corpus).
  if(F_SEED_COMMAND)
    add_test(NAME ${name}_make_seeds COMMAND ${F_SEED_COMMAND} ${seeds})
    set_tests_properties(${name}_make_seeds PROPERTIES LABELS fuzz FIXTURES_SETUP ${name}_seeds)
  endif()
  add_test(NAME ${name}_seeds COMMAND ${name} -runs=0 ${seeds} ${F_SEED_DIRS})
  set_tests_properties(${name}_seeds PROPERTIES LABELS fuzz TIMEOUT 300 FIXTURES_REQUIRED
                                                ${name}_seeds)
endfunction()

vt_add_fuzzer(fuzz_vts_reader
  SOURCES fuzz/fuzz_vts_reader.c robust/vts_reseal.c
          ${PROJECT_SOURCE_DIR}/lib/vts.c ${PROJECT_SOURCE_DIR}/lib/vts_geometry.c
          ${PROJECT_SOURCE_DIR}/lib/vts_crc32c.c ${PROJECT_SOURCE_DIR}/lib/vt_error.c
  LIBS Threads::Threads
  SEED_COMMAND $<TARGET_FILE:make_vts_seeds>
  SEED_DIRS ${CMAKE_CURRENT_SOURCE_DIR}/data/bad)

add_executable(make_vts_seeds fuzz/make_vts_seeds.c)
target_link_libraries(make_vts_seeds PRIVATE vts_fixture)
vt_target_warnings(make_vts_seeds)

# Tile payload decoders (formats/vt_codec_*.c): instrumented here; the squish shim (C++) and the
# libraries come from vtformats.
set(VT_FUZZ_CODEC_SOURCES
    ${PROJECT_SOURCE_DIR}/formats/vt_codec.c ${PROJECT_SOURCE_DIR}/formats/vt_codec_raw.c
    ${PROJECT_SOURCE_DIR}/formats/vt_codec_png.c ${PROJECT_SOURCE_DIR}/formats/vt_codec_jpeg.c
    ${PROJECT_SOURCE_DIR}/formats/vt_codec_bc.c)
vt_add_fuzzer(fuzz_codec_decode
  SOURCES fuzz/fuzz_codec_decode.c ${VT_FUZZ_CODEC_SOURCES}
  LIBS vtformats Threads::Threads
  SEED_COMMAND $<TARGET_FILE:make_codec_seeds>
  SEED_DIRS ${CMAKE_CURRENT_SOURCE_DIR}/data/fuzz/fuzz_codec_decode)

add_executable(make_codec_seeds fuzz/make_codec_seeds.c fuzz/fuzz_codec_decode.c)
target_compile_definitions(make_codec_seeds PRIVATE VT_FUZZ_NO_ENTRY)
target_include_directories(make_codec_seeds PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
target_link_libraries(make_codec_seeds PRIVATE vtformats)
vt_target_warnings(make_codec_seeds)

# Image input (formats/vt_image_input.c and the native readers); the OpenImageIO fallback is
# compiled without VT_HAVE_OIIO here, and the target skips non-native inputs anyway.
vt_add_fuzzer(fuzz_image_input
  SOURCES fuzz/fuzz_image_input.c ${PROJECT_SOURCE_DIR}/formats/vt_image_input.c
          ${PROJECT_SOURCE_DIR}/formats/vt_input_tiff.c ${PROJECT_SOURCE_DIR}/formats/vt_input_png.c
          ${PROJECT_SOURCE_DIR}/formats/vt_input_jpeg.c ${PROJECT_SOURCE_DIR}/formats/vt_input_exr.c
          ${PROJECT_SOURCE_DIR}/formats/vt_input_oiio.c
  LIBS vtformats VT::OpenEXRCore Threads::Threads
  SEED_COMMAND $<TARGET_FILE:make_image_seeds>
  SEED_DIRS ${CMAKE_CURRENT_SOURCE_DIR}/data/fuzz/fuzz_image_input)

add_executable(make_image_seeds fuzz/make_image_seeds.c)
target_link_libraries(make_image_seeds PRIVATE vt_synth_images)
vt_target_warnings(make_image_seeds)

# OBJ/MTL reader (lib/vt_obj.c, vt_mtl.c, vt_text.c), parsed from memory as an OBJ and as an MTL file.
vt_add_fuzzer(fuzz_obj
  SOURCES fuzz/fuzz_obj.c ${PROJECT_SOURCE_DIR}/lib/vt_obj.c ${PROJECT_SOURCE_DIR}/lib/vt_text.c
          ${PROJECT_SOURCE_DIR}/lib/vt_mtl.c ${PROJECT_SOURCE_DIR}/lib/vt_error.c
  SEED_DIRS ${CMAKE_CURRENT_SOURCE_DIR}/data/fuzz/fuzz_obj)

# atlas.json reader (lib/vt_layout.c, vt_layout_json.c), seeded with small layouts.
vt_add_fuzzer(fuzz_layout
  SOURCES fuzz/fuzz_layout.c ${PROJECT_SOURCE_DIR}/lib/vt_layout.c
          ${PROJECT_SOURCE_DIR}/lib/vt_layout_json.c ${PROJECT_SOURCE_DIR}/lib/vt_obj.c
          ${PROJECT_SOURCE_DIR}/lib/vt_text.c ${PROJECT_SOURCE_DIR}/lib/vt_mtl.c
          ${PROJECT_SOURCE_DIR}/lib/vt_error.c ${PROJECT_SOURCE_DIR}/lib/vt_atomic_file.c
  LIBS PkgConfig::JANSSON Threads::Threads m
  SEED_DIRS ${CMAKE_CURRENT_SOURCE_DIR}/data/fuzz/fuzz_layout)
