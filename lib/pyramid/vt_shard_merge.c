/* Merging shards: the complete set, the metadata it drops, the resumed build (see
 * vt_shard_merge.h). */
#include "vt_shard_merge.h"
#include <math.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_shard_seams.h"
#include "vt_error.h"

/* ---- tiles ---- */

int vt_shard_merge_read(const struct vt_shard_merge *m, int k, uint32_t layer, uint32_t level,
                        uint32_t tx, uint32_t ty, void *buf, size_t capacity, size_t *len,
                        struct vts_error *err)
{
    struct vts_error why = {0};
    int rc = vts_store_read(m->stores[k], layer, level, tx, ty, buf, capacity, len, 0, &why);
    if (rc == 0)
        return 0;
    return vt_error_set(err, rc, "'%s': layer %u level %u tile %u,%u: %s", m->names[k], layer,
                        level, tx, ty,
                        rc == VTS_ERR_CHECKSUM ? "payload checksum mismatch" : why.message);
}

int vt_shard_merge_tile(const struct vt_shard_merge *m, uint64_t index, uint32_t layer,
                        uint32_t level, uint32_t tx, uint32_t ty, unsigned char *const buf[2],
                        size_t capacity, int *owner, size_t *len, struct vts_error *err)
{
    int rc = 0;
    size_t other_len = 0;
    *owner = -1;
    *len = 0;
    for (int k = 0; k < m->count && rc == 0; k++) {
        const struct vts_tile_entry *e = vts_store_entry(m->stores[k], index);
        other_len = 0;
        if (e->length == 0)
            continue;
        if (*owner < 0) {
            *owner = k;
            rc = vt_shard_merge_read(m, k, layer, level, tx, ty, buf[0], capacity, len, err);
            continue;
        }
        if (e->length == *len && e->crc32c == vts_store_entry(m->stores[*owner], index)->crc32c)
            rc = vt_shard_merge_read(m, k, layer, level, tx, ty, buf[1], capacity, &other_len, err);
        if (rc == 0 && (other_len != *len || memcmp(buf[0], buf[1], *len) != 0))
            rc = vt_error_set(
                err, VTS_ERR_BAD_INPUT,
                "tile %u,%u of level %u, layer %u, is stored in both '%s' and '%s' with different bytes",
                tx, ty, level, layer, m->names[*owner], m->names[k]);
    }
    return rc;
}

/* ---- plain shard sets: shard=I/N ---- */

bool vt_shard_merge_drops_key(const char *key, bool vt_tiles_build)
{
    return strcmp(key, VT_SHARD_KEY) == 0 ||
           (vt_tiles_build && strncmp(key, VT_SHARD_KEY ".", sizeof VT_SHARD_KEY) == 0);
}

/* The keys whose values differ between the shards of one build: the shard key, and an atlas
 * shard's value range (of the textures it read; the merge writes their union). */
static bool per_shard_key(const char *key)
{
    return strcmp(key, VT_SHARD_KEY) == 0 || strcmp(key, VT_SHARD_RANGE_KEY) == 0;
}

/* Index of the first metadata entry at or after i that is not a per-shard key. */
static uint32_t skip_shard_key(const struct vts_store *s, uint32_t i)
{
    while (i < vts_store_meta_count(s) && per_shard_key(vts_store_meta_key(s, i)))
        i++;
    return i;
}

/* Widens [lo, hi] with one "MIN:MAX" item of a range list; false when it is not one. */
static bool widen_item(const char *item, size_t len, float *lo, float *hi)
{
    char buf[64], tail[2];
    float a, b;
    if (len == 0 || len >= sizeof buf)
        return false;
    memcpy(buf, item, len);
    buf[len] = '\0';
    if (sscanf(buf, "%f:%f%1s", &a, &b, tail) != 2 || !(a <= b))
        return false;
    *lo = a < *lo ? a : *lo;
    *hi = b > *hi ? b : *hi;
    return true;
}

int vt_shard_merge_range(const struct vt_shard_merge *m, char *out, size_t cap)
{
    float lo[VTS_MAX_LAYERS], hi[VTS_MAX_LAYERS];
    uint32_t items = 0;
    for (int k = 0; k < m->count; k++) {
        const char *v = vts_store_meta_find(m->stores[k], VT_SHARD_RANGE_KEY);
        if (!v)
            return -1;
        uint32_t n = 0;
        for (const char *p = v;; n++) {
            size_t len = strcspn(p, ",");
            if (n >= VTS_MAX_LAYERS || (k > 0 && n >= items))
                return -1;
            if (k == 0)
                lo[n] = INFINITY, hi[n] = -INFINITY;
            if (!(len == 1 && *p == '-') && !widen_item(p, len, &lo[n], &hi[n]))
                return -1;
            if (p[len] == '\0')
                break;
            p += len + 1;
        }
        if (k > 0 && n + 1 != items)
            return -1;
        items = n + 1;
    }
    size_t used = 0;
    bool any = false;
    out[0] = '\0';
    for (uint32_t i = 0; i < items; i++) {
        int w = lo[i] <= hi[i] ? snprintf(out + used, cap - used, "%s%.9g:%.9g", i ? "," : "",
                                          (double)lo[i], (double)hi[i])
                               : snprintf(out + used, cap - used, "%s-", i ? "," : "");
        if (w < 0 || (size_t)w >= cap - used)
            return -1;
        used += (size_t)w;
        any |= lo[i] <= hi[i];
    }
    return any ? 1 : 0;
}

/* True when a and b have the same metadata, in the same order, apart from the shard key. */
static bool same_metadata_but_shard(const struct vts_store *a, const struct vts_store *b)
{
    uint32_t i = skip_shard_key(a, 0), j = skip_shard_key(b, 0);
    for (; i < vts_store_meta_count(a) && j < vts_store_meta_count(b);
         i = skip_shard_key(a, i + 1), j = skip_shard_key(b, j + 1))
        if (strcmp(vts_store_meta_key(a, i), vts_store_meta_key(b, j)) != 0 ||
            strcmp(vts_store_meta_value(a, i), vts_store_meta_value(b, j)) != 0)
            return false;
    return i >= vts_store_meta_count(a) && j >= vts_store_meta_count(b);
}

bool vt_shard_merge_is_single_build(const struct vt_shard_merge *m)
{
    int n = m->count;
    bool *seen = calloc((size_t)n, sizeof *seen);
    bool ok = seen != NULL;
    for (int k = 0; ok && k < n; k++) {
        const char *v = vts_store_meta_find(m->stores[k], VT_SHARD_KEY);
        char tail[2];
        uint32_t i = 0, count = 0;
        ok = v && sscanf(v, "%u/%u%1s", &i, &count, tail) == 2 && count == (uint32_t)n && i >= 1 &&
             i <= count && !seen[i - 1] && same_metadata_but_shard(m->stores[0], m->stores[k]);
        if (ok)
            seen[i - 1] = true;
    }
    free(seen);
    return ok;
}

/* ---- shards of vt-tiles --shard: the complete set ---- */

/* The first metadata key (not the shard key) whose value differs between a and b, or NULL. */
static const char *metadata_difference(const struct vts_store *a, const struct vts_store *b)
{
    const struct vts_store *s[2] = {a, b};
    for (int t = 0; t < 2; t++)
        for (uint32_t i = 0; i < vts_store_meta_count(s[t]); i++) {
            const char *key = vts_store_meta_key(s[t], i),
                       *other = vts_store_meta_find(s[1 - t], key);
            if (!per_shard_key(key) &&
                (!other || strcmp(other, vts_store_meta_value(s[t], i)) != 0))
                return key;
        }
    return NULL;
}

/* Checks input k against the first one (shard count, a shard given twice, another build) and
 * records it as the owner of its index. */
static int check_shard(const struct vt_shard_merge *m, int k, uint32_t index, uint32_t c,
                       uint32_t count, int *owner, struct vts_error *err)
{
    const char *key = metadata_difference(m->stores[0], m->stores[k]);
    if (c != count)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "'%s' is shard %u/%u but '%s' is a shard of %u: not one build",
                            m->names[k], index, c, m->names[0], count);
    if (owner[index - 1] >= 0)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "shard %u/%u is given twice: '%s' and '%s'",
                            index, c, m->names[owner[index - 1]], m->names[k]);
    if (key) {
        const char *va = vts_store_meta_find(m->stores[k], key);
        const char *vb = vts_store_meta_find(m->stores[0], key);
        return vt_error_set(
            err, VTS_ERR_BAD_INPUT,
            "'%s' (shard %u/%u) is from another build: its %s is '%s', not '%s' as in '%s'",
            m->names[k], index, c, key, va ? va : "(none)", vb ? vb : "(none)", m->names[0]);
    }
    owner[index - 1] = k;
    return 0;
}

int vt_shard_merge_check(const struct vt_shard_merge *m, struct vts_error *err)
{
    int n = m->count, with = 0, rc = 0;
    while (with + 1 < n && !vts_store_meta_find(m->stores[with], VT_SHARD_BUILD_KEY))
        with++;
    uint32_t count = 0, index = 0, c = 0;
    int *owner = NULL;
    for (int k = 0; k < n && rc == 0; k++) {
        const char *v = vts_store_meta_find(m->stores[k], VT_SHARD_KEY);
        if (!vts_store_meta_find(m->stores[k], VT_SHARD_BUILD_KEY) ||
            vt_shard_parse(v, &index, &c)) {
            rc = vt_error_set(
                err, VTS_ERR_BAD_INPUT,
                "'%s' is not a shard of vt-tiles --shard (no %s metadata), unlike '%s'",
                m->names[k], VT_SHARD_BUILD_KEY, m->names[with]);
            break;
        }
        if (k == 0) {
            count = c;
            if (!(owner = malloc(count * sizeof *owner)))
                return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
            for (uint32_t i = 0; i < count; i++)
                owner[i] = -1;
        }
        rc = check_shard(m, k, index, c, count, owner, err);
    }
    uint32_t missing = 0, first = 0;
    for (uint32_t i = 0; rc == 0 && i < count; i++)
        if (owner[i] < 0 && missing++ == 0)
            first = i + 1;
    if (rc == 0 && missing)
        rc = vt_error_set(
            err, VTS_ERR_BAD_INPUT,
            "shard %u/%u is missing%s%.0u%s: merge all %u shards of a vt-tiles --shard build at once",
            first, count, missing > 1 ? " (and " : "", missing > 1 ? missing - 1 : 0,
            missing > 1 ? " more)" : "", count);
    free(owner);
    return rc;
}

/* ---- shards of vt-tiles --shard: the levels above them ---- */

int vt_shard_merge_options(const struct vt_shard_merge *m, struct vt_pyramid_options *o,
                           struct vt_source_info *input, struct vt_shard_build *build,
                           struct vts_error *err)
{
    const struct vts_store *s0 = m->stores[0];
    const struct vts_geometry *g = vts_store_geometry(s0);
    const struct vts_layer *L = vts_store_layer(s0, 0), *F = vts_store_layer(s0, 1);
    const char *filter_name = vts_store_meta_find(s0, "filter");
    enum vt_filter_kind filter;
    if (g->layer_count != 2 || strncmp(F->name, VT_SHARD_LAYER_NAME, VTS_LAYER_NAME_BYTES) != 0 ||
        F->codec != VTS_CODEC_RAW || F->sample != VTS_SAMPLE_F32 ||
        vt_shard_build_parse(vts_store_meta_find(s0, VT_SHARD_BUILD_KEY), build) ||
        F->channels != build->channels || !filter_name || vt_filter_parse(filter_name, &filter) ||
        (build->seams && (g->flags & VTS_STORE_WRAP_X) != 0))
        return vt_error_set(
            err, VTS_ERR_BAD_INPUT,
            "'%s': not a well-formed vt-tiles shard (layer table, %s or filter metadata)",
            m->names[0], VT_SHARD_BUILD_KEY);
    *input = (struct vt_source_info){.width = g->width,
                                     .height = g->height,
                                     .channels = build->channels,
                                     .sample = VTS_SAMPLE_F32,
                                     .colour = L->colour,
                                     .has_alpha = build->has_alpha,
                                     .premultiplied = build->premultiplied};
    *o = (struct vt_pyramid_options){.width = g->width,
                                     .height = g->height,
                                     .tile_content_px = g->tile_content_px,
                                     .border_px = g->border_px,
                                     .level_count = g->level_count,
                                     .filter = filter,
                                     .colour = L->colour,
                                     .wrap = (g->flags & VTS_STORE_WRAP_X) != 0,
                                     .out_channels = L->channels,
                                     .out_sample = L->sample,
                                     .levels_per_pass = build->levels_per_pass,
                                     .resume_input = input};
    return 0;
}

/* Reading the carried tiles: a buffer for any payload of the inputs. */
struct carried_reader {
    const struct vt_shard_merge *m;
    uint32_t level, channels;
    unsigned char *payload;
    size_t capacity;
    int *part_input; /* seams: input of each part (column + row * columns) */
    uint32_t columns;
};

/* Reads carried payload (level, tx, ty) of input k, which must hold width x height texels, into
 * texels. */
static int read_payload(const struct carried_reader *c, int k, uint32_t level, uint32_t tx,
                        uint32_t ty, uint32_t width, uint32_t height, float *texels, size_t stride,
                        struct vts_error *err)
{
    const struct vt_shard_merge *m = c->m;
    size_t len = 0, want = (size_t)width * height * c->channels * 4;
    int rc = vt_shard_merge_read(m, k, 1, level, tx, ty, c->payload, c->capacity, &len, err);
    if (rc)
        return rc;
    if (len != want)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "'%s': carried tile %u,%u of level %u has %zu bytes, not %zu",
                            m->names[k], tx, ty, level, len, want);
    for (uint32_t y = 0; y < height; y++)
        vt_shard_unpack_row(c->payload, width, c->channels, y, texels + y * stride);
    return 0;
}

/* vt_pyramid_level_fn over the shards: tile (tx, ty) of the carried layer, from the first input
 * that stores it. */
static int read_carried(void *user, uint32_t tx, uint32_t ty, uint32_t width, uint32_t height,
                        float *texels, size_t stride, struct vts_error *err)
{
    const struct carried_reader *c = user;
    const struct vt_shard_merge *m = c->m;
    int owner = -1, rc = 0;
    struct vts_tile_entry e;
    for (int i = 0; i < m->count && owner < 0; i++) {
        if ((rc = vts_store_tile(m->stores[i], 1, c->level, tx, ty, &e, err)) != 0)
            return rc;
        if (e.length)
            owner = i;
    }
    if (owner < 0)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "no shard holds the carried texels of tile %u,%u of level %u", tx, ty,
                            c->level);
    return read_payload(c, owner, c->level, tx, ty, width, height, texels, stride, err);
}

static int alloc_payload(const struct vt_shard_merge *m, struct carried_reader *c,
                         struct vts_error *err)
{
    for (int i = 0; i < m->count; i++)
        if (vts_store_max_payload(m->stores[i]) > c->capacity)
            c->capacity = vts_store_max_payload(m->stores[i]);
    if (!(c->payload = malloc(c->capacity + 1)))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for tile buffers");
    return 0;
}

struct vt_pyramid_resume *vt_shard_merge_assemble(const struct vt_shard_merge *m,
                                                  const struct vt_pyramid_options *o,
                                                  struct vts_error *err)
{
    struct vt_pyramid_plan plan;
    vt_pyramid_plan(o, &plan);
    struct carried_reader c = {
        .m = m, .level = plan.levels_per_pass, .channels = o->resume_input->channels};
    if (alloc_payload(m, &c, err) != 0)
        return NULL;
    struct vt_pyramid_resume *r = vt_pyramid_resume_create(o, read_carried, &c, err);
    free(c.payload);
    return r;
}

/* ---- shards of vt-tiles --shard without wrap: the seams ---- */

/* vt_seams_read_fn over the shards: the input of the part. */
static int read_seam(void *user, uint32_t col, uint32_t row, uint32_t level, uint32_t tx,
                     uint32_t ty, const struct vt_seams_rect *r, float *texels, size_t stride,
                     struct vts_error *err)
{
    const struct carried_reader *c = user;
    int k = c->part_input[col + row * c->columns];
    return read_payload(c, k, level, tx, ty, r->width, r->height, texels, stride, err);
}

/* The seams of the build, and (part_input not NULL) the input of each part. */
static struct vt_seams *merge_seams(const struct vt_shard_merge *m,
                                    const struct vt_pyramid_options *o, int **part_input,
                                    uint32_t *columns, struct vts_error *err)
{
    struct vt_pyramid_plan plan;
    uint32_t xcuts[65], ycuts[65], gx, gy, index, count;
    vt_pyramid_plan(o, &plan);
    if (!vt_pyramid_part_cuts(&plan, (uint32_t)m->count, xcuts, &gx, ycuts, &gy)) {
        vt_error_set(err, VTS_ERR_BAD_INPUT, "%d shards: not a power of two", m->count);
        return NULL;
    }
    if (part_input) {
        if (!(*part_input = malloc((size_t)m->count * sizeof **part_input))) {
            vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
            return NULL;
        }
        for (int k = 0; k < m->count; k++) /* vt_shard_merge_check() made sure of these */
            if (vt_shard_parse(vts_store_meta_find(m->stores[k], VT_SHARD_KEY), &index, &count) ==
                    0 &&
                index <= (uint32_t)m->count)
                (*part_input)[index - 1] = k;
        *columns = gx;
    }
    return vt_seams_create(o, o->resume_input, xcuts, gx, ycuts, gy, err);
}

uint64_t vt_shard_merge_seam_tiles(const struct vt_shard_merge *m,
                                   const struct vt_pyramid_options *o)
{
    struct vt_seams *s = merge_seams(m, o, NULL, NULL, NULL);
    uint64_t n = s ? vt_seams_tile_count(s, UINT32_MAX, UINT32_MAX) : 0;
    vt_seams_destroy(s);
    return n;
}

int vt_shard_merge_seams(const struct vt_shard_merge *m, const struct vt_pyramid_options *o,
                         struct vts_error *err)
{
    struct vt_pyramid_plan plan;
    vt_pyramid_plan(o, &plan);
    struct carried_reader c = {
        .m = m, .level = plan.levels_per_pass, .channels = o->resume_input->channels};
    struct vt_seams *s = merge_seams(m, o, &c.part_input, &c.columns, err);
    int rc = s ? alloc_payload(m, &c, err) : (err ? err->status : VTS_ERR_NOMEM);
    if (rc == 0)
        rc = vt_seams_merge_run(s, read_seam, &c, err);
    vt_seams_destroy(s);
    free(c.part_input);
    free(c.payload);
    return rc;
}
