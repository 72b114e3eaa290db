/* Builds a large real-content test image for benchmarks: a mosaic of 256x256 crops, at native
 * resolution, of real photographs (randomly chosen, positioned and flipped, seeded), written as a
 * tiled (256x256, deflate; -u: uncompressed) RGB TIFF. Benchmark tool, not part of vtpipe.
 * usage: make_mosaic [-u] OUT.tif SIZE PHOTO.png...   (photos: 8-bit PNG, at least 256x256) */
#include <png.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <tiffio.h>

#define CELL 256

struct photo {
    uint32_t w, h;
    unsigned char *rgb;
};

static int load(const char *path, struct photo *p)
{
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&im, path))
        return -1;
    im.format = PNG_FORMAT_RGB;
    p->w = im.width;
    p->h = im.height;
    p->rgb = malloc(PNG_IMAGE_SIZE(im));
    if (!p->rgb || !png_image_finish_read(&im, NULL, p->rgb, 0, NULL))
        return -1;
    return p->w >= CELL && p->h >= CELL ? 0 : -1;
}

static uint32_t hash(uint32_t v)
{
    v ^= v >> 16;
    v *= 0x7feb352dU;
    v ^= v >> 15;
    v *= 0x846ca68bU;
    return v ^ (v >> 16);
}

int main(int argc, char **argv)
{
    int raw = argc > 1 && strcmp(argv[1], "-u") == 0;
    argc -= raw;
    argv += raw;
    if (argc < 4)
        return 2;
    uint32_t size = (uint32_t)strtoul(argv[2], NULL, 10);
    int n = argc - 3;
    struct photo *ph = calloc((size_t)n, sizeof *ph);
    for (int i = 0; i < n; i++)
        if (load(argv[3 + i], &ph[i])) {
            fprintf(stderr, "make_mosaic: cannot use '%s'\n", argv[3 + i]);
            return 1;
        }
    TIFF *t = TIFFOpen(argv[1], size * (uint64_t)size * 3 > 0xF0000000u ? "w8" : "w");
    if (!t)
        return 1;
    TIFFSetField(t, TIFFTAG_IMAGEWIDTH, size);
    TIFFSetField(t, TIFFTAG_IMAGELENGTH, size);
    TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, 3);
    TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, 8);
    TIFFSetField(t, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_RGB);
    TIFFSetField(t, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    TIFFSetField(t, TIFFTAG_COMPRESSION, raw ? COMPRESSION_NONE : COMPRESSION_ADOBE_DEFLATE);
    if (!raw)
        TIFFSetField(t, TIFFTAG_ZIPQUALITY, 1);
    TIFFSetField(t, TIFFTAG_TILEWIDTH, CELL);
    TIFFSetField(t, TIFFTAG_TILELENGTH, CELL);
    unsigned char *tile = malloc(CELL * CELL * 3);
    for (uint32_t ty = 0; ty < size; ty += CELL)
        for (uint32_t tx = 0; tx < size; tx += CELL) {
            uint32_t h = hash(tx * 7919u + ty * 104729u + 17u);
            const struct photo *p = &ph[h % (uint32_t)n];
            uint32_t ox = hash(h) % (p->w - CELL + 1),
                     oy = hash(h ^ 0x5bd1e995u) % (p->h - CELL + 1);
            int flip_x = h >> 30 & 1, flip_y = h >> 31 & 1;
            for (uint32_t y = 0; y < CELL; y++)
                for (uint32_t x = 0; x < CELL; x++) {
                    uint32_t sx = ox + (flip_x ? CELL - 1 - x : x);
                    uint32_t sy = oy + (flip_y ? CELL - 1 - y : y);
                    memcpy(tile + (y * CELL + x) * 3, p->rgb + ((size_t)sy * p->w + sx) * 3, 3);
                }
            if (TIFFWriteTile(t, tile, tx, ty, 0, 0) < 0)
                return 1;
        }
    TIFFClose(t);
    return 0;
}
