/* Wang packs: patches from the sample, the tiles in pack order, the virtual output (vt_wang.h). */
#include "vt_wang.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_checked.h"

void vt_wang_grid(const struct vt_wang_params *p, uint32_t *cols, uint32_t *rows)
{
    if (p->corners) {
        *cols = p->kh * p->kh;
        *rows = vts_wang_corner_rows(p->kh);
    } else {
        *cols = p->kv * p->kv;
        *rows = p->kh * p->kh;
    }
}

static uint64_t next_random(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static int check_params(const struct vt_image *sample, const struct vt_wang_params *p,
                        uint32_t patch, struct vts_error *err)
{
    if (p->tile_px < 8 || p->tile_px % 2 || p->tile_px > 4096)
        return vt_error_set(err, VTS_ERR_ARG, "tile size %u: expected an even 8..4096", p->tile_px);
    if (p->kh < 1 || p->kh > VTS_WANG_MAX_COLOURS || p->kv < 1 || p->kv > VTS_WANG_MAX_COLOURS)
        return vt_error_set(err, VTS_ERR_ARG, "colours %ux%u: expected 1..%u each", p->kh, p->kv,
                            VTS_WANG_MAX_COLOURS);
    if (p->corners && p->kh != p->kv)
        return vt_error_set(err, VTS_ERR_ARG, "corner tiles have one colour count (KxK), not %ux%u",
                            p->kh, p->kv);
    if (sample->sample != VTS_SAMPLE_U8)
        return vt_error_set(err, VTS_ERR_ARG, "the sample must have 8-bit samples");
    if (sample->width < patch || sample->height < patch)
        return vt_error_set(err, VTS_ERR_ARG, "the sample (%ux%u) is smaller than a patch (%u)",
                            sample->width, sample->height, patch);
    return 0;
}

/* A patch: a view of the sample (no copy) at a random position. */
static void pick_patch(const struct vt_image *sample, uint32_t patch, uint64_t *state,
                       struct vt_image *out)
{
    uint32_t x = (uint32_t)(next_random(state) % (sample->width - patch + 1));
    uint32_t y = (uint32_t)(next_random(state) % (sample->height - patch + 1));
    *out = *sample;
    out->width = out->height = patch;
    out->pixels = vt_image_at(sample, x, y);
}

/* The tile of pack slot (col, row) in canonical order, into dst (a view of the pack). */
static void make_tile(const struct vt_wang_params *p, const struct vt_image *hp,
                      const struct vt_image *vp, uint32_t col, uint32_t row, struct vt_image *dst)
{
    const struct vt_image *patches[4];
    if (p->corners) {
        struct vts_wang_corners c;
        vts_wang_corner_colours(p->kh, col, row, &c);
        const struct vt_image *q[4] = {&hp[c.nw], &hp[c.ne], &hp[c.sw], &hp[c.se]};
        memcpy(patches, q, sizeof q);
        vt_wang_corner_tile(patches, dst);
    } else {
        struct vts_wang_edges e;
        vts_wang_tile_edges(col, row, &e);
        const struct vt_image *q[4] = {&hp[e.n], &vp[e.e], &hp[e.s], &vp[e.w]};
        memcpy(patches, q, sizeof q);
        vt_wang_edge_tile(patches, dst);
    }
}

int vt_wang_build(const struct vt_image *sample, const struct vt_wang_params *p,
                  struct vt_image *pack, uint32_t *order, struct vts_error *err)
{
    memset(pack, 0, sizeof *pack);
    uint32_t patch = p->tile_px + (p->corners ? 2 * vt_wang_corner_margin(p->tile_px) : 0);
    int rc = check_params(sample, p, patch, err);
    if (rc)
        return rc;
    uint32_t cols, rows, t = p->tile_px;
    vt_wang_grid(p, &cols, &rows);
    uint64_t w, h;
    if (!vt_u64_mul(cols, t, &w) || !vt_u64_mul(rows, t, &h) || w * h > VT_WANG_MAX_PACK_TEXELS)
        return vt_error_set(
            err, VTS_ERR_LIMIT,
            "a pack of %ux%u tiles of %u texels is too large (more than 2^30 texels)", cols, rows,
            t);
    rc = vt_image_alloc(pack, (uint32_t)w, (uint32_t)h, sample->channels, VTS_SAMPLE_U8, err);
    if (rc)
        return rc;
    struct vt_image hp[VTS_WANG_MAX_COLOURS], vp[VTS_WANG_MAX_COLOURS];
    uint64_t state = p->seed;
    for (uint32_t c = 0; c < p->kh; c++)
        pick_patch(sample, patch, &state, &hp[c]);
    for (uint32_t c = 0; c < p->kv; c++)
        pick_patch(sample, patch, &state, &vp[c]);
    uint32_t n = cols * rows;
    for (uint32_t i = 0; i < n && order; i++)
        order[i] = i;
    uint64_t shuffle = p->shuffle_seed;
    for (uint32_t i = n - 1; p->shuffle && order && i > 0; i--) {
        uint32_t j = (uint32_t)(next_random(&shuffle) % (i + 1)), tmp = order[i];
        order[i] = order[j];
        order[j] = tmp;
    }
    for (uint32_t slot = 0; slot < n; slot++) {
        uint32_t to = p->shuffle && order ? order[slot] : slot;
        struct vt_image view = *pack;
        view.width = view.height = t;
        view.pixels = vt_image_at(pack, to % cols * t, to / cols * t);
        make_tile(p, hp, vp, slot % cols, slot / cols, &view);
    }
    return 0;
}

void vt_wang_info_locate(const struct vt_wang_info *info, uint32_t x, uint32_t y, uint32_t *col,
                         uint32_t *row)
{
    struct vts_wang_hash h = {info->hash, info->hash_n, info->kh, info->kv};
    if (info->corners) {
        struct vts_wang_corners c;
        vts_wang_hash_corners(&h, x, y, &c);
        vts_wang_corner_position(info->kh, &c, col, row);
    } else {
        struct vts_wang_edges e;
        vts_wang_hash_edges(&h, x, y, &e);
        vts_wang_tile_position(&e, col, row);
    }
    if (info->order) {
        uint32_t slot = info->order[*row * info->cols + *col];
        *col = slot % info->cols;
        *row = slot / info->cols;
    }
}

void vt_wang_assemble(const struct vt_wang_info *info, const struct vt_image *pack_level,
                      uint32_t level, uint64_t x0, uint64_t y0, struct vt_image *dst)
{
    uint32_t t = info->tile_px >> level;
    size_t texel = vt_image_texel_bytes(dst);
    if (t == 0)
        t = 1;
    for (uint32_t y = 0; y < dst->height; y++) {
        uint64_t vy = y0 + y;
        for (uint32_t x = 0; x < dst->width;) {
            uint64_t vx = x0 + x;
            uint32_t tx = (uint32_t)(vx / t % info->hash_n), ty = (uint32_t)(vy / t % info->hash_n);
            uint32_t col, row, ix = (uint32_t)(vx % t), iy = (uint32_t)(vy % t);
            vt_wang_info_locate(info, tx, ty, &col, &row);
            uint32_t run = t - ix < dst->width - x ? t - ix : dst->width - x;
            memcpy(vt_image_at(dst, x, y), vt_image_at(pack_level, col * t + ix, row * t + iy),
                   run * texel);
            x += run;
        }
    }
}

char *vt_wang_hash_format(const uint32_t *perm, uint32_t n)
{
    size_t cap = (size_t)n * 7 + 1, len = 0;
    char *s = malloc(cap);
    if (!s)
        return NULL;
    s[0] = '\0';
    for (uint32_t i = 0; i < n; i++) {
        int k = snprintf(s + len, cap - len, i ? " %u" : "%u", perm[i]);
        if (k < 0 || (size_t)k >= cap - len) {
            free(s);
            return NULL;
        }
        len += (size_t)k;
    }
    return s;
}
