# Image input (formats/vt_image_input.h): seeded image-file generators and the reader tests.
# Imported targets are directory-scoped: find them here too (formats/ did the same;
# VT::OpenEXRCore is global).
find_package(TIFF REQUIRED)
find_package(JPEG REQUIRED)
add_library(vt_synth_images STATIC synth/vt_synth_images.c)
target_include_directories(vt_synth_images PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/synth)
target_link_libraries(vt_synth_images PUBLIC vtlib PRIVATE TIFF::TIFF PNG::PNG JPEG::JPEG
                      VT::OpenEXRCore)
vt_target_warnings(vt_synth_images)

vt_add_unit_test(test_vt_image_input unit/test_vt_image_input.c
                 LIBS vtformats vt_synth_images Threads::Threads)
if(TARGET vt_oiio)
  # The test dlopen()s the module through the reader; it must be built, never linked.
  add_dependencies(test_vt_image_input vt_oiio)
  target_compile_definitions(test_vt_image_input PRIVATE VT_TEST_HAVE_OIIO=1)
endif()

# Command-line wrapper of the generator, used by scripts/demo.
add_executable(vt-synth-image synth/vt_synth_image_main.c)
target_link_libraries(vt-synth-image PRIVATE vt_synth_images vt_synth)
vt_target_warnings(vt-synth-image)
