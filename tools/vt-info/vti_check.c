/* vt-info --verify (every tile read and checked) and --stats (per level and layer figures). */
#include <jansson.h>
#include <stdio.h>
#include <string.h>

#include "tool_common.h"
#include "vt_level_stats.h"
#include "vt_shard.h"
#include "vti.h"

/* True for the carried-texels layer of a vt-tiles --shard store. */
static bool is_shard_carry(const struct vts_store *s, uint32_t layer)
{
    const struct vts_layer *l = vts_store_layer(s, layer);
    return l && strcmp(l->name, VT_SHARD_LAYER_NAME) == 0 && vts_store_meta_find(s, VT_SHARD_KEY);
}

int vti_run_verify(const struct vts_store *s)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    struct vt_tile_reader r = {0};
    struct vts_error err = {0};
    struct vt_progress progress;
    uint64_t stored = 0, done = 0;
    int rc = 0;
    for (uint64_t i = 0; i < vts_store_tile_count(s); i++)
        stored += vts_store_entry(s, i)->length > 0;
    vt_progress_start(&progress, "verifying", "tiles", stored);
    for (uint32_t layer = 0; layer < g->layer_count && rc == 0; layer++) {
        vt_tile_reader_release(&r);
        rc = vt_tile_reader_init(&r, s, layer, &err);
        /* a shard's carried texels are float rectangles, not tiles of the layer's shape: their
         * checksums are checked, vt-merge reads them (docs/sharding.md) */
        r.crc_only = is_shard_carry(s, layer);
        for (uint32_t level = 0; level < g->level_count && rc == 0; level++) {
            struct vts_level L;
            vts_store_level(s, level, &L);
            for (uint32_t ty = 0; ty < L.tiles_y && rc == 0; ty++)
                for (uint32_t tx = 0; tx < L.tiles_x && rc == 0; tx++) {
                    bool is_stored = false;
                    rc = vt_tile_reader_read(&r, level, tx, ty, &is_stored, &err);
                    done += is_stored;
                    vt_progress_update(&progress, done);
                }
        }
    }
    vt_tile_reader_release(&r);
    vt_progress_end(&progress);
    if (rc != 0) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        return VT_EXIT_BAD_INPUT;
    }
    vt_log(VT_LOG_INFO, "verified %llu tiles", (unsigned long long)done);
    return VT_EXIT_OK;
}

/* --stats: every level of every layer (or of --layer), as text or JSON on stdout. */
int vti_run_stats(const struct vts_store *s, const struct options *o)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    if (o->has_layer && o->layer >= g->layer_count)
        return vt_usage_error("--layer %u: '%s' has layers 0..%u", o->layer, o->store_path,
                              g->layer_count - 1);
    struct vt_tile_reader r = {0};
    struct vts_error err = {0};
    json_t *layers = o->json ? json_array() : NULL;
    int rc = 0;
    for (uint32_t layer = 0; layer < g->layer_count && rc == 0; layer++) {
        if (o->has_layer && layer != o->layer)
            continue;
        const struct vts_layer *info = vts_store_layer(s, layer);
        vt_tile_reader_release(&r);
        rc = vt_tile_reader_init(&r, s, layer, &err);
        json_t *levels = o->json ? json_array() : NULL;
        for (uint32_t level = 0; level < g->level_count && rc == 0; level++) {
            struct vt_level_stats st;
            rc = vt_level_stats_compute(&r, level, &st, &err);
            if (rc)
                break;
            struct vts_level L;
            vts_store_level(s, level, &L);
            if (!o->json) {
                printf("layer %u '%s' %s x%u, level %u %ux%u: %llu texels, %llu empty tiles\n",
                       layer, info->name, vts_sample_name(info->sample), info->channels, level,
                       L.width, L.height, (unsigned long long)st.texels,
                       (unsigned long long)st.empty_tiles);
                for (uint32_t c = 0; c < st.channels; c++) {
                    const struct vt_channel_stats *cs = &st.ch[c];
                    printf("  channel %u: min %.9g max %.9g mean %.6f stddev %.6f", c, cs->min,
                           cs->max, cs->mean, cs->stddev);
                    if (cs->nan)
                        printf(" (%llu NaN)", (unsigned long long)cs->nan);
                    putchar('\n');
                }
                continue;
            }
            json_t *channels = json_array();
            for (uint32_t c = 0; c < st.channels; c++) {
                const struct vt_channel_stats *cs = &st.ch[c];
                json_array_append_new(channels,
                                      json_pack("{s:f,s:f,s:f,s:f,s:I}", "min", cs->min, "max",
                                                cs->max, "mean", cs->mean, "stddev", cs->stddev,
                                                "nan", (json_int_t)cs->nan));
            }
            json_array_append_new(levels,
                                  json_pack("{s:i,s:i,s:i,s:I,s:I,s:o}", "level", (int)level,
                                            "width", (int)L.width, "height", (int)L.height,
                                            "texels", (json_int_t)st.texels, "empty_tiles",
                                            (json_int_t)st.empty_tiles, "channels", channels));
        }
        if (o->json)
            json_array_append_new(
                layers, json_pack("{s:i,s:s,s:s,s:o}", "layer", (int)layer, "name", info->name,
                                  "sample", vts_sample_name(info->sample), "levels", levels));
    }
    vt_tile_reader_release(&r);
    if (rc != 0) {
        json_decref(layers);
        vt_log(VT_LOG_ERROR, "%s", err.message);
        return VT_EXIT_BAD_INPUT;
    }
    if (o->json) {
        json_t *root = json_pack("{s:o}", "layers", layers);
        json_dumpf(root, stdout, JSON_INDENT(1) | JSON_REAL_PRECISION(9));
        putchar('\n');
        json_decref(root);
    }
    return VT_EXIT_OK;
}
