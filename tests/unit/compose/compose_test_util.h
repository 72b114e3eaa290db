/* Shared by the compose tests: generated textures, and NTEX of them held in memory and opened by
 * name through the atlas build's open callback (a path's file name starts with the texture's
 * digit), the rows each one had decoded counted in rows_read[]. Define NTEX before including. */
#ifndef COMPOSE_TEST_UTIL_H
#define COMPOSE_TEST_UTIL_H

#include <stdint.h>
#include <string.h>

#include "vt_error.h"
#include "vt_image.h"
#include "vt_source.h"

#ifndef NTEX
#error "define NTEX (how many textures are held in memory) before including compose_test_util.h"
#endif

/* A w x h texture of ch 8-bit channels: gradients plus xorshift noise (seeded, below noise_mask +
 * 1), alpha a horizontal ramp when ch is 4. */
static inline void fill_texture(struct vt_image *img, uint32_t w, uint32_t h, uint32_t ch,
                                uint32_t seed, uint32_t noise_mask)
{
    vt_image_alloc(img, w, h, ch, VTS_SAMPLE_U8, NULL);
    uint32_t s = seed * 2654435761u + 1;
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            uint8_t *p = vt_image_at(img, x, y);
            for (uint32_t c = 0; c < ch; c++) {
                s ^= s << 13, s ^= s >> 17, s ^= s << 5;
                p[c] = (uint8_t)((x * 7 + y * 3 + c * 50) + (s & noise_mask));
            }
            if (ch == 4)
                p[3] = (uint8_t)(x * 255 / w);
        }
}

static struct vt_image textures[NTEX];
static uint64_t rows_read[NTEX];

static int mem_read(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst, struct vts_error *err)
{
    int i = (int)(intptr_t)ctx;
    (void)err;
    __atomic_fetch_add(&rows_read[i], dst->height, __ATOMIC_RELAXED);
    for (uint32_t j = 0; j < dst->height; j++)
        memcpy(vt_image_at(dst, 0, j), vt_image_at(&textures[i], x, y + j),
               (size_t)dst->width * textures[i].channels);
    return 0;
}

static void mem_close(void *ctx)
{
    (void)ctx;
}

static const struct vt_source_ops mem_ops = {mem_read, mem_close};

/* The atlas build's open callback: textures[digit of the path's file name]. */
static int open_mem(void *user, const char *path, struct vt_source *out, struct vts_error *err)
{
    const char *b = strrchr(path, '/');
    int i = (b ? b[1] : path[0]) - '0';
    (void)user;
    if (i < 0 || i >= NTEX)
        return vt_error_set(err, VTS_ERR_IO, "no texture '%s'", path);
    struct vt_image *t = &textures[i];
    *out = (struct vt_source){{t->width, t->height, t->channels, VTS_SAMPLE_U8, VTS_COLOUR_SRGB,
                               t->channels == 4, false, true, 0, 0, "mem"},
                              &mem_ops,
                              (void *)(intptr_t)i,
                              "mem"};
    return 0;
}

#endif
