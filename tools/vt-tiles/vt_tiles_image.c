/* vt-tiles INPUT -o OUT.vts: the single-image build (see vt_tiles_image.h). */
#include "vt_tiles_image.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "tool_common.h"
#include "vt_codec.h"
#include "vt_error.h"
#include "vt_image_input.h"
#include "vt_output_path.h"
#include "vt_pool.h"
#include "vt_pyramid.h"
#include "vt_shard.h"
#include "vt_tile_sink.h"
#include "vt_version.h"
#include "vts_writer.h"

struct run {
    const struct vt_tiles_image_options *o;
    const struct vt_codec *codec;
    struct vt_codec_params params;
    struct vts_writer *writer;
    struct vt_tile_sink *sink; /* every layer; its scratch buffers also pack the carried texels */
    uint32_t layer;            /* the layer being built (one band group per layer) */
    bool empty_nodata;         /* tiles whose texels all equal nodata are left empty */
    double nodata;
    uint32_t carry_level, content; /* shards: the carried level (with wrap), the tiles' content */
    struct vt_progress progress;
};

/* True when every sample of img equals nodata (NaN matches NaN); u8/u16 with a nodata outside
 * their range or not an integer never match. f16 tiles are never empty. */
static bool all_nodata(const struct vt_image *img, double nodata)
{
    size_t n = (size_t)img->width * img->channels;
    bool nan = isnan(nodata);
    for (uint32_t y = 0; y < img->height; y++) {
        const unsigned char *row = (const unsigned char *)img->pixels + y * img->stride;
        for (size_t i = 0; i < n; i++) {
            double v;
            if (img->sample == VTS_SAMPLE_U8)
                v = row[i];
            else if (img->sample == VTS_SAMPLE_U16)
                v = ((const uint16_t *)(const void *)row)[i];
            else if (img->sample == VTS_SAMPLE_F32)
                v = ((const float *)(const void *)row)[i];
            else
                return false;
            if (nan ? !isnan(v)
                    : v != (img->sample == VTS_SAMPLE_F32 ? (double)(float)nodata : nodata))
                return false;
        }
    }
    return true;
}

static int emit_tile(void *user, unsigned worker, uint32_t level, uint32_t tx, uint32_t ty,
                     const struct vt_image *payload, struct vts_error *err)
{
    struct run *r = user;
    if (payload && r->empty_nodata && all_nodata(payload, r->nodata))
        return 0; /* never put: an empty tile */
    return vt_tile_sink_put(r->sink, worker, r->layer, level, tx, ty, payload, err);
}

/* A shard's carried texels (vt_shard.h): one payload of the extra layer per rectangle, in the
 * tile of `level` that holds it. */
static int carry_at(struct run *r, unsigned worker, uint32_t level, uint32_t x, uint32_t y,
                    uint32_t width, uint32_t height, uint32_t channels, const float *texels,
                    size_t stride, struct vts_error *err)
{
    unsigned char *buf = vt_tile_sink_scratch(r->sink, worker, NULL);
    vt_shard_pack(buf, texels, width, height, channels, stride);
    size_t len = (size_t)width * height * channels * 4;
    return vts_writer_put(r->writer, 1, level, x / r->content, y / r->content, buf, len, err);
}

/* With wrap: every first-pass block's texels of the carried level. */
static int carry_tile(void *user, unsigned worker, uint32_t x, uint32_t y, uint32_t width,
                      uint32_t height, uint32_t channels, const float *texels, size_t stride,
                      struct vts_error *err)
{
    struct run *r = user;
    return carry_at(r, worker, r->carry_level, x, y, width, height, channels, texels, stride, err);
}

/* Without wrap: the texels along the seams the merge needs (worker 0: the calling thread). */
static int carry_seam(void *user, uint32_t level, uint32_t x, uint32_t y, uint32_t width,
                      uint32_t height, uint32_t channels, const float *texels, size_t stride,
                      struct vts_error *err)
{
    return carry_at(user, 0, level, x, y, width, height, channels, texels, stride, err);
}

/* Shard metadata (after the single build's): shard=I/N, what the merge needs, the input's id. */
static int set_shard_metadata(struct vts_writer *w, const struct vt_tiles_image_options *o,
                              const struct vt_shard_build *b, struct vts_error *err)
{
    char value[256];
    struct stat st;
    if (stat(o->input, &st) != 0)
        return vt_error_set(err, VTS_ERR_IO, "'%s': cannot stat the input", o->input);
    snprintf(value, sizeof value, "%u/%u", o->shard, o->shard_count);
    int rc = vts_writer_set_meta(w, VT_SHARD_KEY, value, err);
    vt_shard_build_format(b, value, sizeof value);
    if (rc == 0)
        rc = vts_writer_set_meta(w, VT_SHARD_BUILD_KEY, value, err);
    snprintf(value, sizeof value, "size=%lld mtime=%lld", (long long)st.st_size,
             (long long)st.st_mtime);
    return rc ? rc : vts_writer_set_meta(w, VT_SHARD_INPUT_KEY, value, err);
}

static int show_progress(void *user, uint64_t done, uint64_t total)
{
    struct run *r = user;
    (void)total;
    vt_progress_update(&r->progress, done);
    return 0;
}

/* Picks codec, output channels and sample for the input; logs what it decided. */
static const struct vt_codec *choose_codec(const struct vt_tiles_image_options *o,
                                           const struct vt_source_info *in, uint32_t colour,
                                           bool keep_alpha, uint32_t *out_sample)
{
    /* auto: the input's own sample type decides (16-bit and float inputs keep their depth) */
    uint32_t channels = in->channels - (in->has_alpha && !keep_alpha);
    const char *name =
        vt_tile_sink_layer_codec_name(o->codec_name, in->sample, channels, keep_alpha, colour);
    bool is_float = in->sample == VTS_SAMPLE_F16 || in->sample == VTS_SAMPLE_F32;
    const struct vt_codec *codec = vt_codec_find(name);
    if (!codec) {
        vt_usage_error(
            "codec '%s' is not available (raw, png, jpeg, bc1, bc3, bc4, bc5, auto, gpu)", name);
        return NULL;
    }
    *out_sample = in->sample;
    if (codec->fourcc == VTS_CODEC_PNG && is_float)
        *out_sample = VTS_SAMPLE_U16;
    else if (codec->fourcc != VTS_CODEC_RAW && codec->fourcc != VTS_CODEC_PNG)
        *out_sample = VTS_SAMPLE_U8;
    if (vt_filter_is_selection(o->filter) &&
        ((codec->fourcc != VTS_CODEC_RAW && codec->fourcc != VTS_CODEC_PNG) ||
         *out_sample != in->sample)) {
        /* a selection keeps the input's values: only a lossless codec of its sample keeps them */
        vt_usage_error(
            "'%s': --filter %s keeps exact values: codec %s would store %s samples "
            "%s (use %s)",
            o->input_name, vt_filter_name(o->filter), codec->name, vts_sample_name(in->sample),
            *out_sample != in->sample ? "converted" : "lossily", is_float ? "raw" : "png or raw");
        return NULL;
    }
    if (*out_sample != in->sample)
        vt_log(VT_LOG_WARN, "'%s': %s samples stored as %s for codec %s", o->input_name,
               vts_sample_name(in->sample), vts_sample_name(*out_sample), codec->name);
    return codec;
}

/* One layer of the store: a group of up to 4 bands of the input (docs/geospatial.md). */
struct layer_plan {
    uint32_t first, count; /* 0-based first band and bands; count 0: every band (at most 4) */
    struct vt_source_info in;
    uint32_t colour, channels, out_sample;
    bool keep_alpha;
    const struct vt_codec *codec;
};

/* One layer for an input of up to 4 bands (unless --band-layers), else one per 4 bands (the last
 * one holds the rest) or one per band. Returns the layer count. */
static uint32_t plan_groups(const struct vt_input_raster *ras, bool band_layers,
                            struct layer_plan *plans)
{
    if (ras->band_count <= 4 && !band_layers) {
        plans[0].first = plans[0].count = 0;
        return 1;
    }
    uint32_t per = band_layers ? 1 : 4, n = 0;
    for (uint32_t b = 0; b < ras->band_count; b += per, n++) {
        plans[n].first = b;
        plans[n].count = ras->band_count - b < per ? ras->band_count - b : per;
    }
    return n;
}

/* A layer's name: --name for a single layer; else the group's band descriptions joined by '+'
 * when every band has one and they fit, else "band3" / "bands1-4" (1-based, as GDAL counts). */
static void layer_name(const struct vt_tiles_image_options *o, const struct vt_input_raster *ras,
                       uint32_t n_layers, const struct layer_plan *p,
                       char name[VTS_LAYER_NAME_BYTES])
{
    if (n_layers == 1) {
        snprintf(name, VTS_LAYER_NAME_BYTES, "%s", o->name);
        return;
    }
    char joined[4 * VTS_LAYER_NAME_BYTES + 4] = "";
    bool all = true;
    for (uint32_t b = p->first; b < p->first + p->count; b++) {
        all = all && ras->band_names[b][0];
        if (joined[0])
            strcat(joined, "+");
        strcat(joined, ras->band_names[b]);
    }
    size_t len = strlen(joined);
    if (all && len < VTS_LAYER_NAME_BYTES)
        memcpy(name, joined, len + 1);
    else if (p->count == 1)
        snprintf(name, VTS_LAYER_NAME_BYTES, "band%u", p->first + 1);
    else
        snprintf(name, VTS_LAYER_NAME_BYTES, "bands%u-%u", p->first + 1, p->first + p->count);
}

static int open_sources(const struct vt_tiles_image_options *o, const struct layer_plan *p,
                        struct vt_source *src, unsigned n, struct vts_error *err)
{
    struct vt_input_limits limits = {o->max_pixels};
    int rc = vt_image_input_open_bands(o->input, &limits, p->first, p->count, &src[0], err);
    for (unsigned i = 1; rc == 0 && !src[0].info.sequential && i < n; i++)
        rc = vt_image_input_open_bands(o->input, &limits, p->first, p->count, &src[i], err);
    return rc;
}

/* Opens the layer's bands once to settle colour, alpha, codec and output sample. Returns 0, a
 * negative status (err set) or VT_EXIT_USAGE (an unavailable codec, reported). */
static int plan_layer(const struct vt_tiles_image_options *o, struct layer_plan *p,
                      struct vts_error *err)
{
    struct vt_source src;
    int rc = open_sources(o, p, &src, 1, err);
    if (rc)
        return rc;
    p->in = src.info;
    p->colour = o->colour_set ? o->colour : p->in.colour;
    bool opaque = true;
    if (p->in.has_alpha && (rc = vt_source_alpha_opaque(&src, &opaque, err)) != 0)
        goto out_close;
    p->keep_alpha = p->in.has_alpha && !opaque;
    p->codec = choose_codec(o, &p->in, p->colour, p->keep_alpha, &p->out_sample);
    if (!p->codec)
        rc = VT_EXIT_USAGE;
    p->channels = p->in.channels - (p->in.has_alpha && !p->keep_alpha);
out_close:
    vt_source_close(&src);
    return rc;
}

/* Georeferencing and bands (docs/geospatial.md): geo.transform (GDAL's six numbers), geo.crs_wkt,
 * nodata, source.bands and, with several layers, layer.N.bands (1-based, "5-6"). */
static int set_geo_metadata(struct vts_writer *w, const struct vt_input_raster *ras,
                            const struct layer_plan *plans, uint32_t n_layers,
                            struct vts_error *err)
{
    char key[32], value[512];
    int rc = 0;
    if (ras->has_geotransform) {
        const double *t = ras->geotransform;
        snprintf(value, sizeof value, "%.17g %.17g %.17g %.17g %.17g %.17g", t[0], t[1], t[2], t[3],
                 t[4], t[5]);
        rc = vts_writer_set_meta(w, "geo.transform", value, err);
    }
    if (rc == 0 && ras->crs_wkt)
        rc = vts_writer_set_meta(w, "geo.crs_wkt", ras->crs_wkt, err);
    if (rc == 0 && ras->has_nodata) {
        snprintf(value, sizeof value, "%.17g", ras->nodata);
        rc = vts_writer_set_meta(w, "nodata", value, err);
    }
    if (rc == 0 && (ras->band_count > 4 || n_layers > 1)) {
        snprintf(value, sizeof value, "%u", ras->band_count);
        rc = vts_writer_set_meta(w, "source.bands", value, err);
    }
    for (uint32_t l = 0; rc == 0 && n_layers > 1 && l < n_layers; l++) {
        snprintf(key, sizeof key, "layer.%u.bands", l);
        const struct layer_plan *p = &plans[l];
        if (p->count == 1)
            snprintf(value, sizeof value, "%u", p->first + 1);
        else
            snprintf(value, sizeof value, "%u-%u", p->first + 1, p->first + p->count);
        rc = vts_writer_set_meta(w, key, value, err);
    }
    return rc;
}

/* --value-scale/--value-offset, else the first band's scale/offset GDAL reports: layer.N.scale and
 * layer.N.offset of every layer (the value of a stored sample is stored * scale + offset, as GDAL's
 * band scale and offset; docs/geospatial.md). */
static int set_value_metadata(struct vts_writer *w, double scale, double offset, uint32_t n_layers,
                              struct vts_error *err)
{
    char key[48], value[64];
    int rc = 0;
    for (uint32_t l = 0; rc == 0 && l < n_layers; l++) {
        snprintf(key, sizeof key, "layer.%u.scale", l);
        snprintf(value, sizeof value, "%.17g", scale);
        rc = vts_writer_set_meta(w, key, value, err);
        snprintf(key, sizeof key, "layer.%u.offset", l);
        snprintf(value, sizeof value, "%.17g", offset);
        if (rc == 0)
            rc = vts_writer_set_meta(w, key, value, err);
    }
    return rc;
}

static int set_metadata(struct vts_writer *w, const struct vt_tiles_image_options *o,
                        const char *codec, struct vts_error *err)
{
    char quality[16];
    snprintf(quality, sizeof quality, "%u", o->quality);
    if (strcmp(codec, "jpeg") != 0) /* the only codec with a quality */
        snprintf(quality, sizeof quality, "-");
    const char *pairs[][2] = {{"tool", "vt-tiles"},        {"tool.version", VT_VERSION_STRING},
                              {"source", o->input_name},   {"filter", vt_filter_name(o->filter)},
                              {"filtering", o->filtering}, {"codec", codec},
                              {"quality", quality},        {"wrap", o->wrap ? "yes" : "no"}};
    for (size_t i = 0; i < sizeof pairs / sizeof pairs[0]; i++) {
        int rc = vts_writer_set_meta(w, pairs[i][0], pairs[i][1], err);
        if (rc)
            return rc;
    }
    /* --colour index: the layer's colour is data; consumers sample it without interpolating */
    return o->index ? vts_writer_set_meta(w, "colour", "index", err) : 0;
}

/* Border and tile geometry from the options; returns 0 or a usage exit status. */
static int make_geometry(struct vt_tiles_image_options *o, const struct vt_source_info *in,
                         const struct vt_codec *codec, struct vts_geometry *g)
{
    bool bc = codec->fourcc == VTS_CODEC_BC1 || codec->fourcc == VTS_CODEC_BC3 ||
              codec->fourcc == VTS_CODEC_BC4 || codec->fourcc == VTS_CODEC_BC5;
    if (!o->border_set) {
        o->border = o->aniso <= 1 ? o->aniso + 1 : o->aniso / 2;
        if (bc && o->border < 4)
            o->border = 4;
    }
    uint32_t content = o->keep_content ? o->tile_size : o->tile_size - 2 * o->border;
    if (!o->keep_content && o->tile_size <= 2 * o->border)
        return vt_usage_error("--tile-size %u leaves no content with --border %u", o->tile_size,
                              o->border);
    if (o->border > content)
        return vt_usage_error("--border %u is larger than the tile content %u", o->border, content);
    *g = (struct vts_geometry){in->width,
                               in->height,
                               content,
                               o->border,
                               content + 2 * o->border,
                               0,
                               1,
                               o->wrap ? VTS_STORE_WRAP_X | VTS_STORE_WRAP_Y : 0};
    if (g->tile_payload_px > VTS_MAX_PAYLOAD_PX)
        return vt_usage_error("tile payload %u exceeds %u", g->tile_payload_px, VTS_MAX_PAYLOAD_PX);
    g->level_count = vts_full_level_count(g->width, g->height, g->tile_content_px);
    return 0;
}

static int build(struct run *r, struct vt_source *src, const struct vt_pyramid_options *po,
                 struct vts_error *err)
{
    struct vt_source *ptrs[256];
    for (unsigned i = 0; i < po->threads; i++)
        ptrs[i] = src[0].info.sequential ? NULL : &src[i];
    ptrs[0] = &src[0];
    vt_progress_start(&r->progress, "tiling", "tiles", vt_pyramid_tile_count(po));
    uint32_t pp = po->tile_content_px + 2 * po->border_px;
    r->progress.megapixels_per_unit = (double)pp * pp / 1e6;
    int rc = vt_pyramid_build(ptrs, po, err);
    vt_progress_end(&r->progress);
    return rc;
}

/* Builds every layer: each one's band group opened (one source per worker), its pyramid run. */
static int build_layers(struct run *r, struct vt_source *src, struct vt_pyramid_options *po,
                        const struct layer_plan *plans, uint32_t n_layers,
                        const struct vt_input_raster *ras, struct vts_error *err)
{
    int rc = 0;
    for (uint32_t l = 0; rc == 0 && l < n_layers; l++) {
        const struct layer_plan *p = &plans[l];
        if ((rc = open_sources(r->o, p, src, po->threads, err)) == 0) {
            r->layer = l;
            r->empty_nodata = ras->has_nodata && p->out_sample == p->in.sample;
            r->nodata = ras->nodata;
            po->colour = p->colour;
            po->out_channels = p->channels;
            po->out_sample = p->out_sample;
            rc = build(r, src, po, err);
        }
        for (unsigned i = 0; i < po->threads; i++)
            vt_source_close(&src[i]);
    }
    return rc;
}

int vt_tiles_image_run(const struct vt_tiles_image_options *opt)
{
    struct vt_tiles_image_options copy = *opt; /* make_geometry() settles the border */
    struct vt_tiles_image_options *o = &copy;
    struct vt_source src[256];
    memset(src, 0, sizeof src);
    struct vts_error err = {0};
    struct run r = {.o = o};
    struct vts_geometry g;
    struct vt_input_raster ras;
    memset(&ras, 0, sizeof ras);
    struct layer_plan plans[VTS_MAX_LAYERS];
    memset(plans, 0, sizeof plans);
    int status = VT_EXIT_BAD_INPUT, rc = 0;
    struct stat in_stat;
    if (o->shard && (stat(o->input, &in_stat) != 0 || !S_ISREG(in_stat.st_mode))) {
        rc = vt_error_set(&err, VTS_ERR_BAD_INPUT,
                          "'%s': --shard needs INPUT to be a regular file (every shard reads it)",
                          o->input);
        goto out;
    }
    struct vt_input_limits limits = {o->max_pixels};
    if ((rc = vt_image_input_describe(o->input, &limits, &ras, &err)) != 0)
        goto out;
    if (ras.geo_unread)
        vt_log(VT_LOG_WARN,
               "'%s': its GeoTIFF georeferencing is not kept: cannot load the GDAL module (%s)",
               o->input_name, ras.why);
    uint32_t n_layers = plan_groups(&ras, o->band_layers, plans);
    if (n_layers > 1 && o->shard) {
        status = vt_usage_error("--shard builds one layer: '%s' makes %u", o->input_name, n_layers);
        goto out;
    }
    for (uint32_t l = 0; l < n_layers; l++) {
        if ((rc = plan_layer(o, &plans[l], &err)) == VT_EXIT_USAGE) {
            rc = 0;
            status = VT_EXIT_USAGE;
            goto out;
        }
        if (rc)
            goto out;
    }
    const struct vt_source_info *in = &plans[0].in;
    uint32_t colour = plans[0].colour;
    r.codec = plans[0].codec;
    status = make_geometry(o, in, r.codec, &g);
    if (status != 0)
        goto out;
    status = VT_EXIT_BAD_INPUT;
    r.params = (struct vt_codec_params){(int)o->quality, vt_tile_sink_effort(r.codec, o->best),
                                        (int)o->subsampling};
    struct vts_layer layers[VTS_MAX_LAYERS];
    struct vt_tile_sink_layer sink_layers[VTS_MAX_LAYERS];
    memset(sink_layers, 0, sizeof sink_layers);
    for (uint32_t l = 0; l < n_layers; l++) {
        const struct layer_plan *p = &plans[l];
        if ((rc = p->codec->check(g.tile_payload_px, p->channels, p->out_sample, &err)) != 0)
            goto out;
        layers[l] = (struct vts_layer){p->codec->fourcc,
                                       (uint8_t)p->channels,
                                       (uint8_t)p->out_sample,
                                       (uint8_t)p->colour,
                                       0,
                                       0,
                                       {0}};
        layers[l].codec_param = p->codec->fourcc == VTS_CODEC_JPEG ? o->quality : 0;
        if (p->keep_alpha && p->in.premultiplied)
            layers[l].flags |= VTS_LAYER_PREMULTIPLIED;
        layer_name(o, &ras, n_layers, p, layers[l].name);
        struct vt_codec_params params = {(int)o->quality, vt_tile_sink_effort(p->codec, o->best),
                                         (int)o->subsampling};
        sink_layers[l] = (struct vt_tile_sink_layer){p->codec, params, p->channels, p->out_sample};
    }
    g.layer_count = n_layers;
    size_t carry = 0;
    if (o->shard) { /* + the carried texels: at most a tile's content of floats (vt_shard.h) */
        layers[1] = (struct vts_layer){
            VTS_CODEC_RAW,      (uint8_t)in->channels, VTS_SAMPLE_F32, (uint8_t)colour, 0, 0,
            VT_SHARD_LAYER_NAME};
        g.layer_count = 2;
        carry = (size_t)g.tile_content_px * g.tile_content_px * in->channels * 4;
        r.content = g.tile_content_px;
    }
    if (!(r.writer = vts_writer_create(o->output, &g, layers, &err)) ||
        !(r.sink = vt_tile_sink_create(r.writer, g.tile_payload_px, sink_layers, g.layer_count,
                                       o->threads, carry, &err))) {
        rc = err.status;
        goto out;
    }
    vts_writer_set_max_bytes(r.writer, o->max_store);
    struct vt_pyramid_options po = {.width = g.width,
                                    .height = g.height,
                                    .tile_content_px = g.tile_content_px,
                                    .border_px = g.border_px,
                                    .level_count = g.level_count,
                                    .filter = o->filter,
                                    .colour = colour,
                                    .wrap = o->wrap,
                                    .out_channels = plans[0].channels,
                                    .out_sample = plans[0].out_sample,
                                    .threads = o->threads,
                                    .temp_dir = o->temp_dir,
                                    .emit = emit_tile,
                                    .progress = show_progress,
                                    .user = &r};
    char dir[VT_PATH_MAX];
    if (!po.temp_dir) {
        if ((rc = vt_output_path_scratch_dir(o->output, dir, sizeof dir, &err)) != 0)
            goto out;
        po.temp_dir = dir;
    }
    struct vt_pyramid_plan plan;
    vt_pyramid_plan(&po, &plan);
    struct vt_shard_build sb = {
        plan.levels_per_pass,      in->channels, in->has_alpha, in->premultiplied, o->subsampling,
        (uint32_t)r.params.effort, false};
    if (o->shard) {
        po.part = true;
        po.carry = carry_tile;
        po.seam_carry = carry_seam;
        po.part_index = o->shard - 1;
        po.part_count = o->shard_count;
        sb.seams = vt_pyramid_part_seams(&po);
        r.carry_level = plan.levels_per_pass;
        vt_pyramid_part(&plan, o->shard - 1, o->shard_count, &po.part_x0, &po.part_y0, &po.part_x1,
                        &po.part_y1);
        vt_log(VT_LOG_INFO, "shard %u/%u: first-pass blocks %u..%u x %u..%u of %ux%u%s", o->shard,
               o->shard_count, po.part_x0, po.part_x1, po.part_y0, po.part_y1, plan.blocks_x,
               plan.blocks_y, po.part_x0 < po.part_x1 && po.part_y0 < po.part_y1 ? "" : " (empty)");
    }
    rc = build_layers(&r, src, &po, plans, n_layers, &ras, &err);
    if (rc == VTS_ERR_IO && !strstr(err.message, o->output)) { /* a temporary file: say whose */
        char m[sizeof err.message];
        snprintf(m, sizeof m, "%s", err.message);
        vt_error_set(&err, rc, "'%s': %s", o->output, m);
    }
    if (rc == 0)
        rc = set_metadata(r.writer, o, r.codec->name, &err);
    if (rc == 0)
        rc = set_geo_metadata(r.writer, &ras, plans, n_layers, &err);
    if (rc == 0 && o->has_value_scale) /* the options', else GDAL's for its input */
        rc = set_value_metadata(r.writer, o->value_scale, o->value_offset, n_layers, &err);
    else if (rc == 0 && ras.has_scale)
        rc = set_value_metadata(r.writer, ras.scale, ras.offset, n_layers, &err);
    if (rc == 0 && o->shard)
        rc = set_shard_metadata(r.writer, o, &sb, &err);
    if (rc == 0)
        rc = vts_writer_finish(r.writer, &err);
    if (rc == 0) {
        struct vts_writer_stats st;
        vts_writer_stats(r.writer, &st);
        vt_log(
            VT_LOG_INFO,
            "wrote '%s': %ux%u, %u levels, %llu tiles stored (%llu shared), %llu empty, %llu payload bytes",
            o->output, g.width, g.height, g.level_count, (unsigned long long)st.tiles_stored,
            (unsigned long long)st.tiles_shared, (unsigned long long)st.tiles_empty,
            (unsigned long long)st.unique_bytes);
        status = VT_EXIT_OK;
    }
out:
    if (rc)
        vt_log(VT_LOG_ERROR, "%s", err.message);
    vt_tile_sink_destroy(r.sink);
    vts_writer_destroy(r.writer);
    for (unsigned i = 0; i < o->threads; i++)
        vt_source_close(&src[i]);
    vt_input_raster_release(&ras);
    return status;
}
