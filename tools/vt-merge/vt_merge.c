/* vt-merge, shards of `vt-tiles --shard`: checks that the inputs are one complete shard set, then
 * builds the levels above the shards from their carried float texels with the single build's
 * options, so that the output is the single build byte for byte (docs/sharding.md). */
#include <stdlib.h>
#include <string.h>

#include "vt_error.h"
#include "vt_float_file.h"
#include "vt_merge.h"
#include "vt_pool.h"
#include "vt_pyramid.h"
#include "vt_shard.h"

/* ---- shards of vt-tiles --shard: the complete set, then the coarse levels ---- */

/* The first metadata key (not the shard key) whose value differs between a and b, or NULL. */
static const char *metadata_difference(const struct vts_store *a, const struct vts_store *b)
{
    const struct vts_store *s[2] = {a, b};
    for (int t = 0; t < 2; t++)
        for (uint32_t i = 0; i < vts_store_meta_count(s[t]); i++) {
            const char *key = vts_store_meta_key(s[t], i),
                       *other = vts_store_meta_find(s[1 - t], key);
            if (strcmp(key, SHARD_KEY) != 0 &&
                (!other || strcmp(other, vts_store_meta_value(s[t], i)) != 0))
                return key;
        }
    return NULL;
}

/* Every input is a shard of one vt-tiles --shard build, each of 1/N .. N/N exactly once. */
int vt_merge_check_shard_build(const struct merge *m, struct vts_error *err)
{
    int n = m->o->input_count, with = 0, rc = 0;
    while (!vts_store_meta_find(m->in[with], VT_SHARD_BUILD_KEY))
        with++;
    uint32_t count = 0, index = 0, c = 0;
    int *owner = NULL;
    for (int k = 0; k < n && rc == 0; k++) {
        const char *v = vts_store_meta_find(m->in[k], SHARD_KEY);
        if (!vts_store_meta_find(m->in[k], VT_SHARD_BUILD_KEY) || vt_shard_parse(v, &index, &c)) {
            rc = vt_error_set(
                err, VTS_ERR_BAD_INPUT,
                "'%s' is not a shard of vt-tiles --shard (no %s metadata), unlike '%s'",
                m->o->inputs[k], VT_SHARD_BUILD_KEY, m->o->inputs[with]);
            break;
        }
        if (k == 0) {
            count = c;
            if (!(owner = malloc(count * sizeof *owner)))
                return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
            for (uint32_t i = 0; i < count; i++)
                owner[i] = -1;
        }
        const char *key = metadata_difference(m->in[0], m->in[k]);
        if (c != count)
            rc = vt_error_set(err, VTS_ERR_BAD_INPUT,
                              "'%s' is shard %u/%u but '%s' is a shard of %u: not one build",
                              m->o->inputs[k], index, c, m->o->inputs[0], count);
        else if (owner[index - 1] >= 0)
            rc = vt_error_set(err, VTS_ERR_BAD_INPUT, "shard %u/%u is given twice: '%s' and '%s'",
                              index, c, m->o->inputs[owner[index - 1]], m->o->inputs[k]);
        else if (key) {
            const char *va = vts_store_meta_find(m->in[k], key);
            const char *vb = vts_store_meta_find(m->in[0], key);
            rc = vt_error_set(
                err, VTS_ERR_BAD_INPUT,
                "'%s' (shard %u/%u) is from another build: its %s is '%s', not '%s' as in '%s'",
                m->o->inputs[k], index, c, key, va ? va : "(none)", vb ? vb : "(none)",
                m->o->inputs[0]);
        } else
            owner[index - 1] = k;
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

static int emit_coarse_tile(void *user, unsigned worker, uint32_t level, uint32_t tx, uint32_t ty,
                            const struct vt_image *payload, struct vts_error *err)
{
    struct merge *m = user;
    return vt_tile_sink_put(m->sink, worker, 0, level, tx, ty, payload, err);
}

static int coarse_progress(void *user, uint64_t done, uint64_t total)
{
    struct merge *m = user;
    (void)total;
    vt_progress_update(&m->progress, done);
    return 0;
}

/* Copies the carried texels of every shard (layer `layer`, level k) into the pass image f. */
static int assemble_carried(struct merge *m, struct vt_float_file *f, uint32_t layer, uint32_t k,
                            uint32_t channels, float *row, struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(m->in[0]);
    struct vts_level L;
    vts_store_level(m->in[0], k, &L);
    uint32_t c = g->tile_content_px, pp = g->tile_payload_px;
    size_t want = (size_t)pp * pp * channels * 4;
    for (uint32_t ty = 0; ty < L.tiles_y; ty++)
        for (uint32_t tx = 0; tx < L.tiles_x; tx++) {
            int owner = -1;
            struct vts_tile_entry e;
            for (int i = 0; i < m->o->input_count && owner < 0; i++) {
                int rc = vts_store_tile(m->in[i], layer, k, tx, ty, &e, err);
                if (rc)
                    return rc;
                if (e.length)
                    owner = i;
            }
            if (owner < 0)
                return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                    "no shard holds the carried texels of tile %u,%u of level %u",
                                    tx, ty, k);
            size_t len = 0;
            int rc = vt_merge_read_tile(m, owner, 0, layer, k, tx, ty, &len, err);
            if (rc == 0 && len != want)
                rc = vt_error_set(err, VTS_ERR_BAD_INPUT,
                                  "'%s': carried tile %u,%u of level %u has %zu bytes, not %zu",
                                  m->o->inputs[owner], tx, ty, k, len, want);
            uint32_t w = L.width - tx * c < c ? L.width - tx * c : c;
            uint32_t h = L.height - ty * c < c ? L.height - ty * c : c;
            for (uint32_t y = 0; rc == 0 && y < h; y++) {
                vt_shard_unpack_row(m->buf[0], pp, g->border_px, channels, y, w, row);
                rc = vt_float_file_write(f, tx * c, ty * c + y, row, w, err);
            }
            if (rc)
                return rc;
        }
    return 0;
}

/* Builds the levels above the shards' first pass from their carried texels, with the options
 * the shards recorded: the same bytes as the single build's passes. */
int vt_merge_build_coarse(struct merge *m, struct vts_error *err)
{
    const struct vts_store *s0 = m->in[0];
    const struct vts_geometry *g = vts_store_geometry(s0);
    const struct vts_layer *L = vts_store_layer(s0, 0), *F = vts_store_layer(s0, 1);
    const char *filter_name = vts_store_meta_find(s0, "filter");
    struct vt_shard_build sb;
    enum vt_filter_kind filter;
    if (g->layer_count != 2 || strncmp(F->name, VT_SHARD_LAYER_NAME, VTS_LAYER_NAME_BYTES) != 0 ||
        F->codec != VTS_CODEC_RAW || F->sample != VTS_SAMPLE_F32 ||
        vt_shard_build_parse(vts_store_meta_find(s0, VT_SHARD_BUILD_KEY), &sb) ||
        F->channels != sb.channels || !filter_name || vt_filter_parse(filter_name, &filter))
        return vt_error_set(
            err, VTS_ERR_BAD_INPUT,
            "'%s': not a well-formed vt-tiles shard (layer table, %s or filter metadata)",
            m->o->inputs[0], VT_SHARD_BUILD_KEY);
    /* the shards recorded the effort their codec was given */
    struct vt_tile_sink_layer sink_layer = {
        vt_codec_by_fourcc(L->codec),
        {L->codec == VTS_CODEC_JPEG ? (int)L->codec_param : 0, (int)sb.effort, (int)sb.subsampling},
        L->channels,
        L->sample};
    if (!sink_layer.codec)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "'%s': codec of layer 0 is not available",
                            m->o->inputs[0]);
    struct vt_source_info input = {.width = g->width,
                                   .height = g->height,
                                   .channels = sb.channels,
                                   .sample = VTS_SAMPLE_F32,
                                   .colour = L->colour,
                                   .has_alpha = sb.has_alpha,
                                   .premultiplied = sb.premultiplied};
    char dir[4096];
    const char *slash = strrchr(m->o->out_path, '/');
    snprintf(dir, sizeof dir, "%.*s",
             slash ? (int)(slash - m->o->out_path) + (slash == m->o->out_path) : 1,
             slash ? m->o->out_path : ".");
    struct vt_pyramid_options po = {.width = g->width,
                                    .height = g->height,
                                    .tile_content_px = g->tile_content_px,
                                    .border_px = g->border_px,
                                    .level_count = g->level_count,
                                    .filter = filter,
                                    .colour = L->colour,
                                    .wrap = (g->flags & VTS_STORE_WRAP_X) != 0,
                                    .out_channels = L->channels,
                                    .out_sample = L->sample,
                                    .threads = m->o->threads,
                                    .levels_per_pass = sb.levels_per_pass,
                                    .temp_dir = m->o->temp_dir ? m->o->temp_dir : dir,
                                    .emit = emit_coarse_tile,
                                    .progress = coarse_progress,
                                    .user = m,
                                    .resume_input = &input};
    struct vt_pyramid_plan plan;
    vt_pyramid_plan(&po, &plan);
    if (!plan.has_next) /* the shards' first pass made every level */
        return 0;
    struct vt_source src = {0};
    struct vt_source *ptrs[256];
    float *row = malloc((size_t)g->tile_content_px * sb.channels * sizeof *row);
    int rc = row ? 0 : vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    if (rc == 0 && !(m->sink = vt_tile_sink_create(m->out, g->tile_payload_px, &sink_layer, 1,
                                                   po.threads, 0, err)))
        rc = err->status;
    struct vt_float_file *f = rc ? NULL
                                 : vt_float_file_create(po.temp_dir, plan.carry_width,
                                                        plan.carry_height, sb.channels, err);
    if (rc == 0 && !f)
        rc = err->status;
    if (rc == 0)
        rc = assemble_carried(m, f, 1, plan.levels_per_pass, sb.channels, row, err);
    if (rc == 0)
        rc = vt_float_file_source(f, L->colour, sb.has_alpha, &src, err);
    if (rc == 0) {
        for (unsigned i = 0; i < po.threads; i++)
            ptrs[i] = &src;
        vt_log(VT_LOG_INFO, "building levels %u..%u from the shards' level %u (%ux%u)",
               plan.levels_per_pass + 1, g->level_count - 1, plan.levels_per_pass, plan.carry_width,
               plan.carry_height);
        vt_progress_start(&m->progress, "coarse levels", "tiles", vt_pyramid_tile_count(&po));
        rc = vt_pyramid_build(ptrs, &po, err);
        vt_progress_end(&m->progress);
    }
    vt_source_close(&src);
    vt_float_file_destroy(f);
    vt_tile_sink_destroy(m->sink);
    m->sink = NULL;
    free(row);
    return rc;
}
