/* The texture pass of the atlas build (see internal/vt_atlas_build_impl.h and
 * docs/atlas-build.md): every texture file decoded once, its chains streamed into blocks. */
#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_atlas_build_impl.h"
#include "internal/vt_chain_stream.h"
#include "internal/vt_mip_chain.h"
#include "vt_checked.h"
#include "vt_error.h"
#include "vt_pool.h"
#include "vt_source.h"
#include "vts.h"

#define BAND_ROWS 16u /* texture rows decoded at a time */

struct tex_info {
    uint8_t channels, sample;
    bool has_alpha, opaque;
};

/* The keys reading one texture file (keys[first .. first + count) of the run's sorted keys). */
struct group {
    uint32_t first, count;
    uint64_t texels;
};

struct chains_run {
    struct vt_atlas_tile *t;
    const struct vt_atlas_build_options *o;
    uint32_t level_count;
    struct tex_info *tex; /* per key */
    uint32_t *keys;       /* keys with a texture file, sorted by path */
    struct group *groups;
    uint32_t ngroups, *order;        /* groups by decreasing size */
    uint64_t (*alt)[VTS_MAX_LEVELS]; /* per key of a file with alpha: ids of its chain without */
    float (*range)[2]; /* per key: smallest and largest colour value of its level 0 (wide
                          layers; each key's chain is built by one worker) */
    int phase;         /* 0 scan, 1 files with alpha, 2 the others */
    uint64_t next, done, total, decodes;
};

static uint32_t ceil_shift(uint32_t v, uint32_t k)
{
    return k >= 32 ? 1 : (uint32_t)(((uint64_t)v + (1ull << k) - 1) >> k);
}

static const struct vt_layout_texture *key_texture(const struct vt_atlas_tile *t, uint32_t key)
{
    return &t->lay->entries[key / t->nslots].textures[t->slots[key % t->nslots].layer];
}

static const char *key_path(const struct vt_atlas_tile *t, uint32_t key)
{
    const struct vt_layout_texture *x = key_texture(t, key);
    return x->resolved ? x->resolved : x->path;
}

/* ---- block ids ---- */

static int plan_chains(struct chains_run *r, struct vts_error *err)
{
    struct vt_atlas_tile *t = r->t;
    size_t nkeys = (size_t)t->lay->entry_count * t->nslots;
    t->chains = calloc(nkeys ? nkeys : 1, sizeof *t->chains);
    r->alt = calloc(nkeys ? nkeys : 1, sizeof *r->alt);
    if (!t->chains || !r->alt)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the atlas tables");
    for (size_t k = 0; k < nkeys; k++) {
        const struct vt_layout_entry *en = &t->lay->entries[k / t->nslots];
        struct vt_atlas_chain_info *ci = &t->chains[k];
        uint32_t lmax = t->lmax[k / t->nslots];
        ci->levels = lmax + 1u < r->level_count ? lmax + 1u : r->level_count;
        ci->fill = key_texture(t, (uint32_t)k)->path == NULL;
        ci->w0 = ci->fill ? 1 : en->crop_width;
        ci->h0 = ci->fill ? 1 : en->crop_height;
    }
    return 0;
}

static uint64_t level_blocks(const struct vt_atlas_chain_info *ci, uint32_t l)
{
    uint32_t w = ci->fill ? 1 : ceil_shift(ci->w0, l), h = ci->fill ? 1 : ceil_shift(ci->h0, l);
    return (uint64_t)ceil_shift(w, VT_BLOCK_CACHE_SHIFT) * ceil_shift(h, VT_BLOCK_CACHE_SHIFT);
}

/* Block ids of every chain (after the scan: a file with alpha gets a second range, for its chain
 * without alpha), and the block cache. */
static int plan_blocks(struct chains_run *r, struct vts_error *err)
{
    struct vt_atlas_tile *t = r->t;
    size_t nkeys = (size_t)t->lay->entry_count * t->nslots;
    uint64_t id = 0;
    for (size_t k = 0; k < nkeys; k++) {
        struct vt_atlas_chain_info *ci = &t->chains[k];
        for (uint32_t l = 0; l < ci->levels; l++) {
            ci->base[l] = id;
            id += level_blocks(ci, l);
        }
        for (uint32_t l = 0; r->tex[k].has_alpha && l < ci->levels; l++) {
            r->alt[k][l] = id;
            id += level_blocks(ci, l);
        }
    }
    uint64_t budget = r->o->cache_bytes ? r->o->cache_bytes : VT_ATLAS_BUILD_CACHE;
    t->blocks = vt_block_cache_create(id, budget, r->o->temp_dir, err);
    return t->blocks ? 0 : err ? err->status : VTS_ERR_NOMEM;
}

struct key_sink {
    struct vt_atlas_tile *t;
    const uint64_t *base; /* block ids of its levels */
    uint32_t key;
    size_t texel_bytes;
    float *range; /* the key's range to widen with its level 0, or NULL */
};

/* Widens ks->range with the colour channels of n texels of its chain (alpha, NaN and infinities
 * skipped). */
static void widen_range(const struct key_sink *ks, const uint8_t *px, size_t n)
{
    const struct vt_atlas_layer_format *f = &ks->t->slots[ks->key % ks->t->nslots].fmt;
    uint32_t ch = (uint32_t)(ks->texel_bytes / vts_sample_bytes(f->sample));
    struct vt_pixel_mode plain = {ch, VTS_COLOUR_DATA, false};
    float *range = ks->range;
    for (size_t i = 0; i < n; i++) {
        float v[4];
        vt_filter_to_working(&plain, f->sample, px + i * ks->texel_bytes, v, 1);
        for (uint32_t c = 0; c < f->colour_channels; c++)
            if (isfinite(v[c])) {
                range[0] = v[c] < range[0] ? v[c] : range[0];
                range[1] = v[c] > range[1] ? v[c] : range[1];
            }
    }
}

static int put_block(void *user, uint32_t level, uint32_t bx, uint32_t by, const uint8_t *px,
                     uint32_t w, uint32_t h, struct vts_error *err)
{
    struct key_sink *ks = user;
    const struct vt_atlas_chain_info *ci = &ks->t->chains[ks->key];
    uint32_t lw = ci->fill ? 1 : ceil_shift(ci->w0, level);
    uint64_t id = ks->base[level] + (uint64_t)by * ceil_shift(lw, VT_BLOCK_CACHE_SHIFT) + bx;
    if (ks->range && level == 0)
        widen_range(ks, px, (size_t)w * h);
    return vt_block_cache_put(ks->t->blocks, id, px, (size_t)w * h * ks->texel_bytes, err);
}

/* Cuts a whole chain into its blocks. */
static int put_chain(struct key_sink *ks, const struct vt_mip_chain *c, struct vts_error *err)
{
    uint8_t *block = malloc((size_t)VT_BLOCK_CACHE_EDGE * VT_BLOCK_CACHE_EDGE * 16);
    if (!block)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a texture block");
    int rc = 0;
    for (uint32_t l = 0; l < c->level_count && rc == 0; l++) {
        const struct vt_image *lv = &c->levels[l];
        size_t tb = vt_image_texel_bytes(lv);
        for (uint32_t y = 0; y < lv->height && rc == 0; y += VT_BLOCK_CACHE_EDGE)
            for (uint32_t x = 0; x < lv->width && rc == 0; x += VT_BLOCK_CACHE_EDGE) {
                uint32_t bw =
                    lv->width - x < VT_BLOCK_CACHE_EDGE ? lv->width - x : VT_BLOCK_CACHE_EDGE;
                uint32_t bh =
                    lv->height - y < VT_BLOCK_CACHE_EDGE ? lv->height - y : VT_BLOCK_CACHE_EDGE;
                for (uint32_t j = 0; j < bh; j++)
                    memcpy(block + j * bw * tb, vt_image_at(lv, x, y + j), bw * tb);
                rc = put_block(ks, l, x >> VT_BLOCK_CACHE_SHIFT, y >> VT_BLOCK_CACHE_SHIFT, block,
                               bw, bh, err);
            }
    }
    free(block);
    return rc;
}

/* ---- the chain of one key ---- */

static void key_spec(const struct chains_run *r, uint32_t key, bool alpha,
                     struct vt_mip_chain_spec *spec)
{
    const struct vt_atlas_tile *t = r->t;
    const struct vt_layout_entry *en = &t->lay->entries[key / t->nslots];
    const struct vt_atlas_layer_format *f = &t->slots[key % t->nslots].fmt;
    assert(en->crop_width && en->crop_height); /* vt_layout_check() fills them in */
    *spec = (struct vt_mip_chain_spec){.width = en->width,
                                       .height = en->height,
                                       .crop_x = en->crop_x,
                                       .crop_y = en->crop_y,
                                       .crop_width = en->crop_width,
                                       .crop_height = en->crop_height,
                                       .wrap = en->wrap,
                                       .level_count = t->chains[key].levels,
                                       .colour_channels = f->colour_channels,
                                       .alpha = alpha,
                                       .colour = f->colour,
                                       .sample = f->sample,
                                       .srgb_source = t->slots[key % t->nslots].srgb_source,
                                       .filter = r->o->filter,
                                       .max_pixels = r->o->max_pixels};
}

/* What one decode of a file feeds: per key, a stream or (when the stream cannot build its chain)
 * the whole decoded image. */
struct file_job {
    struct chains_run *r;
    struct vt_source src;
    uint32_t n;
    uint32_t *keys;
    struct vt_mip_chain_spec *spec;
    struct vt_chain_stream **cs;
    struct key_sink *sink;
    bool whole, check_alpha, opaque;
    uint64_t reserved; /* bytes of its buffers counted in the cache's budget */
};

/* Bytes the job's buffers hold outside the cache: the decoded rows, one key's converted band
 * (at most 4 channels of 4 bytes) and every stream's buffers, plus `more` expected. */
static uint64_t job_bytes(const struct file_job *j, uint32_t rows, uint64_t more)
{
    const struct vt_source_info *in = &j->src.info;
    uint64_t b = (uint64_t)in->width * rows * in->channels * vts_sample_bytes(in->sample);
    b += (uint64_t)in->width * BAND_ROWS * 16 + more;
    for (uint32_t i = 0; i < j->n; i++)
        b += j->cs[i] ? vt_chain_stream_bytes(j->cs[i]) : 0;
    return b;
}

/* Counts the job's buffers (now `bytes`) in the cache's budget; the first call may wait for the
 * other workers' buffers (vt_block_cache_reserve). */
static int job_reserve(struct file_job *j, uint64_t bytes, struct vts_error *err)
{
    if (bytes <= j->reserved)
        return 0;
    int rc = vt_block_cache_reserve(j->r->t->blocks, bytes - j->reserved, j->reserved == 0, err);
    j->reserved = bytes;
    return rc;
}

/* What the job's first bands will add: per stream, a few float bands of the texture's width
 * (conversion, output, filter scratch, kept rows); a whole decode, its chains (levels of the
 * layer's sample type, 4/3 of each crop at most 4 channels). */
static uint64_t job_expected(const struct file_job *j)
{
    uint64_t more = 0;
    for (uint32_t i = 0; i < j->n; i++) {
        const struct vt_mip_chain_spec *s = &j->spec[i];
        uint64_t ch = s->colour_channels + (s->alpha ? 1u : 0u);
        uint64_t tb = ch * vts_sample_bytes(vt_mip_chain_sample(s));
        if (j->cs[i])
            more += 4ull * BAND_ROWS * j->src.info.width * ch * sizeof(float);
        else
            more += (uint64_t)s->crop_width * s->crop_height * tb * 4 / 3;
    }
    return more;
}

/* Rows [y, y + band->height) of the file into every streamed key. */
static int feed_band(struct file_job *j, const struct vt_image *band, struct vts_error *err)
{
    if (j->check_alpha && j->opaque)
        j->opaque = vt_image_alpha_opaque(band);
    for (uint32_t i = 0; i < j->n; i++) {
        if (!j->cs[i])
            continue;
        struct vt_image conv = {0};
        int rc = vt_mip_chain_convert(&j->spec[i], &j->src.info, band, &conv, err);
        if (rc == 0)
            rc = vt_chain_stream_push(j->cs[i], &conv, err);
        vt_image_release(&conv);
        if (rc)
            return rc;
    }
    return 0;
}

static int decode_file(struct file_job *j, struct vts_error *err)
{
    const struct vt_source_info *in = &j->src.info;
    struct vt_image img = {0};
    uint32_t rows = j->whole ? in->height : BAND_ROWS < in->height ? BAND_ROWS : in->height;
    int rc = job_reserve(j, job_bytes(j, rows, job_expected(j)), err);
    if (rc == 0)
        rc = vt_image_alloc(&img, in->width, rows, in->channels, in->sample, err);
    for (uint32_t y = 0; rc == 0 && y < in->height; y += rows) {
        struct vt_image band = img;
        band.height = in->height - y < rows ? in->height - y : rows;
        rc = vt_source_read(&j->src, 0, y, &band, err);
        if (rc == 0 && j->whole) { /* streamed keys get it in bands all the same */
            for (uint32_t b = 0; rc == 0 && b < in->height; b += BAND_ROWS) {
                struct vt_image v = img;
                v.pixels = (uint8_t *)img.pixels + b * img.stride;
                v.height = in->height - b < BAND_ROWS ? in->height - b : BAND_ROWS;
                rc = feed_band(j, &v, err);
            }
        } else if (rc == 0) {
            rc = feed_band(j, &band, err);
        }
        if (rc == 0)
            rc = job_reserve(j, job_bytes(j, rows, 0), err);
    }
    for (uint32_t i = 0; rc == 0 && j->whole && i < j->n; i++) {
        if (j->cs[i])
            continue;
        struct vt_mip_chain c;
        rc = vt_mip_chain_from_image(&c, &j->spec[i], in, &img, err);
        if (rc == 0)
            rc = put_chain(&j->sink[i], &c, err);
        vt_mip_chain_release(&c);
    }
    vt_image_release(&img);
    return rc;
}

static int check_limit(const struct vt_mip_chain_spec *s, const char *path, struct vts_error *err)
{
    if ((uint64_t)s->crop_width * s->crop_height <= s->max_pixels)
        return 0;
    return vt_error_set(
        err, VTS_ERR_LIMIT,
        "'%s': the entry's crop of %ux%u texels (copies of %ux%u) exceeds the limit of %llu texels",
        path, s->crop_width, s->crop_height, s->width, s->height,
        (unsigned long long)s->max_pixels);
}

/* Decodes the file of group g once and builds the chains of its keys that this phase builds. */
static int build_group(struct chains_run *r, const struct group *g, struct vts_error *err)
{
    struct vt_atlas_tile *t = r->t;
    uint32_t n = 2 * g->count; /* phase 1: each key with and without alpha */
    struct file_job j = {.r = r, .n = 0, .opaque = true};
    j.keys = calloc(n, sizeof *j.keys);
    j.spec = calloc(n, sizeof *j.spec);
    j.cs = calloc(n, sizeof *j.cs);
    j.sink = calloc(n, sizeof *j.sink);
    int rc = j.keys && j.spec && j.cs && j.sink
                 ? 0
                 : vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a texture");
    const char *path = key_path(t, r->keys[g->first]);
    if (rc == 0)
        rc = r->o->open(r->o->open_user, path, &j.src, err);
    for (uint32_t i = 0; rc == 0 && i < n; i++) {
        uint32_t key = r->keys[g->first + i / 2];
        if (t->need && !t->need[key / t->nslots]) /* a shard: another part's entry */
            continue;
        bool alpha = i % 2 == 0 ? t->slots[key % t->nslots].fmt.alpha : false;
        if (i % 2 == 1 && r->phase != 1)
            continue;
        uint32_t k = j.n++, pre;
        j.keys[k] = key;
        key_spec(r, key, alpha, &j.spec[k]);
        j.sink[k] =
            (struct key_sink){t, i % 2 ? r->alt[key] : t->chains[key].base, key,
                              (t->slots[key % t->nslots].fmt.colour_channels + alpha) *
                                  vts_sample_bytes(t->slots[key % t->nslots].fmt.sample),
                              t->slots[key % t->nslots].fmt.has_range ? r->range[key] : NULL};
        if ((rc = check_limit(&j.spec[k], path, err)) != 0)
            break;
        if (vt_chain_stream_fits(&j.spec[k], j.src.info.width, j.src.info.height, &pre))
            j.cs[k] = vt_chain_stream_create(&j.spec[k], j.src.info.width, j.src.info.height,
                                             put_block, &j.sink[k], err);
        else
            j.whole = true;
        if (j.cs[k] == NULL && !j.whole)
            rc = err ? err->status : VTS_ERR_NOMEM;
    }
    j.check_alpha = r->phase == 1; /* (a shard decodes a file it needs no chain of for that) */
    if (rc == 0 && (j.n || j.check_alpha)) {
        __atomic_fetch_add(&r->decodes, 1, __ATOMIC_RELAXED);
        rc = decode_file(&j, err);
    }
    if (rc == 0 && j.check_alpha)
        for (uint32_t i = 0; i < g->count; i++)
            r->tex[r->keys[g->first + i]].opaque = j.opaque;
    for (uint32_t i = 0; i < j.n; i++)
        vt_chain_stream_destroy(j.cs[i]);
    if (j.reserved)
        vt_block_cache_unreserve(t->blocks, j.reserved);
    vt_source_close(&j.src);
    free(j.keys);
    free(j.spec);
    free(j.cs);
    free(j.sink);
    return rc;
}

/* The file's size against every texture record naming it, and what it holds. */
static int scan_group(struct chains_run *r, const struct group *g, struct vts_error *err)
{
    const char *path = key_path(r->t, r->keys[g->first]);
    struct vt_source src = {0};
    int rc = r->o->open(r->o->open_user, path, &src, err);
    if (rc)
        return rc;
    const struct vt_source_info *in = &src.info;
    for (uint32_t i = 0; rc == 0 && i < g->count; i++) {
        uint32_t key = r->keys[g->first + i];
        const struct vt_layout_texture *x = key_texture(r->t, key);
        if (in->width != x->width || in->height != x->height)
            rc = vt_error_set(err, VTS_ERR_BAD_INPUT,
                              "'%s': %ux%u texels, but the layout says %ux%u", path, in->width,
                              in->height, x->width, x->height);
        r->tex[key] =
            (struct tex_info){(uint8_t)in->channels, (uint8_t)in->sample, in->has_alpha, true};
    }
    vt_source_close(&src);
    return rc;
}

/* ---- the pool ---- */

static bool group_in_phase(const struct chains_run *r, const struct group *g)
{
    bool alpha = r->tex[r->keys[g->first]].has_alpha;
    if (r->phase == 0)
        return true;
    if (r->phase == 1)
        return alpha;
    if (r->phase == 2 && !alpha && r->t->need) { /* a shard: files of its part only */
        for (uint32_t i = 0; i < g->count; i++)
            if (r->t->need[r->keys[g->first + i] / r->t->nslots])
                return true;
        return false;
    }
    if (r->phase == 2)
        return !alpha;
    return false;
}

static bool chains_next(void *ctx, uint64_t *job)
{
    struct chains_run *r = ctx;
    while (r->next < r->ngroups) {
        uint32_t g = r->order[r->next++];
        if (group_in_phase(r, &r->groups[g])) {
            *job = g;
            return true;
        }
    }
    return false;
}

static int chains_do(void *ctx, unsigned worker, uint64_t job, struct vts_error *err)
{
    struct chains_run *r = ctx;
    const struct group *g = &r->groups[job];
    (void)worker;
    int rc = r->phase == 0 ? scan_group(r, g, err) : build_group(r, g, err);
    if (r->phase != 0)
        __atomic_fetch_add(&r->done, g->count, __ATOMIC_RELAXED);
    return rc;
}

static int chains_progress(void *ctx)
{
    struct chains_run *r = ctx;
    if (!r->o->progress)
        return 0;
    return r->o->progress(r->o->progress_user, __atomic_load_n(&r->done, __ATOMIC_RELAXED),
                          r->total);
}

static int run_phase(struct chains_run *r, int phase, struct vts_error *err)
{
    r->phase = phase;
    r->next = 0;
    struct vt_pool_fns fns = {chains_next, chains_do, chains_progress};
    return r->ngroups ? vt_pool_run(r->o->threads, &fns, r, err) : 0;
}

/* ---- formats ---- */

static void decide_formats(struct chains_run *r, bool final)
{
    struct vt_atlas_tile *t = r->t;
    for (uint32_t s = 0; s < t->nslots; s++) {
        struct vt_atlas_tile_slot *sl = &t->slots[s];
        bool grey = true, alpha = false;
        for (uint32_t e = 0; e < t->lay->entry_count; e++) {
            const struct tex_info *ti = &r->tex[(size_t)e * t->nslots + s];
            grey &= ti->channels <= 2;
            alpha |= !ti->opaque || (!final && ti->has_alpha);
        }
        /* texture files by sample type: each file once (a group is one file) */
        memset(sl->fmt.textures, 0, sizeof sl->fmt.textures);
        for (uint32_t g = 0; g < r->ngroups; g++) {
            const struct group *gr = &r->groups[g];
            for (uint32_t i = 0; i < gr->count; i++) {
                uint32_t key = r->keys[gr->first + i];
                if (key % t->nslots != s)
                    continue;
                uint8_t sample = r->tex[key].sample;
                if (sample >= VTS_SAMPLE_U8 && sample <= VTS_SAMPLE_F32)
                    sl->fmt.textures[sample - 1]++;
                break;
            }
        }
        const uint32_t *n = sl->fmt.textures;
        uint32_t sample = VTS_SAMPLE_U8;
        if (n[VTS_SAMPLE_F32 - 1] || (n[VTS_SAMPLE_F16 - 1] && n[VTS_SAMPLE_U16 - 1]))
            sample = VTS_SAMPLE_F32;
        else if (n[VTS_SAMPLE_F16 - 1])
            sample = VTS_SAMPLE_F16;
        else if (n[VTS_SAMPLE_U16 - 1])
            sample = VTS_SAMPLE_U16;
        bool is_float = sample == VTS_SAMPLE_F16 || sample == VTS_SAMPLE_F32;
        uint32_t colour = t->lay->layers[sl->layer].colour;
        sl->srgb_source = is_float && colour == VTS_COLOUR_SRGB;
        sl->fmt.colour = sl->srgb_source ? VTS_COLOUR_LINEAR : colour;
        sl->fmt.sample = sample;
        /* the range of the values a viewer maps (docs/atlas-build.md): float and linear u16 */
        sl->fmt.has_range = is_float || (sample == VTS_SAMPLE_U16 && colour != VTS_COLOUR_SRGB);
        sl->fmt.colour_channels = grey && sl->fmt.colour != VTS_COLOUR_NORMAL ? 1 : 3;
        sl->fmt.alpha = alpha;
        sl->fmt.channels = sl->fmt.colour_channels + (alpha ? 1u : 0u);
        vt_atlas_slot_derive(sl);
    }
}

void vt_atlas_slot_derive(struct vt_atlas_tile_slot *sl)
{
    uint32_t sample = sl->fmt.sample;
    sl->texel_bytes = (size_t)sl->fmt.channels * vts_sample_bytes(sample);
    sl->mode = (struct vt_pixel_mode){sl->fmt.channels, sl->fmt.colour,
                                      sl->fmt.alpha && sl->fmt.colour != VTS_COLOUR_DATA};
    memset(sl->empty_px, 0, sizeof sl->empty_px);
    if (sl->fmt.colour == VTS_COLOUR_NORMAL && sample == VTS_SAMPLE_U8) {
        sl->empty_px[0] = sl->empty_px[1] = 128; /* a flat normal, not (-1,-1,-1) */
        sl->empty_px[2] = 255;
    } else if (sl->fmt.colour == VTS_COLOUR_NORMAL) { /* (0, 0, 1), alpha 0 */
        const float flat[4] = {0.0f, 0.0f, 1.0f, 0.0f};
        vt_filter_from_working(&sl->mode, sample, flat, sl->empty_px, 1);
    }
}

/* After phase 1: each key of a file with alpha keeps the chain its layer's format calls for. */
static void drop_unused(struct chains_run *r)
{
    struct vt_atlas_tile *t = r->t;
    size_t nkeys = (size_t)t->lay->entry_count * t->nslots;
    for (size_t k = 0; k < nkeys; k++) {
        struct vt_atlas_chain_info *ci = &t->chains[k];
        if (!r->tex[k].has_alpha)
            continue;
        bool alpha = t->slots[k % t->nslots].fmt.alpha;
        for (uint32_t l = 0; l < ci->levels; l++) {
            uint64_t keep = alpha ? ci->base[l] : r->alt[k][l];
            uint64_t drop = alpha ? r->alt[k][l] : ci->base[l];
            for (uint64_t b = 0; b < level_blocks(ci, l); b++)
                vt_block_cache_drop(t->blocks, drop + b);
            ci->base[l] = keep;
        }
    }
}

/* ---- keys grouped by file ---- */

struct path_key {
    const char *path;
    uint32_t key;
};

static int by_path(const void *a, const void *b)
{
    const struct path_key *x = a, *y = b;
    int c = strcmp(x->path, y->path);
    return c ? c : (x->key > y->key) - (x->key < y->key);
}

struct size_group {
    uint64_t texels;
    uint32_t group;
};

static int by_size(const void *a, const void *b)
{
    const struct size_group *x = a, *y = b;
    if (x->texels != y->texels)
        return x->texels < y->texels ? 1 : -1;
    return (x->group > y->group) - (x->group < y->group);
}

static int group_keys(struct chains_run *r, struct vts_error *err)
{
    struct vt_atlas_tile *t = r->t;
    size_t nkeys = (size_t)t->lay->entry_count * t->nslots, n = 0;
    r->keys = malloc((nkeys ? nkeys : 1) * sizeof *r->keys);
    r->groups = malloc((nkeys ? nkeys : 1) * sizeof *r->groups);
    r->order = malloc((nkeys ? nkeys : 1) * sizeof *r->order);
    if (!r->keys || !r->groups || !r->order)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the atlas tables");
    struct path_key *pk = malloc((nkeys ? nkeys : 1) * sizeof *pk);
    struct size_group *sg = malloc((nkeys ? nkeys : 1) * sizeof *sg);
    if (!pk || !sg) {
        free(pk);
        free(sg);
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the atlas tables");
    }
    for (size_t k = 0; k < nkeys; k++)
        if (!t->chains[k].fill)
            pk[n++] = (struct path_key){key_path(t, (uint32_t)k), (uint32_t)k};
    qsort(pk, n, sizeof *pk, by_path);
    r->ngroups = 0;
    for (size_t i = 0; i < n; i++) {
        const struct vt_layout_texture *x = key_texture(t, pk[i].key);
        r->keys[i] = pk[i].key;
        if (i == 0 || strcmp(pk[i - 1].path, pk[i].path) != 0)
            r->groups[r->ngroups++] = (struct group){(uint32_t)i, 0, 0};
        struct group *g = &r->groups[r->ngroups - 1];
        g->count++;
        g->texels = (uint64_t)x->width * x->height;
    }
    for (uint32_t g = 0; g < r->ngroups; g++)
        sg[g] = (struct size_group){r->groups[g].texels, g};
    qsort(sg, r->ngroups, sizeof *sg, by_size);
    for (uint32_t g = 0; g < r->ngroups; g++)
        r->order[g] = sg[g].group;
    free(pk);
    free(sg);
    r->total = n;
    return 0;
}

/* ---- the pass ---- */

/* Fills: one texel per level, the layer's final format. */
static int build_fills(struct chains_run *r, struct vts_error *err)
{
    struct vt_atlas_tile *t = r->t;
    size_t nkeys = (size_t)t->lay->entry_count * t->nslots;
    int rc = 0;
    for (size_t k = 0; k < nkeys && rc == 0; k++) {
        if (!t->chains[k].fill)
            continue;
        struct vt_mip_chain_spec spec;
        struct vt_mip_chain c;
        key_spec(r, (uint32_t)k, t->slots[k % t->nslots].fmt.alpha, &spec);
        rc = vt_mip_chain_from_fill(&c, &spec, key_texture(t, (uint32_t)k)->fill, err);
        struct key_sink ks = {t, t->chains[k].base, (uint32_t)k,
                              t->slots[k % t->nslots].texel_bytes,
                              t->slots[k % t->nslots].fmt.has_range ? r->range[k] : NULL};
        if (rc == 0)
            rc = put_chain(&ks, &c, err);
        vt_mip_chain_release(&c);
    }
    return rc;
}

int vt_atlas_chains_build(struct vt_atlas_tile *t, const struct vt_atlas_build_options *o,
                          uint32_t level_count, uint64_t *decodes, struct vts_error *err)
{
    struct chains_run r = {.t = t, .o = o, .level_count = level_count};
    size_t nkeys = (size_t)t->lay->entry_count * t->nslots;
    r.tex = calloc(nkeys ? nkeys : 1, sizeof *r.tex);
    r.range = malloc((nkeys ? nkeys : 1) * sizeof *r.range);
    int rc = r.tex && r.range
                 ? 0
                 : vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the atlas tables");
    for (size_t k = 0; rc == 0 && k < nkeys; k++)
        r.range[k][0] = INFINITY, r.range[k][1] = -INFINITY;
    if (rc == 0)
        rc = plan_chains(&r, err);
    if (rc == 0)
        rc = group_keys(&r, err);
    for (size_t k = 0; rc == 0 && k < nkeys; k++)
        if (t->chains[k].fill) {
            const double *f = key_texture(t, (uint32_t)k)->fill;
            bool grey = f[0] == f[1] && f[1] == f[2];
            r.tex[k] =
                (struct tex_info){(uint8_t)(grey ? 1 : 3), VTS_SAMPLE_U8, false, f[3] >= 1.0};
        }
    if (rc == 0)
        rc = run_phase(&r, 0, err);
    if (rc == 0)
        rc = plan_blocks(&r, err);
    /* files with alpha first, their chains built with and without alpha from one decode: the
     * decode tells whether the layer needs alpha, and the other chain is dropped */
    if (rc == 0) {
        decide_formats(&r, false);
        rc = run_phase(&r, 1, err);
    }
    if (rc == 0) {
        decide_formats(&r, true);
        drop_unused(&r);
        rc = run_phase(&r, 2, err);
    }
    if (rc == 0)
        rc = build_fills(&r, err);
    for (uint32_t s = 0; rc == 0 && s < t->nslots; s++) {
        struct vt_atlas_layer_format *f = &t->slots[s].fmt;
        f->range[0] = INFINITY, f->range[1] = -INFINITY;
        for (size_t k = s; f->has_range && k < nkeys; k += t->nslots) {
            f->range[0] = r.range[k][0] < f->range[0] ? r.range[k][0] : f->range[0];
            f->range[1] = r.range[k][1] > f->range[1] ? r.range[k][1] : f->range[1];
        }
        f->has_range = f->has_range && f->range[0] <= f->range[1];
    }
    *decodes = r.decodes;
    free(r.tex);
    free(r.alt);
    free(r.range);
    free(r.keys);
    free(r.groups);
    free(r.order);
    return rc;
}
