/* Sharded atlas builds (see vt_atlas_build_part in vt_atlas_build.h and docs/sharding.md): which
 * tiles a shard or the merge emits, the entries a shard needs, the payload a shard carries and the
 * merge's chains and carried level made from it.
 *
 * Every tile of an atlas is a function of the layout and the textures alone (owned texels read an
 * entry's chain at their level, mixed texels average their children one level down, recursively):
 * no tile is computed from another level's tiles. A shard therefore emits exactly the single
 * build's tiles of its part. Above the carried level K, a texel is either owned (by an entry of
 * alignment above 2^K: its chain's levels above K travel in the carry) or mixed, and a mixed texel
 * of level K + 1 averages four texels of level K, which the carry holds as the single build
 * computes them (floats, before any rounding). The merge's tiles above K are thus the single
 * build's too. */
#include <stdlib.h>
#include <string.h>

#include "internal/vt_atlas_build_impl.h"
#include "vt_checked.h"
#include "vt_error.h"
#include "vts.h"

static uint32_t ceil_shift(uint32_t v, uint32_t k)
{
    return k >= 32 ? 1 : (uint32_t)(((uint64_t)v + (1ull << k) - 1) >> k);
}

bool vt_atlas_shard_emits(const struct vt_atlas_build *b, uint32_t L, uint32_t tx, uint32_t ty)
{
    if (!b->part.count)
        return true;
    if (b->part.merge)
        return L > b->carried;
    uint32_t sh = b->part_shift - L;
    return L <= b->carried && (tx >> sh) == b->part_x && (ty >> sh) == b->part_y;
}

uint32_t vt_atlas_build_carried_level(const struct vt_atlas_build *b)
{
    return b->carried;
}

bool vt_atlas_build_part_tile(const struct vt_atlas_build *b, uint32_t index, uint32_t *px,
                              uint32_t *py)
{
    *px = index % b->parts_x;
    *py = index / b->parts_x;
    return (uint64_t)*px < b->tx[b->carried] && (uint64_t)*py < b->ty[b->carried];
}

bool vt_atlas_build_carries(const struct vt_atlas_build *b)
{
    return b->part.count && b->carried + 1 < b->level_count;
}

/* ---- geometry ---- */

static const struct vt_layout_texture *key_texture(const struct vt_atlas_tile *t, size_t key)
{
    return &t->lay->entries[key / t->nslots].textures[t->slots[key % t->nslots].layer];
}

/* Level-0 texels of part (px, py): [x0, x1) x [y0, y1), clipped to the atlas (empty past it). */
static void part_rect(const struct vt_atlas_build *b, uint32_t px, uint32_t py, uint64_t r[4])
{
    uint64_t side = (uint64_t)b->t.content << b->part_shift;
    uint64_t w = b->t.lay->width, h = b->t.lay->height;
    r[0] = px * side < w ? px * side : w;
    r[1] = py * side < h ? py * side : h;
    r[2] = (px + 1) * side < w ? (px + 1) * side : w;
    r[3] = (py + 1) * side < h ? (py + 1) * side : h;
}

static bool entry_starts_in(const struct vt_atlas_build *b, uint32_t e, const uint64_t r[4])
{
    const struct vt_layout_entry *en = &b->t.lay->entries[e];
    uint64_t x = vt_layout_cell_x(en), y = vt_layout_cell_y(en);
    return x >= r[0] && x < r[2] && y >= r[1] && y < r[3];
}

/* Chain levels above the carried one of entry e (0 when it has none). */
static uint32_t levels_above(const struct vt_atlas_build *b, uint32_t e)
{
    uint32_t levels = b->t.chains[(size_t)e * b->t.nslots].levels;
    return levels > b->carried + 1 ? levels - b->carried - 1 : 0;
}

static void level_size(const struct vt_atlas_chain_info *ci, uint32_t L, uint32_t *w, uint32_t *h)
{
    *w = ci->fill ? 1 : ceil_shift(ci->w0, L);
    *h = ci->fill ? 1 : ceil_shift(ci->h0, L);
}

/* The slots' formats in the merge: the shards', as vt_atlas_chains.c decides them. */
static void merge_formats(struct vt_atlas_build *b)
{
    for (uint32_t s = 0; s < b->t.nslots; s++) {
        struct vt_atlas_tile_slot *sl = &b->t.slots[s];
        sl->fmt = b->part.formats[s];
        vt_atlas_slot_derive(sl);
    }
}

/* The merge's chains: block ids of the levels above the carried one only, and the cache. */
static int merge_chains(struct vt_atlas_build *b, struct vts_error *err)
{
    struct vt_atlas_tile *t = &b->t;
    size_t nkeys = (size_t)t->lay->entry_count * t->nslots;
    t->chains = calloc(nkeys ? nkeys : 1, sizeof *t->chains);
    if (!t->chains)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the atlas tables");
    uint64_t id = 0;
    for (size_t k = 0; k < nkeys; k++) {
        const struct vt_layout_entry *en = &t->lay->entries[k / t->nslots];
        struct vt_atlas_chain_info *ci = &t->chains[k];
        uint32_t lmax = t->lmax[k / t->nslots];
        ci->levels = lmax + 1u < b->level_count ? lmax + 1u : b->level_count;
        ci->fill = key_texture(t, k)->path == NULL;
        ci->w0 = ci->fill ? 1 : en->crop_width;
        ci->h0 = ci->fill ? 1 : en->crop_height;
        for (uint32_t l = b->carried + 1; l < ci->levels; l++) {
            uint32_t w, h;
            level_size(ci, l, &w, &h);
            ci->base[l] = id;
            id +=
                (uint64_t)ceil_shift(w, VT_BLOCK_CACHE_SHIFT) * ceil_shift(h, VT_BLOCK_CACHE_SHIFT);
        }
    }
    uint64_t budget = b->o.cache_bytes ? b->o.cache_bytes : VT_ATLAS_BUILD_CACHE;
    t->blocks = vt_block_cache_create(id ? id : 1, budget, b->o.temp_dir, err);
    if (!t->blocks)
        return err ? err->status : VTS_ERR_NOMEM;
    t->carried_level = b->carried;
    for (uint32_t s = 0; s < t->nslots && vt_atlas_build_carries(b); s++) {
        size_t n;
        uint32_t ch = t->slots[s].fmt.channels + 1;
        if (!vt_size_mul3((size_t)t->lw[b->carried], t->lh[b->carried], ch, &n) ||
            !(t->carried[s] = calloc(n ? n : 1, sizeof(float))))
            return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the carried level");
    }
    return 0;
}

int vt_atlas_shard_prepare(struct vt_atlas_build *b, struct vts_error *err)
{
    const struct vt_atlas_build_part *p = &b->o.part;
    uint32_t m = 0;
    while ((1u << m) < p->count)
        m++;
    if ((1u << m) != p->count || p->index >= p->count || (p->merge && !p->formats))
        return vt_error_set(err, VTS_ERR_ARG, "atlas build: bad part %u of %u", p->index, p->count);
    b->part = *p;
    /* the grid 2^a x 2^(m - a) whose parts are the smallest (the atlas's shape), ties to the
     * image shards' 2^ceil(m/2) x 2^floor(m/2) */
    b->part_shift = UINT32_MAX;
    for (uint32_t i = 0; i <= m; i++) {
        uint32_t a = i == 0 ? (m + 1) / 2 : i - 1 < (m + 1) / 2 ? i - 1 : i, sh = 0;
        while (((uint64_t)1 << a << sh) < b->tx[0] || ((uint64_t)1 << (m - a) << sh) < b->ty[0])
            sh++;
        if (sh < b->part_shift) {
            b->part_shift = sh;
            b->parts_x = 1u << a;
        }
    }
    b->carried = b->part_shift < b->level_count - 1 ? b->part_shift : b->level_count - 1;
    b->part_x = p->index % b->parts_x;
    b->part_y = p->index / b->parts_x;
    if (p->merge) {
        merge_formats(b);
        return merge_chains(b, err);
    }
    /* the entries whose cell meets the part's tiles with their borders, at every level up to K */
    uint32_t ne = b->t.lay->entry_count;
    if (!(b->need = calloc(ne ? ne : 1, 1)))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the atlas tables");
    uint64_t r[4];
    part_rect(b, b->part_x, b->part_y, r);
    uint64_t margin = (uint64_t)b->t.border << b->carried;
    if (r[0] < r[2] && r[1] < r[3]) {
        r[0] = r[0] > margin ? r[0] - margin : 0;
        r[1] = r[1] > margin ? r[1] - margin : 0;
        r[2] += margin;
        r[3] += margin;
        for (uint32_t e = 0; e < ne; e++) {
            const struct vt_layout_entry *en = &b->t.lay->entries[e];
            uint64_t x0 = vt_layout_cell_x(en), y0 = vt_layout_cell_y(en);
            b->need[e] =
                x0 < r[2] && x0 + en->cell_width > r[0] && y0 < r[3] && y0 + en->cell_height > r[1];
        }
    }
    b->t.need = b->need;
    return 0;
}

/* ---- the carried payload ---- */

static void put_u32(unsigned char *d, uint32_t u)
{
    d[0] = (unsigned char)u;
    d[1] = (unsigned char)(u >> 8);
    d[2] = (unsigned char)(u >> 16);
    d[3] = (unsigned char)(u >> 24);
}

static uint32_t get_u32(const unsigned char *s)
{
    return (uint32_t)s[0] | (uint32_t)s[1] << 8 | (uint32_t)s[2] << 16 | (uint32_t)s[3] << 24;
}

static void put_f32(unsigned char *d, float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    put_u32(d, u);
}

static float get_f32(const unsigned char *s)
{
    uint32_t u = get_u32(s);
    float f;
    memcpy(&f, &u, 4);
    return f;
}

/* Texels of level K of part (px, py): [x0, x0 + w) x [y0, y0 + h). */
static void carried_rect(const struct vt_atlas_build *b, uint32_t px, uint32_t py, uint32_t *x0,
                         uint32_t *y0, uint32_t *w, uint32_t *h)
{
    uint32_t c = b->t.content, K = b->carried;
    uint64_t ax = (uint64_t)px * c, ay = (uint64_t)py * c;
    *x0 = ax < b->t.lw[K] ? (uint32_t)ax : b->t.lw[K];
    *y0 = ay < b->t.lh[K] ? (uint32_t)ay : b->t.lh[K];
    *w = b->t.lw[K] - *x0 < c ? b->t.lw[K] - *x0 : c;
    *h = b->t.lh[K] - *y0 < c ? b->t.lh[K] - *y0 : c;
}

/* Payload bytes of the entries' chains above K (per entry: index, then every slot's levels). */
static bool entry_bytes(const struct vt_atlas_build *b, uint32_t e, size_t *out)
{
    size_t n = 4;
    for (uint32_t s = 0; s < b->t.nslots; s++) {
        const struct vt_atlas_chain_info *ci = &b->t.chains[(size_t)e * b->t.nslots + s];
        for (uint32_t l = b->carried + 1; l < ci->levels; l++) {
            uint32_t w, h;
            level_size(ci, l, &w, &h);
            size_t lb;
            if (!vt_size_mul3(w, h, b->t.slots[s].texel_bytes, &lb) || !vt_size_add(n, lb, &n))
                return false;
        }
    }
    *out = n;
    return true;
}

/* Copies level l of key's chain between the block cache and a row-major level: from the cache
 * into px, or (from not NULL) from `from` into the cache. */
static int chain_level(struct vt_atlas_build *b, size_t key, uint32_t l, unsigned char *px,
                       const unsigned char *from, struct vts_error *err)
{
    struct vt_atlas_tile *t = &b->t;
    const struct vt_atlas_chain_info *ci = &t->chains[key];
    struct vt_atlas_tile_worker *wk = &b->workers[b->o.threads];
    uint32_t w, h, E = VT_BLOCK_CACHE_EDGE;
    size_t ch = t->slots[key % t->nslots].texel_bytes; /* bytes per texel */
    level_size(ci, l, &w, &h);
    uint32_t nbx = ceil_shift(w, VT_BLOCK_CACHE_SHIFT);
    bool to_cache = from != NULL;
    unsigned char *tmp = to_cache ? malloc((size_t)E * E * ch) : NULL;
    if (to_cache && !tmp)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a chain block");
    int rc = 0;
    for (uint32_t y = 0; y < h && rc == 0; y += E)
        for (uint32_t x = 0; x < w && rc == 0; x += E) {
            uint32_t bw = w - x < E ? w - x : E, bh = h - y < E ? h - y : E;
            uint64_t id = ci->base[l] + (uint64_t)(y / E) * nbx + x / E;
            const uint8_t *blk = tmp;
            if (!to_cache)
                rc = vt_block_cache_get(t->blocks, &wk->pins, id, &blk, err);
            for (uint32_t j = 0; j < bh && rc == 0; j++) {
                size_t row = ((size_t)(y + j) * w + x) * ch;
                if (to_cache)
                    memcpy(tmp + (size_t)j * bw * ch, from + row, (size_t)bw * ch);
                else
                    memcpy(px + row, blk + (size_t)j * bw * ch, (size_t)bw * ch);
            }
            if (rc == 0 && to_cache)
                rc = vt_block_cache_put(t->blocks, id, tmp, (size_t)bw * bh * ch, err);
            vt_atlas_tile_unpin(t, wk);
        }
    free(tmp);
    return rc;
}

int vt_atlas_build_carry(struct vt_atlas_build *b, unsigned char **payload, size_t *len,
                         struct vts_error *err)
{
    *payload = NULL;
    *len = 0;
    if (!vt_atlas_build_carries(b) || b->part.merge)
        return 0;
    struct vt_atlas_tile *t = &b->t;
    uint32_t x0, y0, w, h, ne = t->lay->entry_count, count = 0;
    carried_rect(b, b->part_x, b->part_y, &x0, &y0, &w, &h);
    uint64_t r[4];
    part_rect(b, b->part_x, b->part_y, r);
    size_t n = 4, eb;
    for (uint32_t s = 0; s < t->nslots; s++) {
        size_t sb;
        if (!vt_size_mul3((size_t)w * h, t->slots[s].fmt.channels + 1u, 4, &sb) ||
            !vt_size_add(n, sb, &n))
            return vt_error_set(err, VTS_ERR_LIMIT, "the carried level is too large");
    }
    for (uint32_t e = 0; e < ne; e++)
        if (levels_above(b, e) && entry_starts_in(b, e, r)) {
            if (!entry_bytes(b, e, &eb) || !vt_size_add(n, eb, &n))
                return vt_error_set(err, VTS_ERR_LIMIT, "the carried chains are too large");
            count++;
        }
    if (n > UINT32_MAX)
        return vt_error_set(err, VTS_ERR_LIMIT, "the carried data exceed 4 GiB");
    unsigned char *d = malloc(n), *o = d;
    if (!d)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the carried data");
    int rc = 0;
    struct vt_atlas_tile_worker *wk = &b->workers[b->o.threads];
    for (uint32_t s = 0; s < t->nslots && rc == 0; s++) {
        uint32_t ch = t->slots[s].fmt.channels;
        for (uint32_t j = 0; j < h && rc == 0; j++)
            for (uint32_t i = 0; i < w && rc == 0; i++) {
                float v[4], cov;
                rc = vt_atlas_tile_working(t, wk, s, b->carried, x0 + i, y0 + j, v, &cov, err);
                for (uint32_t c = 0; c < ch; c++, o += 4)
                    put_f32(o, v[c]);
                put_f32(o, cov);
                o += 4;
            }
        vt_atlas_tile_unpin(t, wk);
    }
    put_u32(o, count);
    o += 4;
    for (uint32_t e = 0; e < ne && rc == 0; e++) {
        if (!levels_above(b, e) || !entry_starts_in(b, e, r))
            continue;
        put_u32(o, e);
        o += 4;
        for (uint32_t s = 0; s < t->nslots && rc == 0; s++) {
            size_t key = (size_t)e * t->nslots + s;
            for (uint32_t l = b->carried + 1; l < t->chains[key].levels && rc == 0; l++) {
                uint32_t lw, lh;
                level_size(&t->chains[key], l, &lw, &lh);
                rc = chain_level(b, key, l, o, NULL, err);
                o += (size_t)lw * lh * t->slots[s].texel_bytes;
            }
        }
    }
    if (rc) {
        free(d);
        return rc;
    }
    *payload = d;
    *len = n;
    return 0;
}

int vt_atlas_build_put_carry(struct vt_atlas_build *b, uint32_t index, const unsigned char *payload,
                             size_t len, struct vts_error *err)
{
    if (!b->part.merge || index >= b->part.count)
        return vt_error_set(err, VTS_ERR_ARG, "atlas build: not a merge, or part %u", index);
    if (!vt_atlas_build_carries(b))
        return 0;
    struct vt_atlas_tile *t = &b->t;
    uint32_t px = index % b->parts_x, py = index / b->parts_x, x0, y0, w, h;
    carried_rect(b, px, py, &x0, &y0, &w, &h);
    uint64_t r[4];
    part_rect(b, px, py, r);
    size_t at = 0;
    for (uint32_t s = 0; s < t->nslots; s++) {
        uint32_t ch = t->slots[s].fmt.channels + 1;
        size_t need = (size_t)w * h * ch * 4;
        if (len - at < need)
            return vt_error_set(err, VTS_ERR_BAD_INPUT, "carried level: %zu bytes, too short", len);
        for (uint32_t j = 0; j < h; j++) {
            float *row = t->carried[s] + ((size_t)(y0 + j) * t->lw[b->carried] + x0) * ch;
            for (size_t i = 0; i < (size_t)w * ch; i++, at += 4)
                row[i] = get_f32(payload + at);
        }
    }
    if (len - at < 4)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "carried data: no entry count");
    uint32_t count = get_u32(payload + at), prev = 0, expected = 0;
    at += 4;
    for (uint32_t e = 0; e < t->lay->entry_count; e++)
        expected += levels_above(b, e) && entry_starts_in(b, e, r);
    if (count != expected)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "carried chains: %u entries, %u expected",
                            count, expected);
    for (uint32_t i = 0; i < count; i++) {
        size_t eb;
        uint32_t e = len - at >= 4 ? get_u32(payload + at) : UINT32_MAX;
        if (e >= t->lay->entry_count || (i && e <= prev) || !levels_above(b, e) ||
            !entry_starts_in(b, e, r) || !entry_bytes(b, e, &eb) || len - at < eb)
            return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                "carried chains: entry %u is not one of this part's", e);
        prev = e;
        at += 4;
        for (uint32_t s = 0; s < t->nslots; s++) {
            size_t key = (size_t)e * t->nslots + s;
            for (uint32_t l = b->carried + 1; l < t->chains[key].levels; l++) {
                uint32_t lw, lh;
                level_size(&t->chains[key], l, &lw, &lh);
                int rc = chain_level(b, key, l, NULL, payload + at, err);
                if (rc)
                    return rc;
                at += (size_t)lw * lh * t->slots[s].texel_bytes;
            }
        }
    }
    if (at != len)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "carried data: %zu bytes, %zu expected", len,
                            at);
    return 0;
}
