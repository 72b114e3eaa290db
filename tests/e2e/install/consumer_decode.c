/* A consumer of libvts-decode, built against the installed headers with pkg-config (vts-decode.pc)
 * as C and C++, and with find_package(vts) + vts::decode. Decodes level 0 of layer 0 whole (rows
 * padded: a stride longer than a row), checks that every tile's content equals its part of the
 * level, and prints the level's size and an FNV-1a hash of its texels (the install test compares
 * it with the installed Python package's). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <vts.h>
#include <vts_decode.h>

static uint64_t fnv1a(uint64_t h, const unsigned char *p, size_t n)
{
    for (size_t i = 0; i < n; i++)
        h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

/* 0 when tile (tx, ty)'s content equals the level image's texels at its place. */
static int check_tile(const struct vts_store *s, const struct vts_level *L, uint32_t tx,
                      uint32_t ty, const unsigned char *level, size_t stride, unsigned char *tile,
                      struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    size_t texel = vts_decode_texel_bytes(s, 0), tile_stride = g->tile_content_px * texel;
    uint32_t x0 = tx * g->tile_content_px, y0 = ty * g->tile_content_px;
    uint32_t cols = L->width - x0 < g->tile_content_px ? L->width - x0 : g->tile_content_px;
    uint32_t rows = L->height - y0 < g->tile_content_px ? L->height - y0 : g->tile_content_px;
    int rc = vts_decode_tile(s, 0, 0, tx, ty, VTS_DECODE_NO_BORDER, tile, tile_stride,
                             tile_stride * g->tile_content_px, err);
    for (uint32_t y = 0; rc == 0 && y < rows; y++)
        if (memcmp(tile + y * tile_stride, level + (y0 + y) * stride + x0 * texel, cols * texel))
            rc = 1;
    return rc;
}

int main(int argc, char **argv)
{
    if (argc != 2)
        return 2;
    if (vts_decode_version() != VTS_VERSION_NUMBER) {
        fprintf(stderr, "consumer_decode: libvts-decode %u, headers %d\n", vts_decode_version(),
                VTS_VERSION_NUMBER);
        return 1;
    }
    struct vts_error err;
    struct vts_store *s = vts_open(argv[1], &err);
    if (!s) {
        fprintf(stderr, "consumer_decode: %s\n", err.message);
        return 1;
    }
    const struct vts_geometry *g = vts_store_geometry(s);
    struct vts_level L;
    vts_store_level(s, 0, &L);
    size_t texel = vts_decode_texel_bytes(s, 0), row = L.width * texel, stride = row + 16;
    unsigned char *level = (unsigned char *)malloc(stride * L.height);
    unsigned char *tile =
        (unsigned char *)malloc((size_t)g->tile_content_px * g->tile_content_px * texel);
    int rc = vts_decode_region(s, 0, 0, 0, 0, L.width, L.height, 0, level, stride,
                               stride * L.height, &err);
    for (uint32_t ty = 0; ty < L.tiles_y && rc == 0; ty++)
        for (uint32_t tx = 0; tx < L.tiles_x && rc == 0; tx++)
            rc = check_tile(s, &L, tx, ty, level, stride, tile, &err);
    uint64_t h = 14695981039346656037ull;
    for (uint32_t y = 0; rc == 0 && y < L.height; y++)
        h = fnv1a(h, level + y * stride, row);
    if (rc == 0)
        printf("%ux%ux%zu fnv1a=%016llx\n", L.width, L.height, texel, (unsigned long long)h);
    else
        fprintf(stderr, "consumer_decode: %s\n",
                rc == 1 ? "a tile differs from the level" : err.message);
    free(tile);
    free(level);
    vts_close(s);
    return rc ? 1 : 0;
}
