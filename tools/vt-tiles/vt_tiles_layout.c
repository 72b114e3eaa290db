/* vt-tiles --layout: the tool side of the atlas build (see vt_tiles_layout.h). */
#include "vt_tiles_layout.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "tool_common.h"
#include "vt_atlas_build.h"
#include "vt_checked.h"
#include "vt_codec.h"
#include "vt_error.h"
#include "vt_image_input.h"
#include "vt_layout.h"
#include "vt_output_path.h"
#include "vt_png_file.h"
#include "vt_shard.h"
#include "vt_tiff_file.h"
#include "vt_tile_sink.h"
#include "vt_version.h"
#include "vts_writer.h"

#define EXPORT_MAX_TEXELS (1ull << 28)
#define EXPORT_BAND_ROWS  VT_TIFF_FILE_ROWS_PER_STRIP /* one TIFF strip per band */

struct layout_run {
    const struct vt_tiles_layout_options *o;
    struct vt_layout lay;
    uint32_t layers[VT_LAYOUT_MAX_LAYERS], nslots;
    struct vt_atlas_build *build;
    struct vt_tile_sink_layer sink_layers[VT_LAYOUT_MAX_LAYERS];
    struct vts_writer *writer;
    struct vt_tile_sink *sink;
    struct vt_progress progress;
    struct vt_input_limits limits;
};

static int open_texture(void *user, const char *path, struct vt_source *out, struct vts_error *err)
{
    const struct layout_run *r = user;
    return vt_image_input_open(path, &r->limits, out, err);
}

static int show_progress(void *user, uint64_t done, uint64_t total)
{
    struct layout_run *r = user;
    (void)total;
    vt_progress_update(&r->progress, done);
    return 0;
}

static int emit_tile(void *user, unsigned worker, uint32_t slot, uint32_t level, uint32_t tx,
                     uint32_t ty, const struct vt_image *payload, struct vts_error *err)
{
    struct layout_run *r = user;
    return vt_tile_sink_put(r->sink, worker, slot, level, tx, ty, payload, err);
}

/* The layout fixes tile content and border; an explicit option must agree. */
static int check_geometry(const struct vt_tiles_layout_options *o, const struct vt_layout *lay)
{
    if (o->border_set && o->border != lay->border)
        return vt_usage_error(
            "--border %u conflicts with the layout's border %u (the layout fixes it: omit --border)",
            o->border, lay->border);
    uint32_t want = o->keep_content ? lay->tile_content : lay->tile_content + 2 * lay->border;
    if (o->tile_size_set && o->tile_size != want)
        return vt_usage_error(
            "--tile-size %u conflicts with the layout's tiles (content %u, border %u: --tile-size %u%s; or omit it)",
            o->tile_size, lay->tile_content, lay->border, want,
            o->keep_content ? "" : " with --keep payload");
    if (lay->tile_content + 2 * lay->border > VTS_MAX_PAYLOAD_PX)
        return vt_usage_error("the layout's tile payload %u exceeds %u",
                              lay->tile_content + 2 * lay->border, VTS_MAX_PAYLOAD_PX);
    return 0;
}

static int pick_layers(struct layout_run *r)
{
    if (!r->o->layer) {
        r->nslots = r->lay.layer_count;
        for (uint32_t i = 0; i < r->nslots; i++)
            r->layers[i] = i;
        return 0;
    }
    int i = vt_layout_layer_index(&r->lay, r->o->layer);
    if (i < 0)
        return vt_usage_error("--layer '%s' is not a layer of '%s'", r->o->layer, r->o->layout);
    r->layers[0] = (uint32_t)i;
    r->nslots = 1;
    return 0;
}

/* Codec of one layer (auto: the single-image rule for the layer's sample type: raw for float,
 * png for u16, alpha, normals and data, else jpeg). A codec that cannot store the layer's sample
 * type (jpeg or bc for u16, png for float) is refused, naming the layer. */
static int pick_codec(struct layout_run *r, uint32_t slot, struct vts_layer *layer,
                      struct vts_error *err)
{
    const struct vt_tiles_layout_options *o = r->o;
    struct vt_atlas_layer_format f;
    vt_atlas_build_format(r->build, slot, &f);
    const char *name = vt_tile_sink_layer_codec_name(
        o->codec_name ? o->codec_name : VT_TILE_SINK_AUTO, f.sample, f.channels, f.alpha, f.colour);
    const struct vt_codec *codec = vt_codec_find(name);
    if (!codec)
        return vt_usage_error(
            "codec '%s' is not available (raw, png, jpeg, bc1, bc3, bc4, bc5, auto, gpu)", name);
    uint32_t pp = r->lay.tile_content + 2 * r->lay.border;
    const struct vt_layout_layer *ll = &r->lay.layers[r->layers[slot]];
    int rc = codec->check(pp, f.channels, f.sample, err);
    if (rc) {
        char why[sizeof err->message];
        snprintf(why, sizeof why, "%s", err->message);
        vt_error_set(err, rc, "layer '%s' of '%s' holds %s samples: %s", ll->name, o->layout,
                     vts_sample_name(f.sample), why);
        return VT_EXIT_BAD_INPUT;
    }
    *layer = (struct vts_layer){
        codec->fourcc, (uint8_t)f.channels, (uint8_t)f.sample, (uint8_t)f.colour, 0, 0, {0}};
    layer->codec_param = codec->fourcc == VTS_CODEC_JPEG ? o->quality : 0;
    snprintf(layer->name, sizeof layer->name, "%s", ll->name);
    r->sink_layers[slot] = (struct vt_tile_sink_layer){
        codec,
        {(int)o->quality, vt_tile_sink_effort(codec, o->best), (int)o->subsampling},
        f.channels,
        f.sample};
    vt_log(
        VT_LOG_INFO,
        "layer '%s': %u channels (%s), %s samples (textures: %u u8, %u u16, %u f16, %u f32; the widest decides, f32 for u16 with f16), codec %s",
        ll->name, f.channels, vts_colour_name(f.colour), vts_sample_name(f.sample), f.textures[0],
        f.textures[1], f.textures[2], f.textures[3], codec->name);
    return 0;
}

static int set_metadata(struct layout_run *r, struct vts_error *err)
{
    const struct vt_tiles_layout_options *o = r->o;
    char names[VT_LAYOUT_MAX_LAYERS * 64] = "", codecs[VT_LAYOUT_MAX_LAYERS * 8] = "";
    char quality[16];
    for (uint32_t s = 0; s < r->nslots; s++) {
        size_t n = strlen(names), c = strlen(codecs);
        snprintf(names + n, sizeof names - n, "%s%s", s ? "," : "",
                 r->lay.layers[r->layers[s]].name);
        snprintf(codecs + c, sizeof codecs - c, "%s%s", s ? "," : "",
                 r->sink_layers[s].codec->name);
    }
    snprintf(quality, sizeof quality, "%u", o->quality);
    const char *pairs[][2] = {{"tool", "vt-tiles"},
                              {"tool.version", VT_VERSION_STRING},
                              {"source", o->layout},
                              {"layout", o->layout},
                              {"layers", names},
                              {"filter", vt_filter_name(o->filter)},
                              {"filtering", o->filtering ? o->filtering : "trilinear"},
                              {"codec", codecs},
                              {"quality", strstr(codecs, "jpeg") ? quality : "-"},
                              {"wrap", "no"}};
    for (size_t i = 0; i < sizeof pairs / sizeof pairs[0]; i++) {
        int rc = vts_writer_set_meta(r->writer, pairs[i][0], pairs[i][1], err);
        if (rc)
            return rc;
    }
    /* the value range of 16-bit and float layers, per layer ("-": none), for viewers' --range */
    char ranges[VT_LAYOUT_MAX_LAYERS * 40] = "";
    bool any_range = false;
    for (uint32_t s = 0; s < r->nslots; s++) {
        struct vt_atlas_layer_format f;
        vt_atlas_build_format(r->build, s, &f);
        size_t n = strlen(ranges);
        if (f.has_range)
            snprintf(ranges + n, sizeof ranges - n, "%s%.9g:%.9g", s ? "," : "", (double)f.range[0],
                     (double)f.range[1]);
        else
            snprintf(ranges + n, sizeof ranges - n, "%s-", s ? "," : "");
        any_range |= f.has_range;
    }
    /* a shard's range is of the textures it read: under its own key, always, for the merge to
     * join (vt_shard_merge_range) into the single build's "range" at this place */
    if (any_range || r->o->shard) {
        int rc =
            vts_writer_set_meta(r->writer, r->o->shard ? VT_SHARD_RANGE_KEY : "range", ranges, err);
        if (rc)
            return rc;
    }
    /* what each material needs (atlas.json's materials: layers, constants, alpha mode), for
     * renderers that group faces by features (docs/atlas-format.md, "Materials") */
    if (r->lay.material_count) {
        char *materials = vt_layout_materials_meta(&r->lay, (size_t)15 << 20, err);
        if (!materials)
            return err->status;
        int rc = vts_writer_set_meta(r->writer, VT_LAYOUT_MATERIALS_KEY, materials, err);
        free(materials);
        if (rc)
            return rc;
    }
    return 0;
}

/* ---- --shard I/N (docs/sharding.md, "Atlas shards") ---- */

/* The payload the merge needs, at level K, the part's tile of the carry layer. */
static int put_shard_carry(struct layout_run *r, struct vts_error *err)
{
    unsigned char *payload;
    size_t len;
    int rc = vt_atlas_build_carry(r->build, &payload, &len, err);
    uint32_t level = vt_atlas_build_carried_level(r->build), px, py;
    bool inside = vt_atlas_build_part_tile(r->build, r->o->shard - 1, &px, &py);
    if (rc == 0 && len && inside)
        rc = vts_writer_put(r->writer, r->nslots, level, px, py, payload, len, err);
    if (rc == 0)
        vt_log(VT_LOG_INFO, "shard %u/%u: levels 0..%u of part %u,%u; %zu bytes carried",
               r->o->shard, r->o->shard_count, level, px, py, inside ? len : 0);
    free(payload);
    return rc;
}

/* After the single build's metadata: shard=I/N, what the merge needs (the carried level and
 * the encoders' settings), and the layout's size and time (shards of one build). */
static int set_shard_metadata(struct layout_run *r, struct vts_error *err)
{
    const struct vt_tiles_layout_options *o = r->o;
    char value[256];
    struct stat st;
    if (stat(o->layout, &st) != 0)
        return vt_error_set(err, VTS_ERR_IO, "'%s': cannot stat the layout", o->layout);
    snprintf(value, sizeof value, "%u/%u", o->shard, o->shard_count);
    int rc = vts_writer_set_meta(r->writer, VT_SHARD_KEY, value, err);
    snprintf(value, sizeof value, "carry=atlas level=%u quality=%u subsampling=%u best=%u",
             vt_atlas_build_carried_level(r->build), o->quality, o->subsampling, o->best ? 1u : 0u);
    if (rc == 0)
        rc = vts_writer_set_meta(r->writer, VT_SHARD_BUILD_KEY, value, err);
    snprintf(value, sizeof value, "size=%lld mtime=%lld", (long long)st.st_size,
             (long long)st.st_mtime);
    return rc ? rc : vts_writer_set_meta(r->writer, VT_SHARD_INPUT_KEY, value, err);
}

static int write_store(struct layout_run *r, struct vts_error *err)
{
    struct vts_layer layers[VT_LAYOUT_MAX_LAYERS + 1];
    for (uint32_t s = 0; s < r->nslots; s++) {
        int status = pick_codec(r, s, &layers[s], err);
        if (status)
            return status;
    }
    uint32_t c = r->lay.tile_content, b = r->lay.border;
    struct vts_geometry g = {r->lay.width,
                             r->lay.height,
                             c,
                             b,
                             c + 2 * b,
                             vt_atlas_build_level_count(r->build),
                             r->nslots + (r->o->shard ? 1u : 0u),
                             0};
    if (r->o->shard) /* + what the merge needs (vt_atlas_build_carry()): raw bytes, one tile */
        layers[r->nslots] = (struct vts_layer){
            VTS_CODEC_RAW, 1, VTS_SAMPLE_F32, VTS_COLOUR_DATA, 0, 0, VT_SHARD_LAYER_NAME};
    if ((r->writer = vts_writer_create(r->o->output, &g, layers, err)))
        vts_writer_set_max_bytes(r->writer, r->o->max_store);
    if (!r->writer || !(r->sink = vt_tile_sink_create(r->writer, g.tile_payload_px, r->sink_layers,
                                                      r->nslots, r->o->threads, 0, err)))
        return VT_EXIT_BAD_INPUT;
    vt_progress_start(&r->progress, "tiling", "tiles", vt_atlas_build_tile_count(r->build));
    int rc = vt_atlas_build_tiles(r->build, emit_tile, r, err);
    vt_progress_end(&r->progress);
    if (rc == 0 && r->o->shard)
        rc = put_shard_carry(r, err);
    if (rc == 0)
        rc = set_metadata(r, err);
    if (rc == 0 && r->o->shard)
        rc = set_shard_metadata(r, err);
    if (rc == 0)
        rc = vts_writer_finish(r->writer, err);
    if (rc)
        return VT_EXIT_BAD_INPUT;
    struct vts_writer_stats st;
    struct vt_atlas_build_stats bs;
    vts_writer_stats(r->writer, &st);
    vt_atlas_build_stats(r->build, &bs);
    vt_log(
        VT_LOG_INFO,
        "wrote '%s': %ux%u, %u levels, %u layers, %llu tiles stored (%llu shared), %llu empty, %llu payload bytes; %llu texture decodes, cache peak %.1f MiB of %.0f (texture buffers %.1f), %.1f MiB spilled",
        r->o->output, g.width, g.height, g.level_count, g.layer_count,
        (unsigned long long)st.tiles_stored, (unsigned long long)st.tiles_shared,
        (unsigned long long)st.tiles_empty, (unsigned long long)st.unique_bytes,
        (unsigned long long)bs.chains_built, (double)bs.cache_peak / (1 << 20),
        (double)bs.cache_budget / (1 << 20), (double)bs.buffers_peak / (1 << 20),
        (double)bs.spilled_bytes / (1 << 20));
    return 0;
}

/* ---- --export-atlas ---- */

static bool ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && strcasecmp(s + n - m, suffix) == 0;
}

/* One band of rows into whichever writer is open. */
static int export_band(struct vt_png_file_writer *png, struct vt_tiff_file_writer *tiff,
                       const struct vt_image *band, struct vts_error *err)
{
    if (png)
        return vt_png_file_writer_rows(png, band->pixels, band->height, band->stride, err);
    return vt_tiff_file_writer_rows(tiff, band->pixels, band->height, band->stride, err);
}

static int export_atlas(struct layout_run *r, struct vts_error *err)
{
    const char *path = r->o->export_atlas;
    uint32_t w = r->lay.width, h = r->lay.height;
    if ((uint64_t)w * h > EXPORT_MAX_TEXELS)
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "cannot export '%s': the atlas has %ux%u texels, more than %llu", path,
                            w, h, (unsigned long long)EXPORT_MAX_TEXELS);
    bool is_png = ends_with(path, ".png");
    if (!is_png && !ends_with(path, ".tif") && !ends_with(path, ".tiff"))
        return vt_error_set(err, VTS_ERR_ARG,
                            "cannot export '%s': the name must end in .png, .tif or .tiff", path);
    struct vt_atlas_layer_format f;
    vt_atlas_build_format(r->build, 0, &f);
    struct vt_png_file_writer *png = NULL;
    struct vt_tiff_file_writer *tiff = NULL;
    struct vt_image band = {0};
    /* the layer's own samples: 8 or 16 bits in either format, f32 in TIFF */
    if (f.sample == VTS_SAMPLE_F16 || (is_png && f.sample == VTS_SAMPLE_F32))
        return vt_error_set(
            err, VTS_ERR_ARG,
            "cannot export '%s': layer '%s' holds %s samples (PNG takes u8 and u16, TIFF u8, u16 and f32)",
            path, r->lay.layers[r->layers[0]].name, vts_sample_name(f.sample));
    int rc = vt_image_alloc(&band, w, h < EXPORT_BAND_ROWS ? h : EXPORT_BAND_ROWS, f.channels,
                            f.sample, err);
    if (rc)
        return rc;
    if (is_png)
        rc = (png = vt_png_file_writer_create(path, w, h, f.channels,
                                              f.sample == VTS_SAMPLE_U16 ? 16 : 8, err))
                 ? 0
                 : err->status;
    else if (f.sample == VTS_SAMPLE_U8)
        rc = (tiff = vt_tiff_file_writer_create(path, w, h, f.channels, err)) ? 0 : err->status;
    else
        rc = (tiff = vt_tiff_file_writer_create_sample(path, w, h, f.channels, f.sample, err))
                 ? 0
                 : err->status;
    for (uint32_t y = 0; rc == 0 && y < h; y += band.height) {
        struct vt_image v = band;
        v.height = h - y < band.height ? h - y : band.height;
        rc = vt_atlas_build_render(r->build, 0, 0, 0, y, &v, err);
        if (rc == 0)
            rc = export_band(png, tiff, &v, err);
    }
    if (rc == 0 && png)
        rc = vt_png_file_writer_finish(png, err);
    if (rc == 0 && tiff)
        rc = vt_tiff_file_writer_finish(tiff, err);
    vt_png_file_writer_destroy(png);
    vt_tiff_file_writer_destroy(tiff);
    vt_image_release(&band);
    if (rc == 0)
        vt_log(VT_LOG_INFO, "wrote '%s': %ux%u, layer '%s'", path, w, h,
               r->lay.layers[r->layers[0]].name);
    return rc;
}

/* ---- run ---- */

static int start_build(struct layout_run *r, struct vts_error *err)
{
    const struct vt_tiles_layout_options *o = r->o;
    r->limits.max_pixels = o->max_pixels;
    char dir[VT_PATH_MAX];
    const char *temp_dir = o->temp_dir;
    struct vts_error dir_err = {0}; /* no directory: the library's default ($TMPDIR) */
    if (!temp_dir && o->output && !vt_output_path_is_stdio(o->output) &&
        vt_output_path_scratch_dir(o->output, dir, sizeof dir, &dir_err) == 0)
        temp_dir = dir;
    struct vt_atlas_build_options bo = {
        .layout = &r->lay,
        .layers = r->layers,
        .layer_count = r->nslots,
        .filter = o->filter,
        .threads = o->threads,
        .cache_bytes = o->cache_bytes,
        .temp_dir = temp_dir,
        .max_pixels = o->max_pixels,
        .open = open_texture,
        .open_user = r,
        .progress = show_progress,
        .progress_user = r,
        .part = {o->shard ? o->shard - 1 : 0, o->shard_count, false, NULL}};
    vt_progress_start(&r->progress, "reading textures", "textures",
                      (uint64_t)r->lay.entry_count * r->nslots);
    r->build = vt_atlas_build_create(&bo, err);
    vt_progress_end(&r->progress);
    return r->build ? 0 : err->status;
}

/* Before any work: neither the store nor the exported image may be the layout, one of its
 * textures or (the export) the store. Returns -1 when they may be written, else the exit status. */
static int check_outputs(const struct layout_run *r)
{
    const struct vt_layout *lay = &r->lay;
    size_t n = 2, cap;
    if (!vt_size_mul((size_t)lay->entry_count, lay->layer_count, &cap) ||
        !vt_size_add(cap, n, &cap)) {
        vt_log(VT_LOG_ERROR, "'%s' names too many textures", r->o->layout);
        return VT_EXIT_BAD_INPUT;
    }
    const char **inputs = malloc(cap * sizeof *inputs);
    if (!inputs) {
        vt_log(VT_LOG_ERROR, "out of memory");
        return VT_EXIT_BAD_INPUT;
    }
    inputs[0] = r->o->layout;
    inputs[1] = NULL; /* the store, for the export */
    for (uint32_t e = 0; e < lay->entry_count; e++)
        for (uint32_t l = 0; l < lay->layer_count; l++)
            inputs[n++] = lay->entries[e].textures[l].resolved; /* NULL for a fill: skipped */
    int status = vt_check_output(r->o->output, inputs, n);
    /* "-o -" is standard output, not an input "-": the export against what it is */
    bool to_stdout = vt_output_path_is_stdio(r->o->output);
    inputs[1] = to_stdout ? NULL : r->o->output;
    if (status < 0)
        status = vt_check_output(r->o->export_atlas, inputs, n);
    if (status < 0 && to_stdout && r->o->export_atlas)
        status = vt_check_output(r->o->output, &r->o->export_atlas, 1);
    free(inputs);
    return status;
}

int vt_tiles_layout_run(const struct vt_tiles_layout_options *options)
{
    struct vt_tiles_layout_options fixed = *options, *o = &fixed;
    if (o->threads == 0)
        o->threads = 1;
    if (o->threads > 256)
        o->threads = 256;
    struct layout_run r = {.o = o};
    struct vts_error err = {0};
    int status = VT_EXIT_BAD_INPUT;
    if (!o->output && !o->export_atlas)
        return vt_usage_error("missing -o OUT.vts (or --export-atlas FILE)");
    if (vt_layout_read(o->layout, NULL, &r.lay, &err))
        goto out;
    if ((status = check_outputs(&r)) >= 0)
        goto out;
    if ((status = check_geometry(o, &r.lay)) != 0 || (status = pick_layers(&r)) != 0)
        goto out;
    status = VT_EXIT_BAD_INPUT;
    if (start_build(&r, &err))
        goto out;
    if (o->output && (status = write_store(&r, &err)) != 0)
        goto out;
    status = VT_EXIT_BAD_INPUT;
    if (o->export_atlas && export_atlas(&r, &err))
        goto out;
    status = VT_EXIT_OK;
out:
    if (status == VT_EXIT_BAD_INPUT && err.status)
        vt_log(VT_LOG_ERROR, "%s", err.message);
    vt_tile_sink_destroy(r.sink);
    vts_writer_destroy(r.writer);
    vt_atlas_build_destroy(r.build);
    vt_layout_release(&r.lay);
    return status;
}
