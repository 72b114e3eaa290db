/* The PNG tile encoder at each effort against the encoder it replaced (libpng -> zlib level 2, SUB
 * filter on every row), on the same tiles of real photographs, one thread, rounds interleaved.
 * Prints per encoder: MP/s, bytes per tile, compressed/raw, and speed and size against the
 * reference. Every payload of ours is decoded once and compared with its tile (exact codec).
 * usage: vt-bench-png [--channels C] [--tiles N] [--rounds R] IMAGE...
 *   C: 3 (RGB, default) or 1 (the first channel); N tiles of 264 x 264 (default 200), cut from the
 *   images row by row; R rounds (default 2; the best round counts). */
#define _POSIX_C_SOURCE 200809L
#include <getopt.h>
#include <png.h>
#include <setjmp.h>
#include <string.h>
#include <time.h>

#include "bench_util.h"
#include "vt_codec.h"
#include "vt_image.h"
#include "vt_image_input.h"
#include "vt_source.h"
#include "vts.h"

#define TILE 264u

struct tiles {
    uint32_t count, channels;
    uint8_t **px; /* TILE x TILE x channels each */
};

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

/* Cuts tiles from one image (8-bit) until t holds max. */
static void cut_tiles(const char *path, struct tiles *t, uint32_t max)
{
    struct vt_source src;
    struct vts_error err = {0};
    struct vt_input_limits limits = {0};
    if (vt_image_input_open(path, &limits, &src, &err))
        die(path, &err);
    if (src.info.sample != VTS_SAMPLE_U8 || src.info.channels < 3) {
        vt_source_close(&src);
        return;
    }
    struct vt_image band = {0};
    if (vt_image_alloc(&band, src.info.width, TILE, src.info.channels, VTS_SAMPLE_U8, &err))
        die(path, &err);
    for (uint32_t y = 0; y + TILE <= src.info.height && t->count < max; y += TILE) {
        if (vt_source_read(&src, 0, y, &band, &err))
            die(path, &err);
        for (uint32_t x = 0; x + TILE <= src.info.width && t->count < max; x += TILE) {
            uint8_t *p = xmalloc((size_t)TILE * TILE * t->channels);
            for (uint32_t j = 0; j < TILE; j++)
                for (uint32_t i = 0; i < TILE; i++)
                    memcpy(p + ((size_t)j * TILE + i) * t->channels,
                           (uint8_t *)vt_image_at(&band, x + i, j), t->channels);
            t->px[t->count++] = p;
        }
    }
    vt_image_release(&band);
    vt_source_close(&src);
}

/* ---- the reference: libpng -> zlib level 2, SUB filter ---- */

struct mem {
    uint8_t *p;
    size_t n, cap;
};

static void mem_write(png_structp png, png_bytep data, size_t len)
{
    struct mem *m = png_get_io_ptr(png);
    if (len > m->cap - m->n)
        png_error(png, "buffer full");
    memcpy(m->p + m->n, data, len);
    m->n += len;
}

static void mem_flush(png_structp png)
{
    (void)png;
}

static size_t ref_body(png_structp png, png_infop info, const uint8_t *px, uint32_t channels,
                       struct mem *m)
{
    static const int types[] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA};
    png_set_write_fn(png, m, mem_write, mem_flush);
    png_set_compression_level(png, 2);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
    png_set_IHDR(png, info, TILE, TILE, 8, types[channels], PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
    png_write_info(png, info);
    for (uint32_t y = 0; y < TILE; y++)
        png_write_row(png, px + (size_t)y * TILE * channels);
    png_write_end(png, NULL);
    return m->n;
}

static size_t ref_run(png_structp png, png_infop info, const uint8_t *px, uint32_t channels,
                      struct mem *m)
{
    if (setjmp(png_jmpbuf(png)))
        return 0;
    return ref_body(png, info, px, channels, m);
}

static size_t ref_encode(const uint8_t *px, uint32_t channels, uint8_t *dst, size_t cap)
{
    struct mem m = {dst, 0, cap};
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    size_t n = info ? ref_run(png, info, px, channels, &m) : 0;
    png_destroy_write_struct(&png, &info);
    if (!n)
        die("reference encode", NULL);
    return n;
}

/* ---- ours ---- */

static size_t our_encode(const struct vt_codec *png, int effort, uint8_t *px, uint32_t channels,
                         uint8_t *dst, size_t cap)
{
    struct vt_image img = {TILE, TILE, channels, VTS_SAMPLE_U8, (size_t)TILE * channels, px};
    struct vt_codec_params params = {.effort = effort};
    struct vts_error err = {0};
    size_t n = 0;
    if (png->encode(&img, &params, dst, cap, &n, &err))
        die("encode", &err);
    return n;
}

static void check_round_trip(const struct vt_codec *png, const struct tiles *t, int effort,
                             uint8_t *buf, size_t cap)
{
    struct vt_image dst = {0};
    struct vts_error err = {0};
    if (vt_image_alloc(&dst, TILE, TILE, t->channels, VTS_SAMPLE_U8, &err))
        die("alloc", &err);
    for (uint32_t i = 0; i < t->count; i++) {
        size_t n = our_encode(png, effort, t->px[i], t->channels, buf, cap);
        if (png->decode(buf, n, &dst, &err))
            die("decode", &err);
        for (uint32_t y = 0; y < TILE; y++)
            if (memcmp(vt_image_at(&dst, 0, y), t->px[i] + (size_t)y * TILE * t->channels,
                       (size_t)TILE * t->channels) != 0)
                die("round trip differs", NULL);
    }
    vt_image_release(&dst);
}

int main(int argc, char **argv)
{
    bench_name = "vt-bench-png";
    uint32_t channels = 3, max = 200, rounds = 2;
    static const struct option opts[] = {{"channels", required_argument, NULL, 'c'},
                                         {"tiles", required_argument, NULL, 'n'},
                                         {"rounds", required_argument, NULL, 'r'},
                                         {NULL, 0, NULL, 0}};
    for (int c; (c = getopt_long(argc, argv, "", opts, NULL)) != -1;) {
        uint32_t v = (uint32_t)strtoul(optarg ? optarg : "0", NULL, 10);
        if (c == 'c' && (v == 1 || v == 3))
            channels = v;
        else if (c == 'n' && v > 0)
            max = v;
        else if (c == 'r' && v > 0)
            rounds = v;
        else
            return fprintf(stderr, "usage: vt-bench-png [--channels 1|3] [--tiles N] "
                                   "[--rounds R] IMAGE...\n"),
                   2;
    }
    struct tiles t = {0, channels, xmalloc(sizeof(uint8_t *) * max)};
    for (int a = optind; a < argc && t.count < max; a++)
        cut_tiles(argv[a], &t, max);
    if (t.count == 0)
        die("no 8-bit RGB(A) image given", NULL);
    const struct vt_codec *png = vt_codec_find("png");
    size_t cap = png->encoded_bound(TILE, TILE, channels, VTS_SAMPLE_U8) * 2;
    uint8_t *buf = xmalloc(cap);
    enum { NENC = 10 }; /* 0: the reference, 1..9: our efforts */
    double best[NENC];
    size_t bytes[NENC] = {0};
    for (int e = 0; e < NENC; e++)
        best[e] = 1e30;
    for (uint32_t r = 0; r < rounds; r++)
        for (int e = 0; e < NENC; e++) {
            size_t total = 0;
            double t0 = now_s();
            for (uint32_t i = 0; i < t.count; i++)
                total += e == 0 ? ref_encode(t.px[i], channels, buf, cap)
                                : our_encode(png, e, t.px[i], channels, buf, cap);
            double dt = now_s() - t0;
            best[e] = dt < best[e] ? dt : best[e];
            bytes[e] = total;
        }
    for (int e = 1; e < NENC; e++)
        check_round_trip(png, &t, e, buf, cap);
    double mp = (double)t.count * TILE * TILE / 1e6, raw = mp * 1e6 * channels;
    printf("%u tiles of %ux%u, %u channel(s), best of %u rounds, one thread\n", t.count, TILE, TILE,
           channels, rounds);
    printf("%-28s %8s %10s %8s %10s %9s\n", "encoder", "MP/s", "B/tile", "of raw", "speed/ref",
           "size/ref");
    for (int e = 0; e < NENC; e++) {
        char name[64];
        if (e == 0)
            snprintf(name, sizeof name, "reference libpng+zlib 2 SUB");
        else
            snprintf(name, sizeof name, "ours effort %d%s", e, e == 1 ? " (default)" : "");
        printf("%-28s %8.1f %10.0f %8.3f %10.2f %9.3f\n", name, mp / best[e],
               (double)bytes[e] / t.count, (double)bytes[e] / raw, best[0] / best[e],
               (double)bytes[e] / (double)bytes[0]);
    }
    for (uint32_t i = 0; i < t.count; i++)
        free(t.px[i]);
    free(t.px);
    free(buf);
    return 0;
}
