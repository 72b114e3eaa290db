/* vt-view outputs: screenshot PNG and statistics JSON. */
#include "vtv_output.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_atomic_file.h"
#include "vt_error.h"
#include "vt_png_file.h"

int vtv_write_screenshot(const char *path, const uint8_t *rgba, uint32_t w, uint32_t h,
                         struct vts_error *err)
{
    uint8_t *row = malloc((size_t)w * 3);
    if (!row)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    struct vt_png_file_writer *pw = vt_png_file_writer_create(path, w, h, 3, 8, err);
    int st = pw ? 0 : err->status;
    for (uint32_t y = 0; st == 0 && y < h; y++) {
        for (uint32_t x = 0; x < w; x++)
            memcpy(row + (size_t)x * 3, rgba + ((size_t)y * w + x) * 4, 3);
        st = vt_png_file_writer_rows(pw, row, 1, (size_t)w * 3, err);
    }
    if (st == 0)
        st = vt_png_file_writer_finish(pw, err);
    vt_png_file_writer_destroy(pw);
    free(row);
    return st;
}

static void json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputc('"', f);
}

/* Clipmap mode's keys of a frame: strips, levels, the paging centre, the uploaded tiles
 * ([level, x, y]) and each level's front ([x0, y0, x1, y1] tiles) after the uploads. */
static void clip_json(FILE *f, const struct vtv_clipmap *c, const struct vtv_clipmap_frame *cf)
{
    fprintf(f,
            ", \"tiles_uploaded\": %" PRIu64 ", \"strips_completed\": %u, \"levels_complete\": "
            "%u, \"centre\": [%.17g, %.17g], \"uploaded\": [",
            cf->tiles, cf->strips, cf->levels_complete, cf->centre[0], cf->centre[1]);
    for (uint64_t i = 0; i < cf->tiles; i++) {
        const uint32_t *t = c->list[cf->first + i];
        fprintf(f, "%s[%u, %u, %u]", i ? ", " : "", t[0], t[1], t[2]);
    }
    fputs("], \"fronts\": [", f);
    for (uint32_t l = 0; l < c->cm.level_count; l++) {
        const struct vts_tile_rect *r = &cf->front[l];
        fprintf(f, "%s[%u, %u, %u, %u]", l ? ", " : "", r->x0, r->y0, r->x1, r->y1);
    }
    fputs("]", f);
}

static void frame_json(FILE *f, const struct vtv_frame_stats *s, const struct vtv_clipmap *c,
                       const struct vtv_clipmap_frame *cf)
{
    fprintf(f,
            "{\"requested\": %" PRIu64 ", \"loaded\": %" PRIu64 ", \"resident\": %" PRIu64
            ", \"uploads\": %" PRIu64 ", \"fallback_pixels\": %" PRIu64 ", \"empty\": %" PRIu64
            ", \"failed\": %" PRIu64 ", \"ram_hits\": %" PRIu64 ", \"reads\": %" PRIu64
            ", \"prefetched\": %" PRIu64 ", \"lod_bias\": %g, \"missed_by_level\": [",
            s->requested, s->loaded, s->resident, s->uploads, s->fallback_pixels, s->empty,
            s->failed, s->ram_hits, s->reads, s->prefetched, (double)s->lod_bias);
    for (uint32_t l = 0; l < s->levels && l < VTS_MAX_LEVELS; l++)
        fprintf(f, "%s%u", l ? ", " : "", s->missed[l]);
    fprintf(f, "], \"bytes_uploaded\": %" PRIu64, s->bytes_uploaded);
    if (c && cf)
        clip_json(f, c, cf);
    fputs("}", f);
}

/* --terrain: what was drawn (docs/viewer.md, "Terrain"). */
static void terrain_json(FILE *f, const struct vtv_terrain_info *t)
{
    fputs("  \"terrain\": {\"store\": ", f);
    json_string(f, t->store);
    fputs(", \"layer\": ", f);
    json_string(f, t->layer);
    fprintf(f,
            ", \"grid\": %u, \"level\": %u, \"level_size\": [%u, %u], \"scale\": %.17g, "
            "\"offset\": %.17g,\n    \"min_height\": %.17g, \"max_height\": %.17g, "
            "\"nodata_texels\": %llu, \"exaggeration\": %.17g, \"unit_per_texel\": %.17g, "
            "\"georeferenced\": %s,\n    \"mapped_by_geo\": %s, \"window\": [%.17g, %.17g, %.17g, "
            "%.17g]},\n",
            t->grid, t->level, t->level_width, t->level_height, t->scale, t->offset, t->min_height,
            t->max_height, (unsigned long long)t->nodata_texels, t->exaggeration, t->unit_per_texel,
            t->geo ? "true" : "false", t->mapped ? "true" : "false", t->window[0], t->window[1],
            t->window[2], t->window[3]);
}

int vtv_write_stats(const char *path, const struct vtv_run_info *info,
                    const struct vtv_frame_stats *frames, size_t count, struct vts_error *err)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    fputs("{\n  \"store\": ", f);
    json_string(f, info->store);
    fprintf(f, ",\n  \"mode\": \"%s\",\n  \"renderer\": \"%s\",\n  \"filtering\": \"%s\",\n",
            info->mode, info->renderer, info->filtering);
    fprintf(f, "  \"size\": [%u, %u],\n  \"feedback_size\": [%u, %u],\n", info->width, info->height,
            info->feedback_width, info->feedback_height);
    fprintf(f, "  \"cache_tiles\": %u,\n  \"uploads_per_frame\": %u,\n  \"sync\": %s,\n",
            info->cache_tiles, info->uploads_per_frame, info->sync ? "true" : "false");
    fprintf(f, "  \"physical_format\": \"%s\",\n", info->physical_format);
    if (info->clip)
        fprintf(f,
                "  \"clipmap\": {\"n\": %u, \"budget\": %" PRIu64 ", \"tile_bytes\": %" PRIu64
                ", \"tiles_per_frame\": %u, \"levels\": %u, \"texture_px\": %u},\n",
                info->clip->cm.n, info->clip->opt.budget, info->clip->gl.tile_bytes,
                info->clip->max_tiles, info->clip->cm.level_count, info->clip->gl.size_px);
    fputs("  \"variants\": [", f);
    for (uint32_t i = 0; i < info->variant_count; i++) {
        const struct vtv_variant *v = &info->variants[i];
        fprintf(f, "%s{\"features\": [", i ? ", " : "");
        for (unsigned k = 0, n = 0; k < VTV_F_COUNT; k++)
            if (v->features & (1u << k))
                fprintf(f, "%s\"%s\"", n++ ? ", " : "", vtv_feature_name(k));
        fprintf(f, "], \"faces\": %llu}", (unsigned long long)v->faces);
    }
    fputs("],\n", f);
    if (info->terrain)
        terrain_json(f, info->terrain);
    fputs("  \"frames\": [", f);
    for (size_t i = 0; i < count; i++) {
        fputs(i ? ",\n    " : "\n    ", f);
        frame_json(f, &frames[i], info->clip,
                   info->clip && i < info->clip->frame_count ? &info->clip->frames[i] : NULL);
    }
    fputs("\n  ],\n  \"last\": ", f);
    struct vtv_frame_stats zero = {0};
    const struct vtv_clipmap *c = info->clip;
    frame_json(f, count ? &frames[count - 1] : &zero, c,
               c && count && count <= c->frame_count ? &c->frames[count - 1] : NULL);
    fputs(",\n  \"timing_ms\": [", f);
    for (size_t i = 0; i < count; i++)
        fprintf(f, "%s%.3f", i ? ", " : "", frames[i].ms);
    fputs("]\n}\n", f);
    fclose(f);
    struct vt_atomic_file af;
    int st = vt_atomic_file_create(&af, path, "tmp", VT_ATOMIC_FILE_SEQUENTIAL, err);
    if (st == 0) {
        st = vt_atomic_file_pwrite(&af, buf, len, 0, err);
        if (st == 0)
            st = vt_atomic_file_commit(&af, err);
        else
            vt_atomic_file_abort(&af);
    }
    free(buf);
    return st;
}
