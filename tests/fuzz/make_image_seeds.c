/* Writes the seed corpus of fuzz_image_input into a directory: small files of every native input
 * format (tests/synth/vt_synth_images.h): TIFF tiled, striped, BigTIFF, planar, palette, 1-bit,
 * 16-bit, half and float; PNG grey to RGBA, 1..16 bits, palette, Adam7; JPEG grey/RGB, 4:2:0,
 * progressive; OpenEXR scanline/tiled, half/float, every compression.
 * Usage: make_image_seeds DIR (created if missing) */
#include <errno.h>
#include <stdio.h>
#include <sys/stat.h>

#include "vt_synth_images.h"
#include "vts.h"

struct seed {
    const char *name;
    struct vt_synth_image_options o; /* zero fields: vt_synth_image_defaults() */
};

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: make_image_seeds DIR\n");
        return 2;
    }
    if (mkdir(argv[1], 0777) != 0 && errno != EEXIST) {
        perror(argv[1]);
        return 1;
    }
    enum { T = VT_SYNTH_TIFF, P = VT_SYNTH_PNG, J = VT_SYNTH_JPEG, E = VT_SYNTH_EXR };
    static const struct seed seeds[] = {
        {"tiff-striped-rgba8.tif", {.format = T, .channels = 4, .sample = VTS_SAMPLE_U8}},
        {"tiff-tiled-rgb16.tif",
         {.format = T, .channels = 3, .sample = VTS_SAMPLE_U16, .tile_w = 16, .tile_h = 16}},
        {"tiff-tiled-lzw-grey.tif",
         {.format = T,
          .channels = 1,
          .sample = VTS_SAMPLE_U8,
          .tile_w = 32,
          .tile_h = 16,
          .compression = VT_SYNTH_TIFF_LZW}},
        {"tiff-big-packbits-ga.tif",
         {.format = T,
          .channels = 2,
          .sample = VTS_SAMPLE_U8,
          .bigtiff = true,
          .compression = VT_SYNTH_TIFF_PACKBITS}},
        {"tiff-planar-rgb.tif",
         {.format = T, .channels = 3, .sample = VTS_SAMPLE_U8, .separate_planes = true}},
        {"tiff-palette.tif",
         {.format = T, .channels = 3, .sample = VTS_SAMPLE_U8, .palette = true}},
        {"tiff-1bit-white.tif",
         {.format = T, .channels = 1, .sample = VTS_SAMPLE_U8, .bits = 1, .min_is_white = true}},
        {"tiff-half.tif", {.format = T, .channels = 4, .sample = VTS_SAMPLE_F16}},
        {"tiff-float-raw.tif",
         {.format = T, .channels = 1, .sample = VTS_SAMPLE_F32, .compression = VT_SYNTH_TIFF_NONE}},
        {"png-rgba8.png", {.format = P, .channels = 4, .sample = VTS_SAMPLE_U8}},
        {"png-grey16.png", {.format = P, .channels = 1, .sample = VTS_SAMPLE_U16}},
        {"png-ga8-adam7.png",
         {.format = P, .channels = 2, .sample = VTS_SAMPLE_U8, .interlaced = true}},
        {"png-palette-trns.png",
         {.format = P, .channels = 4, .sample = VTS_SAMPLE_U8, .palette = true}},
        {"png-grey2.png", {.format = P, .channels = 1, .sample = VTS_SAMPLE_U8, .bits = 2}},
        {"png-rgb16.png", {.format = P, .channels = 3, .sample = VTS_SAMPLE_U16}},
        {"jpeg-rgb444.jpg", {.format = J, .channels = 3, .sample = VTS_SAMPLE_U8}},
        {"jpeg-rgb420-progressive.jpg",
         {.format = J,
          .channels = 3,
          .sample = VTS_SAMPLE_U8,
          .jpeg_420 = true,
          .progressive = true}},
        {"jpeg-grey.jpg", {.format = J, .channels = 1, .sample = VTS_SAMPLE_U8}},
        {"exr-half-zip.exr", {.format = E, .channels = 4, .sample = VTS_SAMPLE_F16}},
        {"exr-float-tiled-piz.exr",
         {.format = E,
          .channels = 3,
          .sample = VTS_SAMPLE_F32,
          .tile_w = 16,
          .tile_h = 16,
          .compression = VT_SYNTH_EXR_PIZ}},
        {"exr-half-rle-y.exr",
         {.format = E, .channels = 1, .sample = VTS_SAMPLE_F16, .compression = VT_SYNTH_EXR_RLE}},
        {"exr-half-ya-origin.exr",
         {.format = E,
          .channels = 2,
          .sample = VTS_SAMPLE_F16,
          .exr_origin_x = -3,
          .exr_origin_y = 5}},
        {"exr-float-zips.exr",
         {.format = E, .channels = 4, .sample = VTS_SAMPLE_F32, .compression = VT_SYNTH_EXR_ZIPS}},
    };
    for (size_t i = 0; i < sizeof seeds / sizeof seeds[0]; i++) {
        struct vt_synth_image_options o;
        vt_synth_image_defaults(&o);
        const struct vt_synth_image_options *s = &seeds[i].o;
        o.format = s->format;
        o.width = 37 + (uint32_t)i;
        o.height = 23 + (uint32_t)(i % 5);
        o.channels = s->channels;
        o.sample = s->sample;
        o.seed = (uint32_t)i + 1;
        o.tile_w = s->tile_w;
        o.tile_h = s->tile_h;
        o.bits = s->bits;
        o.palette = s->palette;
        o.bigtiff = s->bigtiff;
        o.separate_planes = s->separate_planes;
        o.min_is_white = s->min_is_white;
        o.interlaced = s->interlaced;
        if (s->compression || s->format == T || s->format == E)
            o.compression = s->compression
                                ? s->compression
                                : (s->format == T ? VT_SYNTH_TIFF_DEFLATE : VT_SYNTH_EXR_ZIP);
        o.exr_origin_x = s->exr_origin_x;
        o.exr_origin_y = s->exr_origin_y;
        o.jpeg_420 = s->jpeg_420;
        o.progressive = s->progressive;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", argv[1], seeds[i].name);
        struct vts_error err = {0};
        if (vt_synth_image_write(path, &o, &err) != 0) {
            fprintf(stderr, "make_image_seeds: %s: %s\n", seeds[i].name, err.message);
            return 1;
        }
    }
    return 0;
}
