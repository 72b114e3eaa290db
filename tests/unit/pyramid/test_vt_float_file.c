/* lib/pyramid's temporary pass images (vt_float_file): rectangles written in any split (whole
 * stored tiles, pieces of tiles, rectangles across tiles, edge tiles narrower than the rest, tiles
 * taller than one vectored call) read back as the texels written, for every region read; texels
 * never written read as zeros. The comparison is shown to catch a single wrong float. */
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_float_file.h"
#include "vt_error.h"
#include "vt_image.h"
#include "vt_source.h"
#include "vt_test.h"

#define CH 3

static float ref(uint32_t x, uint32_t y, uint32_t c)
{
    return (float)(x * 1000 + y) + (float)c * 0.25f;
}

/* The texels of a w x h image in a buffer whose rows are `pad` texels wider than the image. */
static float *make_image(uint32_t w, uint32_t h, uint32_t pad)
{
    float *img = malloc((size_t)(w + pad) * h * CH * sizeof(float));
    for (uint32_t y = 0; img && y < h; y++)
        for (uint32_t x = 0; x < w + pad; x++)
            for (uint32_t c = 0; c < CH; c++)
                img[((size_t)y * (w + pad) + x) * CH + c] = x < w ? ref(x, y, c) : -1.0f;
    return img;
}

/* True when region (x0, y0) of dst holds the reference texels. */
static bool region_matches(const struct vt_image *dst, uint32_t x0, uint32_t y0)
{
    for (uint32_t y = 0; y < dst->height; y++) {
        const float *row = (const float *)vt_image_at(dst, 0, y);
        for (uint32_t x = 0; x < dst->width; x++)
            for (uint32_t c = 0; c < CH; c++)
                if (row[x * CH + c] != ref(x0 + x, y0 + y, c))
                    return false;
    }
    return true;
}

/* Writes a w x h image tiled by `tile` as the rectangles cut by xs x ys, then reads every region
 * with corners on the cuts (and the whole image) and compares. */
static void round_trip(uint32_t w, uint32_t h, uint32_t tile, const uint32_t *xs, size_t nx,
                       const uint32_t *ys, size_t ny)
{
    struct vts_error err = {0};
    const uint32_t pad = 5;
    float *img = make_image(w, h, pad);
    struct vt_float_file *f = vt_float_file_create(NULL, w, h, CH, tile, &err);
    VT_CHECK(img && f);
    if (!img || !f)
        goto out;
    for (size_t j = 0; j + 1 < ny; j++)
        for (size_t i = 0; i + 1 < nx; i++) {
            const float *first = img + ((size_t)ys[j] * (w + pad) + xs[i]) * CH;
            int rc = vt_float_file_write(f, xs[i], ys[j], xs[i + 1] - xs[i], ys[j + 1] - ys[j],
                                         first, (size_t)(w + pad) * CH, &err);
            VT_CHECK_INT_EQ(rc, 0);
        }
    struct vt_source src;
    VT_CHECK_INT_EQ(vt_float_file_source(f, VTS_COLOUR_LINEAR, false, &src, &err), 0);
    int bad = 0, reads = 0;
    for (size_t j0 = 0; j0 < ny; j0++)
        for (size_t j1 = j0 + 1; j1 < ny; j1++)
            for (size_t i0 = 0; i0 < nx; i0++)
                for (size_t i1 = i0 + 1; i1 < nx; i1++) {
                    struct vt_image dst;
                    uint32_t rw = xs[i1] - xs[i0], rh = ys[j1] - ys[j0];
                    if (vt_image_alloc(&dst, rw + 2, rh, CH, VTS_SAMPLE_F32, &err) != 0)
                        continue;
                    dst.width = rw; /* rows wider than the region: the stride is respected */
                    int rc = vt_source_read(&src, xs[i0], ys[j0], &dst, &err);
                    bad += rc != 0 || !region_matches(&dst, xs[i0], ys[j0]);
                    reads++;
                    vt_image_release(&dst);
                }
    VT_CHECK(reads > 0);
    VT_CHECK_INT_EQ(bad, 0);
    vt_source_close(&src);
out:
    vt_float_file_destroy(f);
    free(img);
}

static void float_file_round_trips_rectangles_of_any_split(void)
{
    /* 37 x 29 in tiles of 8: edge tiles 5 wide and 5 tall; cuts on and off the tile grid */
    const uint32_t xs[] = {0, 8, 13, 16, 29, 32, 37}, ys[] = {0, 5, 8, 24, 29};
    round_trip(37, 29, 8, xs, 7, ys, 5);
    /* whole tiles only: the blocks of a pass writing the next pass's level */
    const uint32_t tx[] = {0, 8, 16, 24, 32, 37}, ty[] = {0, 8, 16, 24, 29};
    round_trip(37, 29, 8, tx, 6, ty, 5);
    /* tiles of 100 rows: more rows than one vectored call moves */
    const uint32_t bx[] = {0, 100, 170, 200, 230}, by[] = {0, 1, 100, 150};
    round_trip(230, 150, 100, bx, 5, by, 4);
}

static void float_file_reads_unwritten_texels_as_zeros(void)
{
    struct vts_error err = {0};
    float *img = make_image(20, 20, 0);
    struct vt_float_file *f = vt_float_file_create(NULL, 20, 20, CH, 8, &err);
    VT_CHECK(img && f);
    if (!img || !f)
        goto out;
    VT_CHECK_INT_EQ(vt_float_file_write(f, 0, 0, 8, 8, img, 20 * CH, &err), 0);
    struct vt_source src;
    vt_float_file_source(f, VTS_COLOUR_LINEAR, false, &src, &err);
    struct vt_image dst;
    VT_CHECK_INT_EQ(vt_image_alloc(&dst, 20, 4, CH, VTS_SAMPLE_F32, &err), 0);
    memset(dst.pixels, 0x7f, dst.stride * dst.height);
    VT_CHECK_INT_EQ(vt_source_read(&src, 0, 16, &dst, &err), 0); /* past the end of the file */
    bool zeros = true;
    for (size_t i = 0; i < (size_t)20 * 4 * CH; i++)
        zeros = zeros && ((const float *)dst.pixels)[i] == 0.0f;
    VT_CHECK(zeros);
    /* the written tile reads back; one wrong float in it fails the comparison */
    struct vt_image t;
    VT_CHECK_INT_EQ(vt_image_alloc(&t, 8, 8, CH, VTS_SAMPLE_F32, &err), 0);
    VT_CHECK_INT_EQ(vt_source_read(&src, 0, 0, &t, &err), 0);
    VT_CHECK(region_matches(&t, 0, 0));
    ((float *)t.pixels)[5 * 8 * CH + 3 * CH + 1] += 1.0f / 1024;
    VT_CHECK(!region_matches(&t, 0, 0));
    vt_image_release(&t);
    vt_image_release(&dst);
    vt_source_close(&src);
out:
    vt_float_file_destroy(f);
    free(img);
}

int main(void)
{
    VT_RUN(float_file_round_trips_rectangles_of_any_split);
    VT_RUN(float_file_reads_unwritten_texels_as_zeros);
    return vt_test_main_result();
}
