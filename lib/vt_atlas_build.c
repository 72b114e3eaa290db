/* Atlas compositing (see vt_atlas_build.h and docs/atlas-build.md). */
#include "vt_atlas_build.h"

#include <assert.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "vt_checked.h"
#include "vt_mip_chain.h"
#include "vt_pool.h"
#include "vts.h"

#define CLS_EMPTY (-1)
#define CLS_MIXED (-2)
#define PINS      8 /* chains a worker holds at once */

enum chain_state { CHAIN_LOADING, CHAIN_READY };

struct chain_node {
    struct vt_mip_chain c;
    uint64_t key;
    int refs;
    enum chain_state state;
    struct chain_node *prev, *next; /* LRU list of unreferenced ready chains */
};

struct tex_info {
    uint8_t channels, sample;
    bool opaque;
};

struct slot {
    uint32_t layer;
    struct vt_atlas_layer_format fmt;
    struct vt_pixel_mode mode;
    uint8_t empty_px[4];
};

struct pin {
    uint64_t key;
    struct chain_node *node;
};

struct worker {
    struct pin pins[PINS];
    uint32_t pin_count, pin_next;
    int32_t *cls; /* content classes of the current tile */
    struct vt_image payload[VT_LAYOUT_MAX_LAYERS];
};

struct vt_atlas_build {
    struct vt_atlas_build_options o;
    const struct vt_layout *lay;
    struct slot slots[VT_LAYOUT_MAX_LAYERS];
    uint32_t nslots;
    uint32_t content, border, payload, level_count;
    uint32_t lw[VTS_MAX_LEVELS + 1],
        lh[VTS_MAX_LEVELS + 1]; /* + 1: keeps GCC's bounds check quiet */
    uint32_t tx[VTS_MAX_LEVELS + 1], ty[VTS_MAX_LEVELS + 1];
    uint64_t first[VTS_MAX_LEVELS + 1]; /* job number of each level's first tile */
    uint8_t *lmax;                      /* per entry: log2(alignment) */
    struct tex_info *tex;               /* entries x slots */
    /* grid over level 0: buckets of 2^gshift texels listing the entries whose cell meets them */
    uint32_t gshift, gw, gh;
    uint32_t *goff, *gidx, *gsat;
    /* chain cache */
    pthread_mutex_t mu;
    pthread_cond_t cv;
    bool sync_ok;
    struct chain_node **table; /* entries x slots */
    struct chain_node *lru_head, *lru_tail;
    uint64_t bytes, peak, built, budget;
    uint64_t tiles_empty, texels_mixed;
    struct worker *workers; /* threads + 1 (the last for render) */
};

static uint32_t ceil_shift(uint32_t v, uint32_t k)
{
    return k >= 32 ? 1 : (uint32_t)(((uint64_t)v + (1ull << k) - 1) >> k);
}

static uint32_t log2_u32(uint32_t v)
{
    uint32_t l = 0;
    while (l < 31 && (1u << (l + 1)) <= v)
        l++;
    return l;
}

/* ---- chain cache ---- */

static void lru_unlink(struct vt_atlas_build *b, struct chain_node *n)
{
    if (n->prev)
        n->prev->next = n->next;
    else
        b->lru_head = n->next;
    if (n->next)
        n->next->prev = n->prev;
    else
        b->lru_tail = n->prev;
    n->prev = n->next = NULL;
}

static void lru_push(struct vt_atlas_build *b, struct chain_node *n)
{
    n->prev = b->lru_tail;
    n->next = NULL;
    if (b->lru_tail)
        b->lru_tail->next = n;
    else
        b->lru_head = n;
    b->lru_tail = n;
}

/* Frees unreferenced chains, oldest first, while over budget. Under the lock. */
static void evict(struct vt_atlas_build *b)
{
    while (b->bytes > b->budget && b->lru_head) {
        struct chain_node *n = b->lru_head;
        lru_unlink(b, n);
        b->table[n->key] = NULL;
        b->bytes -= n->c.bytes;
        vt_mip_chain_release(&n->c);
        free(n);
    }
}

static int build_chain(struct vt_atlas_build *b, uint32_t e, uint32_t s, struct vt_mip_chain *c,
                       struct vt_error *err)
{
    const struct vt_layout_entry *en = &b->lay->entries[e];
    const struct vt_layout_texture *t = &en->textures[b->slots[s].layer];
    const struct vt_atlas_layer_format *f = &b->slots[s].fmt;
    uint32_t levels = b->lmax[e] + 1u < b->level_count ? b->lmax[e] + 1u : b->level_count;
    struct vt_mip_chain_spec spec = {en->width,   en->height,         en->repeat_u, en->repeat_v,
                                     levels,      f->colour_channels, f->alpha,     f->colour,
                                     b->o.filter, b->o.max_pixels};
    if (!t->path)
        return vt_mip_chain_from_fill(c, &spec, t->fill, err);
    struct vt_source src = {0};
    int rc = b->o.open(b->o.open_user, t->resolved ? t->resolved : t->path, &src, err);
    if (rc == 0)
        rc = vt_mip_chain_from_source(c, &spec, &src, err);
    vt_source_close(&src);
    return rc;
}

/* The chain of entry e in slot s, referenced (release with chain_release). */
static int chain_acquire(struct vt_atlas_build *b, uint32_t e, uint32_t s, struct chain_node **out,
                         struct vt_error *err)
{
    uint64_t key = (uint64_t)e * b->nslots + s;
    pthread_mutex_lock(&b->mu);
    for (;;) {
        struct chain_node *n = b->table[key];
        if (!n)
            break;
        if (n->state == CHAIN_READY) {
            if (n->refs++ == 0)
                lru_unlink(b, n);
            pthread_mutex_unlock(&b->mu);
            *out = n;
            return 0;
        }
        pthread_cond_wait(&b->cv, &b->mu); /* another worker is decoding it */
    }
    struct chain_node *n = calloc(1, sizeof *n);
    if (!n) {
        pthread_mutex_unlock(&b->mu);
        return vt_error_set(err, VT_ERR_NOMEM, "out of memory for a texture chain");
    }
    n->key = key;
    n->state = CHAIN_LOADING;
    n->refs = 1;
    b->table[key] = n;
    pthread_mutex_unlock(&b->mu);

    int rc = build_chain(b, e, s, &n->c, err);

    pthread_mutex_lock(&b->mu);
    if (rc) {
        b->table[key] = NULL;
        free(n);
        n = NULL;
    } else {
        n->state = CHAIN_READY;
        b->bytes += n->c.bytes;
        b->built++;
        if (b->bytes > b->peak)
            b->peak = b->bytes;
        evict(b);
    }
    pthread_cond_broadcast(&b->cv);
    pthread_mutex_unlock(&b->mu);
    *out = n;
    return rc;
}

static void chain_release(struct vt_atlas_build *b, struct chain_node *n)
{
    pthread_mutex_lock(&b->mu);
    if (--n->refs == 0) {
        lru_push(b, n);
        evict(b);
    }
    pthread_mutex_unlock(&b->mu);
}

static void unpin_all(struct vt_atlas_build *b, struct worker *w)
{
    for (uint32_t i = 0; i < w->pin_count; i++)
        chain_release(b, w->pins[i].node);
    w->pin_count = 0;
    w->pin_next = 0;
}

/* The chain of (e, s), pinned by worker w until unpin_all (or until PINS others are pinned). */
static int chain_get(struct vt_atlas_build *b, struct worker *w, uint32_t e, uint32_t s,
                     const struct vt_mip_chain **out, struct vt_error *err)
{
    uint64_t key = (uint64_t)e * b->nslots + s;
    for (uint32_t i = 0; i < w->pin_count; i++)
        if (w->pins[i].key == key) {
            *out = &w->pins[i].node->c;
            return 0;
        }
    struct chain_node *n = NULL;
    int rc = chain_acquire(b, e, s, &n, err);
    if (rc)
        return rc;
    uint32_t i;
    if (w->pin_count < PINS) {
        i = w->pin_count++;
    } else { /* drop the oldest pin; texel pointers into it are not kept across calls */
        i = w->pin_next;
        w->pin_next = (w->pin_next + 1) % PINS;
        chain_release(b, w->pins[i].node);
    }
    w->pins[i] = (struct pin){key, n};
    *out = &n->c;
    return 0;
}

/* ---- where texels come from ---- */

static int build_grid(struct vt_atlas_build *b, struct vt_error *err)
{
    const struct vt_layout *lay = b->lay;
    uint64_t target = lay->entry_count * 4ull < 4096 ? 4096 : lay->entry_count * 4ull;
    if (target > (1u << 22))
        target = 1u << 22;
    uint32_t s = 4;
    while (s < 30 && (uint64_t)ceil_shift(lay->width, s) * ceil_shift(lay->height, s) > target)
        s++;
    b->gshift = s;
    b->gw = ceil_shift(lay->width, s);
    b->gh = ceil_shift(lay->height, s);
    size_t nb = (size_t)b->gw * b->gh;
    b->goff = calloc(nb + 1, sizeof *b->goff);
    b->gsat = calloc(((size_t)b->gw + 1) * (b->gh + 1), sizeof *b->gsat);
    if (!b->goff || !b->gsat)
        return vt_error_set(err, VT_ERR_NOMEM, "out of memory for the atlas grid");
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t e = 0; e < lay->entry_count; e++) {
            const struct vt_layout_entry *en = &lay->entries[e];
            uint32_t ex = vt_layout_cell_x(en), ey = vt_layout_cell_y(en);
            uint32_t bx0 = ex >> s, by0 = ey >> s;
            uint32_t bx1 = (uint32_t)(((uint64_t)ex + en->cell_width - 1) >> s);
            uint32_t by1 = (uint32_t)(((uint64_t)ey + en->cell_height - 1) >> s);
            for (uint32_t by = by0; by <= by1; by++)
                for (uint32_t bx = bx0; bx <= bx1; bx++) {
                    size_t i = (size_t)by * b->gw + bx;
                    if (pass == 0)
                        b->goff[i + 1]++;
                    else
                        b->gidx[b->goff[i] + b->gsat[i]++] = e; /* gsat: fill counter here */
                }
        }
        if (pass == 0) {
            for (size_t i = 0; i < nb; i++)
                b->goff[i + 1] += b->goff[i];
            b->gidx = malloc(((size_t)b->goff[nb] + 1) * sizeof *b->gidx);
            if (!b->gidx)
                return vt_error_set(err, VT_ERR_NOMEM, "out of memory for the atlas grid");
        }
    }
    /* summed-area table of occupied buckets: sat[(y) * (gw+1) + x] = buckets in [0,x) x [0,y) */
    memset(b->gsat, 0, ((size_t)b->gw + 1) * (b->gh + 1) * sizeof *b->gsat);
    size_t sw = (size_t)b->gw + 1;
    for (uint32_t y = 0; y < b->gh; y++)
        for (uint32_t x = 0; x < b->gw; x++) {
            size_t i = (size_t)y * b->gw + x;
            uint32_t occ = b->goff[i + 1] > b->goff[i];
            b->gsat[(y + 1) * sw + x + 1] =
                occ + b->gsat[y * sw + x + 1] + b->gsat[(y + 1) * sw + x] - b->gsat[y * sw + x];
        }
    return 0;
}

/* Class of texel (X, Y) of level L: the owning entry (>= 0), CLS_EMPTY or CLS_MIXED. For an owned
 * texel, *run_end is the first X of the row past the owner's cell. */
static int32_t classify(const struct vt_atlas_build *b, uint32_t L, uint32_t X, uint32_t Y,
                        uint32_t *run_end)
{
    const struct vt_layout *lay = b->lay;
    uint64_t fx0 = (uint64_t)X << L, fy0 = (uint64_t)Y << L;
    uint64_t fx1 = ((uint64_t)X + 1) << L, fy1 = ((uint64_t)Y + 1) << L;
    fx1 = fx1 < lay->width ? fx1 : lay->width;
    fy1 = fy1 < lay->height ? fy1 : lay->height;
    uint32_t s = b->gshift;
    uint32_t bx0 = (uint32_t)(fx0 >> s), by0 = (uint32_t)(fy0 >> s);
    uint32_t bx1 = (uint32_t)((fx1 - 1) >> s), by1 = (uint32_t)((fy1 - 1) >> s);
    if (bx1 > bx0 || by1 > by0) {
        size_t sw = (size_t)b->gw + 1;
        uint32_t n = b->gsat[(by1 + 1) * sw + bx1 + 1] - b->gsat[by0 * sw + bx1 + 1] -
                     b->gsat[(by1 + 1) * sw + bx0] + b->gsat[by0 * sw + bx0];
        if (n == 0)
            return CLS_EMPTY;
    }
    for (uint32_t by = by0; by <= by1; by++)
        for (uint32_t bx = bx0; bx <= bx1; bx++) {
            size_t i = (size_t)by * b->gw + bx;
            for (uint32_t j = b->goff[i]; j < b->goff[i + 1]; j++) {
                const struct vt_layout_entry *en = &lay->entries[b->gidx[j]];
                uint64_t cx0 = vt_layout_cell_x(en), cy0 = vt_layout_cell_y(en);
                uint64_t cx1 = cx0 + en->cell_width;
                uint64_t cy1 = cy0 + en->cell_height;
                if (cx0 >= fx1 || cx1 <= fx0 || cy0 >= fy1 || cy1 <= fy0)
                    continue;
                if (L <= b->lmax[b->gidx[j]] && cx0 <= fx0 && cy0 <= fy0 && cx1 >= fx1 &&
                    cy1 >= fy1) {
                    *run_end = (uint32_t)(cx1 >> L);
                    return (int32_t)b->gidx[j];
                }
                return CLS_MIXED;
            }
        }
    return CLS_EMPTY;
}

/* Texel of owned entry e at level L, position (X, Y) clamped into the entry's chain: cell
 * padding and the gutter before x/y repeat the texture's edge. */
static int owned_texel(struct vt_atlas_build *b, struct worker *w, uint32_t s, uint32_t e,
                       uint32_t L, int64_t X, int64_t Y, const uint8_t **out, struct vt_error *err)
{
    const struct vt_mip_chain *c;
    int rc = chain_get(b, w, e, s, &c, err);
    if (rc)
        return rc;
    assert(L < c->level_count);
    const struct vt_layout_entry *en = &b->lay->entries[e];
    const struct vt_image *lv = &c->levels[L];
    int64_t i = X - (int64_t)(en->x >> L), j = Y - (int64_t)(en->y >> L);
    i = i < 0 ? 0 : i >= lv->width ? lv->width - 1 : i;
    j = j < 0 ? 0 : j >= lv->height ? lv->height - 1 : j;
    *out = vt_image_at(lv, (uint32_t)i, (uint32_t)j);
    return 0;
}

/* A mixed texel: the coverage-weighted average of its children one level down (working space,
 * premultiplied). *cov receives the covered fraction of its footprint (0..1). */
static int mixed_texel(struct vt_atlas_build *b, struct worker *w, uint32_t s, uint32_t L,
                       uint32_t X, uint32_t Y, float *out, float *cov, struct vt_error *err)
{
    const struct slot *sl = &b->slots[s];
    uint32_t ch = sl->fmt.channels;
    float sum[4] = {0, 0, 0, 0}, wsum = 0.0f;
    assert(L > 0);
    __atomic_fetch_add(&b->texels_mixed, 1, __ATOMIC_RELAXED);
    for (uint32_t d = 0; d < 4; d++) {
        uint32_t cx = 2 * X + (d & 1), cy = 2 * Y + (d >> 1), run;
        if (cx >= b->lw[L - 1] || cy >= b->lh[L - 1])
            continue;
        int32_t k = classify(b, L - 1, cx, cy, &run);
        float v[4], cw = 1.0f;
        int rc = 0;
        if (k == CLS_EMPTY)
            continue;
        if (k >= 0) {
            const uint8_t *p;
            rc = owned_texel(b, w, s, (uint32_t)k, L - 1, cx, cy, &p, err);
            if (rc == 0)
                vt_filter_to_working(&sl->mode, VTS_SAMPLE_U8, p, v, 1);
        } else {
            rc = mixed_texel(b, w, s, L - 1, cx, cy, v, &cw, err);
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

/* Writes the value of texel (X, Y) of level L whose class is k into o. */
static int texel_value(struct vt_atlas_build *b, struct worker *w, uint32_t s, uint32_t L,
                       uint32_t X, uint32_t Y, int32_t k, uint8_t *o, struct vt_error *err)
{
    const struct slot *sl = &b->slots[s];
    uint32_t ch = sl->fmt.channels;
    if (k >= 0) {
        const uint8_t *p;
        int rc = owned_texel(b, w, s, (uint32_t)k, L, X, Y, &p, err);
        if (rc == 0)
            memcpy(o, p, ch);
        return rc;
    }
    if (k == CLS_MIXED) {
        float v[4], cov;
        int rc = mixed_texel(b, w, s, L, X, Y, v, &cov, err);
        if (rc)
            return rc;
        if (cov > 0.0f) {
            vt_filter_from_working(&sl->mode, VTS_SAMPLE_U8, v, o, 1);
            return 0;
        }
    }
    memcpy(o, sl->empty_px, ch);
    return 0;
}

/* ---- tiles ---- */

/* Tiles are handed out in quadtree post-order: the four children of a tile (one level finer)
 * before the tile itself, children in Z order. Neighbouring tiles and the coarser tiles above them
 * follow each other, so the textures they read are still in the cache. */
struct frame {
    uint32_t level, tx, ty, child;
};

struct tile_run {
    struct vt_atlas_build *b;
    vt_atlas_emit_fn emit;
    void *user;
    uint64_t total, done;
    struct frame stack[VTS_MAX_LEVELS + 1];
    uint32_t depth;
    uint64_t root; /* next tile of the coarsest level to start */
};

/* Job number of a tile: its place in the index (level by level, row-major). */
static void job_tile(const struct vt_atlas_build *b, uint64_t job, uint32_t *L, uint32_t *tx,
                     uint32_t *ty)
{
    uint32_t l = 0;
    while (job >= b->first[l + 1])
        l++;
    uint64_t i = job - b->first[l];
    *L = l;
    *tx = (uint32_t)(i % b->tx[l]);
    *ty = (uint32_t)(i / b->tx[l]);
}

static bool tile_next(void *ctx, uint64_t *job)
{
    struct tile_run *r = ctx;
    const struct vt_atlas_build *b = r->b;
    uint32_t top = b->level_count - 1;
    for (;;) {
        if (r->depth == 0) {
            if (r->root >= (uint64_t)b->tx[top] * b->ty[top])
                return false;
            r->stack[r->depth++] = (struct frame){top, (uint32_t)(r->root % b->tx[top]),
                                                  (uint32_t)(r->root / b->tx[top]), 0};
            r->root++;
        }
        struct frame *f = &r->stack[r->depth - 1];
        if (f->level == 0 || f->child == 4) {
            *job = b->first[f->level] + (uint64_t)f->ty * b->tx[f->level] + f->tx;
            r->depth--;
            return true;
        }
        uint32_t d = f->child++, cx = 2 * f->tx + (d & 1), cy = 2 * f->ty + (d >> 1);
        if (cx < b->tx[f->level - 1] && cy < b->ty[f->level - 1])
            r->stack[r->depth++] = (struct frame){f->level - 1, cx, cy, 0};
    }
}

/* Classes of the tile's content texels; returns whether any is not empty. */
static bool classify_content(struct vt_atlas_build *b, struct worker *w, uint32_t L, uint32_t cx0,
                             uint32_t cy0, uint32_t cw, uint32_t chh)
{
    bool any = false;
    for (uint32_t j = 0; j < chh; j++) {
        int32_t *row = w->cls + (size_t)j * b->content;
        for (uint32_t i = 0; i < cw;) {
            uint32_t run = 0;
            int32_t k = classify(b, L, cx0 + i, cy0 + j, &run);
            uint32_t end = k >= 0 ? run - cx0 : i + 1;
            end = end < cw ? end : cw;
            any |= k != CLS_EMPTY;
            for (; i < end; i++)
                row[i] = k;
        }
    }
    return any;
}

/* Entries of one group are one surface: a border texel whose nearest content texel belongs to
 * entry k reads the group member that owns its own position, if any (else k, clamped). */
static int32_t group_owner(const struct vt_atlas_build *b, uint32_t L, int32_t k, int64_t Xn,
                           int64_t Yn, int64_t Xc, int64_t Yc)
{
    uint32_t g = b->lay->entries[k].group, run;
    if (g == 0 || (Xn == Xc && Yn == Yc))
        return k;
    int32_t k2 = classify(b, L, (uint32_t)Xn, (uint32_t)Yn, &run);
    return k2 >= 0 && b->lay->entries[k2].group == g ? k2 : k;
}

static int fill_payload(struct vt_atlas_build *b, struct worker *w, uint32_t s, uint32_t L,
                        uint32_t cx0, uint32_t cy0, uint32_t cw, uint32_t chh, struct vt_error *err)
{
    struct vt_image *p = &w->payload[s];
    uint32_t ch = b->slots[s].fmt.channels, bd = b->border;
    int64_t lw = b->lw[L], lh = b->lh[L];
    for (uint32_t j = 0; j < b->payload; j++) {
        int64_t Y = (int64_t)cy0 - bd + j;
        int64_t Yn = Y < 0 ? 0 : Y >= lh ? lh - 1 : Y;
        int64_t Yc = Yn < cy0 ? cy0 : Yn >= cy0 + chh ? cy0 + chh - 1 : Yn;
        uint8_t *o = vt_image_at(p, 0, j);
        for (uint32_t i = 0; i < b->payload; i++, o += ch) {
            int64_t X = (int64_t)cx0 - bd + i;
            int64_t Xn = X < 0 ? 0 : X >= lw ? lw - 1 : X;
            int64_t Xc = Xn < cx0 ? cx0 : Xn >= cx0 + cw ? cx0 + cw - 1 : Xn;
            int32_t k = w->cls[(size_t)(Yc - cy0) * b->content + (size_t)(Xc - cx0)];
            int rc;
            if (k >= 0) {
                const uint8_t *t;
                k = group_owner(b, L, k, Xn, Yn, Xc, Yc);
                rc = owned_texel(b, w, s, (uint32_t)k, L, Xn, Yn, &t, err);
                if (rc == 0)
                    memcpy(o, t, ch);
            } else {
                uint32_t run;
                if (Xn != Xc || Yn != Yc)
                    k = classify(b, L, (uint32_t)Xn, (uint32_t)Yn, &run);
                rc = texel_value(b, w, s, L, (uint32_t)Xn, (uint32_t)Yn, k, o, err);
            }
            if (rc)
                return rc;
        }
    }
    return 0;
}

static int tile_do(void *ctx, unsigned worker, uint64_t job, struct vt_error *err)
{
    struct tile_run *r = ctx;
    struct vt_atlas_build *b = r->b;
    struct worker *w = &b->workers[worker];
    uint32_t L, tx, ty;
    job_tile(b, job, &L, &tx, &ty);
    uint32_t cx0 = tx * b->content, cy0 = ty * b->content;
    uint32_t cw = b->lw[L] - cx0 < b->content ? b->lw[L] - cx0 : b->content;
    uint32_t chh = b->lh[L] - cy0 < b->content ? b->lh[L] - cy0 : b->content;
    int rc = 0;
    bool any = classify_content(b, w, L, cx0, cy0, cw, chh);
    if (!any)
        __atomic_fetch_add(&b->tiles_empty, 1, __ATOMIC_RELAXED);
    for (uint32_t s = 0; s < b->nslots && rc == 0; s++) {
        if (any)
            rc = fill_payload(b, w, s, L, cx0, cy0, cw, chh, err);
        if (rc == 0)
            rc = r->emit(r->user, worker, s, L, tx, ty, any ? &w->payload[s] : NULL, err);
    }
    unpin_all(b, w);
    __atomic_fetch_add(&r->done, 1, __ATOMIC_RELAXED);
    return rc;
}

static int tile_progress(void *ctx)
{
    struct tile_run *r = ctx;
    if (!r->b->o.progress)
        return 0;
    return r->b->o.progress(r->b->o.progress_user, __atomic_load_n(&r->done, __ATOMIC_RELAXED),
                            r->total);
}

int vt_atlas_build_tiles(struct vt_atlas_build *b, vt_atlas_emit_fn emit, void *user,
                         struct vt_error *err)
{
    struct tile_run r = {.b = b, .emit = emit, .user = user, .total = b->first[b->level_count]};
    struct vt_pool_fns fns = {tile_next, tile_do, tile_progress};
    return vt_pool_run(b->o.threads, &fns, &r, err);
}

int vt_atlas_build_render(struct vt_atlas_build *b, uint32_t s, uint32_t L, uint32_t x, uint32_t y,
                          struct vt_image *dst, struct vt_error *err)
{
    if (s >= b->nslots || L >= b->level_count || dst->sample != VTS_SAMPLE_U8 ||
        dst->channels != b->slots[s].fmt.channels || (uint64_t)x + dst->width > b->lw[L] ||
        (uint64_t)y + dst->height > b->lh[L])
        return vt_error_set(err, VT_ERR_ARG, "render: bad region or image");
    struct worker *w = &b->workers[b->o.threads];
    int rc = 0;
    for (uint32_t j = 0; j < dst->height && rc == 0; j++) {
        uint8_t *o = vt_image_at(dst, 0, j);
        for (uint32_t i = 0; i < dst->width && rc == 0;) {
            uint32_t run = 0;
            int32_t k = classify(b, L, x + i, y + j, &run);
            uint32_t end = k >= 0 ? run - x : i + 1;
            end = end < dst->width ? end : dst->width;
            for (; i < end && rc == 0; i++)
                rc = texel_value(b, w, s, L, x + i, y + j, k, o + (size_t)i * dst->channels, err);
        }
    }
    unpin_all(b, w);
    return rc;
}

/* ---- the texture scan and the layer formats ---- */

struct scan_run {
    struct vt_atlas_build *b;
    uint64_t next, total, done;
};

static bool scan_next(void *ctx, uint64_t *job)
{
    struct scan_run *r = ctx;
    if (r->next >= r->total)
        return false;
    *job = r->next++;
    return true;
}

static int scan_do(void *ctx, unsigned worker, uint64_t job, struct vt_error *err)
{
    struct scan_run *r = ctx;
    struct vt_atlas_build *b = r->b;
    uint32_t e = (uint32_t)(job / b->nslots), s = (uint32_t)(job % b->nslots);
    const struct vt_layout_texture *t = &b->lay->entries[e].textures[b->slots[s].layer];
    struct tex_info *ti = &b->tex[job];
    (void)worker;
    __atomic_fetch_add(&r->done, 1, __ATOMIC_RELAXED);
    if (!t->path) {
        bool grey = t->fill[0] == t->fill[1] && t->fill[1] == t->fill[2];
        *ti = (struct tex_info){(uint8_t)(grey ? 1 : 3), VTS_SAMPLE_U8, t->fill[3] >= 1.0};
        return 0;
    }
    const char *path = t->resolved ? t->resolved : t->path;
    struct vt_source src = {0};
    int rc = b->o.open(b->o.open_user, path, &src, err);
    if (rc)
        return rc;
    const struct vt_source_info *in = &src.info;
    if (in->width != t->width || in->height != t->height) {
        rc = vt_error_set(err, VT_ERR_BAD_INPUT, "'%s': %ux%u texels, but the layout says %ux%u",
                          path, in->width, in->height, t->width, t->height);
        goto out;
    }
    ti->channels = (uint8_t)in->channels;
    ti->sample = (uint8_t)in->sample;
    ti->opaque = true;
    if (in->has_alpha)
        rc = vt_source_alpha_opaque(&src, &ti->opaque, err);
out:
    vt_source_close(&src);
    return rc;
}

static int scan_progress(void *ctx)
{
    struct scan_run *r = ctx;
    if (!r->b->o.progress)
        return 0;
    return r->b->o.progress(r->b->o.progress_user, __atomic_load_n(&r->done, __ATOMIC_RELAXED),
                            r->total);
}

static void decide_formats(struct vt_atlas_build *b)
{
    for (uint32_t s = 0; s < b->nslots; s++) {
        struct slot *sl = &b->slots[s];
        bool grey = true, alpha = false;
        uint32_t converted = 0;
        for (uint32_t e = 0; e < b->lay->entry_count; e++) {
            const struct tex_info *ti = &b->tex[(size_t)e * b->nslots + s];
            grey &= ti->channels <= 2;
            alpha |= !ti->opaque;
            converted += ti->sample != VTS_SAMPLE_U8;
        }
        sl->fmt.colour = b->lay->layers[sl->layer].colour;
        sl->fmt.colour_channels = grey && sl->fmt.colour != VTS_COLOUR_NORMAL ? 1 : 3;
        sl->fmt.alpha = alpha;
        sl->fmt.channels = sl->fmt.colour_channels + (alpha ? 1u : 0u);
        sl->fmt.converted = converted;
        sl->mode = (struct vt_pixel_mode){sl->fmt.channels, sl->fmt.colour,
                                          alpha && sl->fmt.colour != VTS_COLOUR_DATA};
        memset(sl->empty_px, 0, sizeof sl->empty_px);
        if (sl->fmt.colour == VTS_COLOUR_NORMAL) { /* a flat normal, not (-1,-1,-1) */
            sl->empty_px[0] = sl->empty_px[1] = 128;
            sl->empty_px[2] = 255;
        }
    }
}

static void geometry(struct vt_atlas_build *b)
{
    const struct vt_layout *lay = b->lay;
    b->content = lay->tile_content;
    b->border = lay->border;
    b->payload = b->content + 2 * b->border;
    uint32_t full = vts_full_level_count(lay->width, lay->height, b->content);
    b->level_count = b->o.level_count && b->o.level_count < full ? b->o.level_count : full;
    if (b->level_count > VTS_MAX_LEVELS)
        b->level_count = VTS_MAX_LEVELS;
    b->first[0] = 0;
    uint32_t n = b->level_count; /* a local: the stores below may alias b->level_count */
    for (uint32_t l = 0; l < n; l++) {
        b->lw[l] = ceil_shift(lay->width, l);
        b->lh[l] = ceil_shift(lay->height, l);
        b->tx[l] = b->lw[l] / b->content + (b->lw[l] % b->content != 0);
        b->ty[l] = b->lh[l] / b->content + (b->lh[l] % b->content != 0);
        b->first[l + 1] = b->first[l] + (uint64_t)b->tx[l] * b->ty[l];
    }
}

static int alloc_tables(struct vt_atlas_build *b, struct vt_error *err)
{
    size_t n;
    uint32_t ne = b->lay->entry_count;
    if (!vt_size_mul(ne ? ne : 1, b->nslots, &n))
        return vt_error_set(err, VT_ERR_LIMIT, "too many entries");
    b->tex = calloc(n, sizeof *b->tex);
    b->table = calloc(n, sizeof *b->table);
    b->lmax = calloc(ne ? ne : 1, 1);
    b->workers = calloc((size_t)b->o.threads + 1, sizeof *b->workers);
    if (!b->tex || !b->table || !b->lmax || !b->workers)
        return vt_error_set(err, VT_ERR_NOMEM, "out of memory for the atlas tables");
    for (uint32_t e = 0; e < ne; e++)
        b->lmax[e] = (uint8_t)log2_u32(b->lay->entries[e].alignment);
    for (unsigned t = 0; t <= b->o.threads; t++) {
        struct worker *w = &b->workers[t];
        w->cls = malloc((size_t)b->content * b->content * sizeof *w->cls);
        if (!w->cls)
            return vt_error_set(err, VT_ERR_NOMEM, "out of memory for tile buffers");
    }
    return 0;
}

static int alloc_payloads(struct vt_atlas_build *b, struct vt_error *err)
{
    for (unsigned t = 0; t < b->o.threads; t++)
        for (uint32_t s = 0; s < b->nslots; s++) {
            int rc = vt_image_alloc(&b->workers[t].payload[s], b->payload, b->payload,
                                    b->slots[s].fmt.channels, VTS_SAMPLE_U8, err);
            if (rc)
                return rc;
        }
    return 0;
}

struct vt_atlas_build *vt_atlas_build_create(const struct vt_atlas_build_options *o,
                                             struct vt_error *err)
{
    if (!o->layout || !o->open || o->layer_count < 1 || o->layer_count > VT_LAYOUT_MAX_LAYERS ||
        o->threads < 1 || o->threads > 256) {
        vt_error_set(err, VT_ERR_ARG, "atlas build: bad options");
        return NULL;
    }
    struct vt_atlas_build *b = calloc(1, sizeof *b);
    if (!b) {
        vt_error_set(err, VT_ERR_NOMEM, "out of memory");
        return NULL;
    }
    b->o = *o;
    b->lay = o->layout;
    b->nslots = o->layer_count;
    b->budget = o->cache_bytes ? o->cache_bytes : 1ull << 30;
    if (!b->o.max_pixels)
        b->o.max_pixels = 1ull << 34;
    for (uint32_t s = 0; s < b->nslots; s++) {
        if (o->layers[s] >= b->lay->layer_count) {
            vt_error_set(err, VT_ERR_ARG, "atlas build: layer %u out of range", o->layers[s]);
            goto fail;
        }
        b->slots[s].layer = o->layers[s];
    }
    if (pthread_mutex_init(&b->mu, NULL)) {
        vt_error_set(err, VT_ERR_NOMEM, "cannot create a mutex");
        goto fail;
    }
    if (pthread_cond_init(&b->cv, NULL)) {
        pthread_mutex_destroy(&b->mu);
        vt_error_set(err, VT_ERR_NOMEM, "cannot create a condition variable");
        goto fail;
    }
    b->sync_ok = true;
    geometry(b);
    if (alloc_tables(b, err) || build_grid(b, err))
        goto fail;
    struct scan_run sr = {b, 0, (uint64_t)b->lay->entry_count * b->nslots, 0};
    struct vt_pool_fns fns = {scan_next, scan_do, scan_progress};
    if (sr.total && vt_pool_run(o->threads, &fns, &sr, err))
        goto fail;
    decide_formats(b);
    if (alloc_payloads(b, err))
        goto fail;
    return b;
fail:
    vt_atlas_build_destroy(b);
    return NULL;
}

void vt_atlas_build_format(const struct vt_atlas_build *b, uint32_t slot,
                           struct vt_atlas_layer_format *out)
{
    *out = b->slots[slot].fmt;
}

uint32_t vt_atlas_build_level_count(const struct vt_atlas_build *b)
{
    return b->level_count;
}

uint64_t vt_atlas_build_tile_count(const struct vt_atlas_build *b)
{
    return b->first[b->level_count];
}

void vt_atlas_build_stats(const struct vt_atlas_build *b, struct vt_atlas_build_stats *out)
{
    *out = (struct vt_atlas_build_stats){b->built, b->peak, b->tiles_empty, b->texels_mixed};
}

void vt_atlas_build_destroy(struct vt_atlas_build *b)
{
    if (!b)
        return;
    if (b->workers) {
        for (unsigned t = 0; t <= b->o.threads; t++) {
            unpin_all(b, &b->workers[t]);
            free(b->workers[t].cls);
            for (uint32_t s = 0; s < VT_LAYOUT_MAX_LAYERS; s++)
                vt_image_release(&b->workers[t].payload[s]);
        }
    }
    if (b->table) {
        size_t n = (size_t)(b->lay->entry_count ? b->lay->entry_count : 1) * b->nslots;
        for (size_t i = 0; i < n; i++)
            if (b->table[i]) {
                vt_mip_chain_release(&b->table[i]->c);
                free(b->table[i]);
            }
    }
    if (b->sync_ok) {
        pthread_mutex_destroy(&b->mu);
        pthread_cond_destroy(&b->cv);
    }
    free(b->workers);
    free(b->table);
    free(b->tex);
    free(b->lmax);
    free(b->goff);
    free(b->gidx);
    free(b->gsat);
    free(b);
}
