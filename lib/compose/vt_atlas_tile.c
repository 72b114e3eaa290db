/* Per-tile compositing of an atlas (see vt_atlas_tile.h and docs/atlas-build.md). */
#include "internal/vt_atlas_build_impl.h"
#include "vt_error.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

static uint32_t ceil_shift(uint32_t v, uint32_t k)
{
    return k >= 32 ? 1 : (uint32_t)(((uint64_t)v + (1ull << k) - 1) >> k);
}

int vt_atlas_tile_build_grid(struct vt_atlas_tile *t, struct vts_error *err)
{
    const struct vt_layout *lay = t->lay;
    uint64_t target = lay->entry_count * 4ull < 4096 ? 4096 : lay->entry_count * 4ull;
    if (target > (1u << 22))
        target = 1u << 22;
    uint32_t s = 4;
    while (s < 30 && (uint64_t)ceil_shift(lay->width, s) * ceil_shift(lay->height, s) > target)
        s++;
    t->gshift = s;
    t->gw = ceil_shift(lay->width, s);
    t->gh = ceil_shift(lay->height, s);
    size_t nb = (size_t)t->gw * t->gh;
    t->goff = calloc(nb + 1, sizeof *t->goff);
    t->gsat = calloc(((size_t)t->gw + 1) * (t->gh + 1), sizeof *t->gsat);
    if (!t->goff || !t->gsat)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the atlas grid");
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t e = 0; e < lay->entry_count; e++) {
            const struct vt_layout_entry *en = &lay->entries[e];
            uint32_t ex = vt_layout_cell_x(en), ey = vt_layout_cell_y(en);
            uint32_t bx0 = ex >> s, by0 = ey >> s;
            uint32_t bx1 = (uint32_t)(((uint64_t)ex + en->cell_width - 1) >> s);
            uint32_t by1 = (uint32_t)(((uint64_t)ey + en->cell_height - 1) >> s);
            for (uint32_t by = by0; by <= by1; by++)
                for (uint32_t bx = bx0; bx <= bx1; bx++) {
                    size_t i = (size_t)by * t->gw + bx;
                    if (pass == 0)
                        t->goff[i + 1]++;
                    else
                        t->gidx[t->goff[i] + t->gsat[i]++] = e; /* gsat: fill counter here */
                }
        }
        if (pass == 0) {
            for (size_t i = 0; i < nb; i++)
                t->goff[i + 1] += t->goff[i];
            t->gidx = malloc(((size_t)t->goff[nb] + 1) * sizeof *t->gidx);
            if (!t->gidx)
                return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the atlas grid");
        }
    }
    /* summed-area table of occupied buckets: sat[(y) * (gw+1) + x] = buckets in [0,x) x [0,y) */
    memset(t->gsat, 0, ((size_t)t->gw + 1) * (t->gh + 1) * sizeof *t->gsat);
    size_t sw = (size_t)t->gw + 1;
    for (uint32_t y = 0; y < t->gh; y++)
        for (uint32_t x = 0; x < t->gw; x++) {
            size_t i = (size_t)y * t->gw + x;
            uint32_t occ = t->goff[i + 1] > t->goff[i];
            t->gsat[(y + 1) * sw + x + 1] =
                occ + t->gsat[y * sw + x + 1] + t->gsat[(y + 1) * sw + x] - t->gsat[y * sw + x];
        }
    return 0;
}

/* Class of texel (X, Y) of level L: the owning entry (>= 0), VT_ATLAS_TILE_EMPTY or
 * VT_ATLAS_TILE_MIXED. For an owned texel, *run_end is the first X of the row past the owner's
 * cell. */
int32_t vt_atlas_tile_classify(const struct vt_atlas_tile *t, uint32_t L, uint32_t X, uint32_t Y,
                               uint32_t *run_end)
{
    const struct vt_layout *lay = t->lay;
    uint64_t fx0 = (uint64_t)X << L, fy0 = (uint64_t)Y << L;
    uint64_t fx1 = ((uint64_t)X + 1) << L, fy1 = ((uint64_t)Y + 1) << L;
    fx1 = fx1 < lay->width ? fx1 : lay->width;
    fy1 = fy1 < lay->height ? fy1 : lay->height;
    uint32_t s = t->gshift;
    uint32_t bx0 = (uint32_t)(fx0 >> s), by0 = (uint32_t)(fy0 >> s);
    uint32_t bx1 = (uint32_t)((fx1 - 1) >> s), by1 = (uint32_t)((fy1 - 1) >> s);
    if (bx1 > bx0 || by1 > by0) {
        size_t sw = (size_t)t->gw + 1;
        uint32_t n = t->gsat[(by1 + 1) * sw + bx1 + 1] - t->gsat[by0 * sw + bx1 + 1] -
                     t->gsat[(by1 + 1) * sw + bx0] + t->gsat[by0 * sw + bx0];
        if (n == 0)
            return VT_ATLAS_TILE_EMPTY;
    }
    for (uint32_t by = by0; by <= by1; by++)
        for (uint32_t bx = bx0; bx <= bx1; bx++) {
            size_t i = (size_t)by * t->gw + bx;
            for (uint32_t j = t->goff[i]; j < t->goff[i + 1]; j++) {
                const struct vt_layout_entry *en = &lay->entries[t->gidx[j]];
                uint64_t cx0 = vt_layout_cell_x(en), cy0 = vt_layout_cell_y(en);
                uint64_t cx1 = cx0 + en->cell_width;
                uint64_t cy1 = cy0 + en->cell_height;
                if (cx0 >= fx1 || cx1 <= fx0 || cy0 >= fy1 || cy1 <= fy0)
                    continue;
                if (L <= t->lmax[t->gidx[j]] && cx0 <= fx0 && cy0 <= fy0 && cx1 >= fx1 &&
                    cy1 >= fy1) {
                    *run_end = (uint32_t)(cx1 >> L);
                    return (int32_t)t->gidx[j];
                }
                return VT_ATLAS_TILE_MIXED;
            }
        }
    return VT_ATLAS_TILE_EMPTY;
}

/* Texel of owned entry e at level L, position (X, Y) clamped into the entry's chain: cell
 * padding and the gutter before x/y repeat the texture's edge. A wrap entry's chain is read modulo
 * its level's size instead: texel -1 is texel width - 1, so the gutter, the padding and the
 * borders at its edges show the opposite edge, as the repeating texture does. */
static int owned_run(struct vt_atlas_tile *t, struct vt_atlas_tile_worker *w, uint32_t s,
                     uint32_t e, uint32_t L, int64_t X, int64_t Y, const uint8_t **out,
                     uint32_t *run, struct vts_error *err)
{
    const struct vt_atlas_chain_info *ci = &t->chains[(size_t)e * t->nslots + s];
    assert(L < ci->levels);
    const struct vt_layout_entry *en = &t->lay->entries[e];
    int64_t lw = ci->fill ? 1 : ceil_shift(ci->w0, L), lh = ci->fill ? 1 : ceil_shift(ci->h0, L);
    int64_t i = X - (int64_t)(en->x >> L), j = Y - (int64_t)(en->y >> L);
    bool clamped = !en->wrap && (i < 0 || i >= lw);
    if (en->wrap) {
        i %= lw;
        j %= lh;
        i += i < 0 ? lw : 0;
        j += j < 0 ? lh : 0;
    } else {
        i = i < 0 ? 0 : i >= lw ? lw - 1 : i;
        j = j < 0 ? 0 : j >= lh ? lh - 1 : j;
    }
    uint32_t sh = VT_BLOCK_CACHE_SHIFT, m = VT_BLOCK_CACHE_EDGE - 1;
    uint64_t id =
        ci->base[L] + (uint64_t)(j >> sh) * ceil_shift((uint32_t)lw, sh) + (uint64_t)(i >> sh);
    if (!w->last_px || w->last_id != id) {
        int rc = vt_block_cache_get(t->blocks, &w->pins, id, &w->last_px, err);
        if (rc) {
            w->last_px = NULL;
            return rc;
        }
        w->last_id = id;
    }
    int64_t x0 = i & ~(int64_t)m;
    uint32_t bw = lw - x0 < VT_BLOCK_CACHE_EDGE ? (uint32_t)(lw - x0) : VT_BLOCK_CACHE_EDGE;
    *out = w->last_px + ((size_t)(j & m) * bw + (size_t)(i & m)) * t->slots[s].texel_bytes;
    /* texels X + 1 ... read the next ones of the block's row until its end (the chain's) */
    *run = clamped ? 1 : bw - (uint32_t)(i & m);
    return 0;
}

static int owned_texel(struct vt_atlas_tile *t, struct vt_atlas_tile_worker *w, uint32_t s,
                       uint32_t e, uint32_t L, int64_t X, int64_t Y, const uint8_t **out,
                       struct vts_error *err)
{
    uint32_t run;
    return owned_run(t, w, s, e, L, X, Y, out, &run, err);
}

void vt_atlas_tile_unpin(struct vt_atlas_tile *t, struct vt_atlas_tile_worker *w)
{
    if (t->blocks)
        vt_block_cache_unpin_all(t->blocks, &w->pins);
    w->last_px = NULL;
}

/* A mixed texel: the coverage-weighted average of its children one level down (working space,
 * premultiplied). *cov receives the covered fraction of its footprint (0..1). */
static int mixed_texel(struct vt_atlas_tile *t, struct vt_atlas_tile_worker *w, uint32_t s,
                       uint32_t L, uint32_t X, uint32_t Y, float *out, float *cov,
                       struct vts_error *err)
{
    const struct vt_atlas_tile_slot *sl = &t->slots[s];
    uint32_t ch = sl->fmt.channels;
    float sum[4] = {0, 0, 0, 0}, wsum = 0.0f;
    assert(L > 0);
    __atomic_fetch_add(&t->texels_mixed, 1, __ATOMIC_RELAXED);
    for (uint32_t d = 0; d < 4; d++) {
        uint32_t cx = 2 * X + (d & 1), cy = 2 * Y + (d >> 1), run;
        if (cx >= t->lw[L - 1] || cy >= t->lh[L - 1])
            continue;
        float v[4], cw = 1.0f;
        int rc = 0;
        if (t->carried[s] && L - 1 == t->carried_level) { /* a merge: what the shards carried */
            const float *p = t->carried[s] + ((size_t)cy * t->lw[L - 1] + cx) * (ch + 1);
            if (p[ch] == 0.0f)
                continue;
            memcpy(v, p, ch * sizeof *v);
            cw = p[ch];
            for (uint32_t c = 0; c < ch; c++)
                sum[c] += cw * v[c];
            wsum += cw;
            continue;
        }
        int32_t k = vt_atlas_tile_classify(t, L - 1, cx, cy, &run);
        if (k == VT_ATLAS_TILE_EMPTY)
            continue;
        if (k >= 0) {
            const uint8_t *p;
            rc = owned_texel(t, w, s, (uint32_t)k, L - 1, cx, cy, &p, err);
            if (rc == 0)
                vt_filter_to_working(&sl->mode, sl->fmt.sample, p, v, 1);
        } else {
            rc = mixed_texel(t, w, s, L - 1, cx, cy, v, &cw, err);
        }
        if (rc)
            return rc;
        for (uint32_t c = 0; c < ch; c++)
            sum[c] += cw * v[c];
        wsum += cw;
    }
    *cov = wsum / 4.0f;
    for (uint32_t c = 0; c < ch; c++)
        out[c] = wsum > 0.0f ? sum[c] / wsum : 0.0f;
    if (sl->fmt.colour == VTS_COLOUR_NORMAL && ch >= 3) {
        struct vt_fregion r = {0, 0, 1, 1, ch, out};
        vt_filter_renormalize(&r);
    }
    return 0;
}

int vt_atlas_tile_working(struct vt_atlas_tile *t, struct vt_atlas_tile_worker *w, uint32_t s,
                          uint32_t L, uint32_t X, uint32_t Y, float *v, float *cov,
                          struct vts_error *err)
{
    const struct vt_atlas_tile_slot *sl = &t->slots[s];
    uint32_t run;
    int32_t k = vt_atlas_tile_classify(t, L, X, Y, &run);
    memset(v, 0, sl->fmt.channels * sizeof *v);
    *cov = 0.0f;
    if (k == VT_ATLAS_TILE_EMPTY)
        return 0;
    if (k == VT_ATLAS_TILE_MIXED)
        return mixed_texel(t, w, s, L, X, Y, v, cov, err);
    const uint8_t *p;
    int rc = owned_texel(t, w, s, (uint32_t)k, L, X, Y, &p, err);
    if (rc == 0) {
        vt_filter_to_working(&sl->mode, VTS_SAMPLE_U8, p, v, 1);
        *cov = 1.0f;
    }
    return rc;
}

/* Writes the value of texel (X, Y) of level L whose class is k into o. */
int vt_atlas_tile_texel(struct vt_atlas_tile *t, struct vt_atlas_tile_worker *w, uint32_t s,
                        uint32_t L, uint32_t X, uint32_t Y, int32_t k, uint8_t *o,
                        struct vts_error *err)
{
    const struct vt_atlas_tile_slot *sl = &t->slots[s];
    size_t tb = sl->texel_bytes;
    if (k >= 0) {
        const uint8_t *p;
        int rc = owned_texel(t, w, s, (uint32_t)k, L, X, Y, &p, err);
        if (rc == 0)
            memcpy(o, p, tb);
        return rc;
    }
    if (k == VT_ATLAS_TILE_MIXED) {
        float v[4], cov;
        int rc = mixed_texel(t, w, s, L, X, Y, v, &cov, err);
        if (rc)
            return rc;
        if (cov > 0.0f) {
            vt_filter_from_working(&sl->mode, sl->fmt.sample, v, o, 1);
            return 0;
        }
    }
    memcpy(o, sl->empty_px, tb);
    return 0;
}

/* Classes of the tile's content texels; returns whether any is not empty. */
bool vt_atlas_tile_classify_content(const struct vt_atlas_tile *t, struct vt_atlas_tile_worker *w,
                                    uint32_t L, uint32_t cx0, uint32_t cy0, uint32_t cw,
                                    uint32_t chh)
{
    bool any = false;
    for (uint32_t j = 0; j < chh; j++) {
        int32_t *row = w->cls + (size_t)j * t->content;
        for (uint32_t i = 0; i < cw;) {
            uint32_t run = 0;
            int32_t k = vt_atlas_tile_classify(t, L, cx0 + i, cy0 + j, &run);
            uint32_t end = k >= 0 ? run - cx0 : i + 1;
            end = end < cw ? end : cw;
            any |= k != VT_ATLAS_TILE_EMPTY;
            for (; i < end; i++)
                row[i] = k;
        }
    }
    return any;
}

/* Entries of one group are one surface: a border texel whose nearest content texel belongs to
 * entry k reads the group member that owns its own position, if any (else k, clamped). */
static int32_t group_owner(const struct vt_atlas_tile *t, uint32_t L, int32_t k, int64_t Xn,
                           int64_t Yn, int64_t Xc, int64_t Yc)
{
    uint32_t g = t->lay->entries[k].group, run;
    if (g == 0 || (Xn == Xc && Yn == Yc))
        return k;
    int32_t k2 = vt_atlas_tile_classify(t, L, (uint32_t)Xn, (uint32_t)Yn, &run);
    return k2 >= 0 && t->lay->entries[k2].group == g ? k2 : k;
}

int vt_atlas_tile_fill_payload(struct vt_atlas_tile *t, struct vt_atlas_tile_worker *w, uint32_t s,
                               uint32_t L, uint32_t cx0, uint32_t cy0, uint32_t cw, uint32_t chh,
                               struct vts_error *err)
{
    struct vt_image *p = &w->payload[s];
    size_t tb = t->slots[s].texel_bytes;
    uint32_t bd = t->border;
    int64_t lw = t->lw[L], lh = t->lh[L];
    for (uint32_t j = 0; j < t->payload; j++) {
        int64_t Y = (int64_t)cy0 - bd + j;
        int64_t Yn = Y < 0 ? 0 : Y >= lh ? lh - 1 : Y;
        int64_t Yc = Yn < cy0 ? cy0 : Yn >= cy0 + chh ? cy0 + chh - 1 : Yn;
        uint8_t *o = vt_image_at(p, 0, j);
        const int32_t *cls = w->cls + (size_t)(Yc - cy0) * t->content;
        for (uint32_t i = 0; i < t->payload; i++, o += tb) {
            int64_t X = (int64_t)cx0 - bd + i;
            if (Y == Yc && X >= cx0 && X < (int64_t)cx0 + cw && cls[X - cx0] >= 0) {
                /* content texels of one owner: runs of a block's row (no group, no clamp) */
                uint32_t c = (uint32_t)(X - cx0), n;
                const uint8_t *src;
                int rc = owned_run(t, w, s, (uint32_t)cls[c], L, X, Y, &src, &n, err);
                if (rc)
                    return rc;
                uint32_t m = 1;
                while (m < n && c + m < cw && cls[c + m] == cls[c])
                    m++;
                memcpy(o, src, (size_t)m * tb);
                i += m - 1;
                o += (size_t)(m - 1) * tb;
                continue;
            }
            int64_t Xn = X < 0 ? 0 : X >= lw ? lw - 1 : X;
            int64_t Xc = Xn < cx0 ? cx0 : Xn >= cx0 + cw ? cx0 + cw - 1 : Xn;
            int32_t k = w->cls[(size_t)(Yc - cy0) * t->content + (size_t)(Xc - cx0)];
            int rc;
            if (k >= 0) {
                const uint8_t *src;
                k = group_owner(t, L, k, Xn, Yn, Xc, Yc);
                /* a wrap entry wraps past the atlas's edge too: its own position, not clamped */
                bool wrap = t->lay->entries[k].wrap;
                rc = owned_texel(t, w, s, (uint32_t)k, L, wrap ? X : Xn, wrap ? Y : Yn, &src, err);
                if (rc == 0)
                    memcpy(o, src, tb);
            } else {
                uint32_t run;
                if (Xn != Xc || Yn != Yc)
                    k = vt_atlas_tile_classify(t, L, (uint32_t)Xn, (uint32_t)Yn, &run);
                rc = vt_atlas_tile_texel(t, w, s, L, (uint32_t)Xn, (uint32_t)Yn, k, o, err);
            }
            if (rc)
                return rc;
        }
    }
    return 0;
}

void vt_atlas_tile_release_grid(struct vt_atlas_tile *t)
{
    free(t->goff);
    free(t->gidx);
    free(t->gsat);
    t->goff = t->gidx = t->gsat = NULL;
}
