/* vt-merge: joins .vts stores of identical geometry, as shards of one build or as layers, copying
 * payloads byte for byte one tile at a time; joins the shards of `vt-tiles --shard` and builds
 * their coarse levels. Reference: docs/cli/vt-merge.md, docs/sharding.md. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <sys/stat.h>

#include "tool_common.h"
#include "vt_atlas_build.h"
#include "vt_atomic_file.h"
#include "vt_codec.h"
#include "vt_error.h"
#include "vt_layout.h"
#include "vt_output_path.h"
#include "vt_pool.h"
#include "vt_pyramid.h"
#include "vt_pyramid_resume.h"
#include "vt_shard.h"
#include "vt_shard_merge.h"
#include "vt_tile_sink.h"
#include "vts.h"
#include "vts_writer.h"

struct vt_merge_options {
    char **inputs;
    int input_count;
    const char *out_path, *temp_dir;
    uint32_t threads;
    uint64_t max_store;
};

struct merge {
    const struct vt_merge_options *o;
    struct vts_store **in;
    struct vt_shard_merge set; /* the inputs, for lib/pyramid's shard checks and coarse levels */
    struct vts_writer *out;
    unsigned char *buf[2]; /* payload of the owner of a tile; another input's copy */
    size_t buf_cap;
    struct vt_progress progress;
    bool shard_build;     /* shards of vt-tiles --shard: they carry a float layer (vt_shard.h) */
    bool atlas;           /* shards of vt-tiles --layout --shard (shard.build carry=atlas) */
    uint32_t copy_layers; /* shards mode: layers copied (the float layer is not) */
    struct vt_tile_sink *sink; /* the coarse levels of a shard build */
};

enum { OPT_VERSION = 256, OPT_TEMP_DIR, OPT_MAX_STORE };

static const struct option long_options[] = {
    {"output", required_argument, NULL, 'o'},
    {"quiet", no_argument, NULL, 'q'},
    {"verbose", no_argument, NULL, 'v'},
    {"help", no_argument, NULL, 'h'},
    {"threads", required_argument, NULL, 'j'},
    {"temp-dir", required_argument, NULL, OPT_TEMP_DIR},
    {"max-store-size", required_argument, NULL, OPT_MAX_STORE},
    {"version", no_argument, NULL, OPT_VERSION},
    {NULL, 0, NULL, 0}};

static void usage(void)
{
    fputs("usage: vt-merge A.vts [B.vts...] -o OUT.vts [-j N] [--temp-dir DIR] [-q|-v]\n"
          "Join .vts stores of identical geometry into one, copying payloads byte for byte.\n"
          "The mode follows from the inputs:\n"
          "  shards  every input has the same layer table: the output holds each tile that an\n"
          "          input stores (a tile stored by several inputs must have the same bytes in\n"
          "          each), the others stay empty\n"
          "  layers  the layer tables differ: the output has the layers of every input in\n"
          "          argument order (names must be unique; at most 64 layers)\n"
          "Shards of `vt-tiles --shard I/N` (all N of them, in any order) are joined and their\n"
          "coarse levels built: the output is the single-process build, byte for byte.\n"
          "\n"
          "  -o, --output FILE   the store to write (replaced only when complete); - for\n"
          "                      standard output (not a terminal; spooled in $TMPDIR, then\n"
          "                      copied)\n"
          "  -j, --threads N     worker threads for the coarse levels (default: all cores)\n"
          "      --temp-dir DIR  where the coarse levels' pass images go (default: the output's\n"
          "                      directory)\n"
          "      --max-store-size S  refuse to write more tile bytes than S (suffix K, M, G,\n"
          "                      T; default 2T)\n"
          "  -q, --quiet         print errors only\n"
          "  -v, --verbose       print more (repeatable: info, then debug)\n"
          "  -h, --help          print this help and exit\n"
          "      --version       print the version and exit\n"
          "\n"
          "Metadata: the first input's, plus merge.sources=<the inputs, space separated>. When\n"
          "the inputs are shards 1/N..N/N of one build (metadata shard=I/N, the rest identical),\n"
          "the output has their common metadata without shard and nothing added: it is the\n"
          "single build, byte for byte.\n"
          "Exit status: 0 ok, 1 bad input (unreadable or corrupt store, geometry mismatch,\n"
          "duplicate layer name, a tile stored with different bytes in two inputs, output not\n"
          "written), 2 bad usage.\n",
          stdout);
}

/* Returns an exit code when main should stop now (help, version, usage error), else -1. */
static int parse_options(int argc, char **argv, struct vt_merge_options *o)
{
    int c, verbosity = VT_LOG_WARN;
    *o = (struct vt_merge_options){.threads = vt_pool_cpu_count(),
                                   .max_store = VT_DEFAULT_MAX_STORE};
    opterr = 0;
    while ((c = vt_getopt_long(argc, argv, ":hqvo:j:", long_options)) != -1) {
        if (c == 'h') {
            usage();
            return VT_EXIT_OK;
        } else if (c == OPT_VERSION) {
            vt_print_version(stdout);
            return VT_EXIT_OK;
        } else if (c == 'q' || c == 'v') {
            verbosity = c == 'q' ? VT_LOG_ERROR : verbosity + 1;
        } else if (c == 'o') {
            o->out_path = optarg;
        } else if (c == 'j') {
            if (vt_parse_u32(optarg, 1, 256, &o->threads))
                return vt_usage_error("-j must be 1..256, not '%s'", optarg);
        } else if (c == OPT_TEMP_DIR) {
            o->temp_dir = optarg;
        } else if (c == OPT_MAX_STORE) {
            if (vt_parse_size(optarg, &o->max_store) || o->max_store == 0)
                return vt_usage_error("--max-store-size: '%s' is not a size like 500G", optarg);
        } else {
            return vt_usage_getopt_error(c, argv);
        }
    }
    vt_log_set_level(verbosity);
    o->inputs = argv + optind;
    o->input_count = argc - optind;
    if (o->input_count == 0)
        return vt_usage_error("missing input stores");
    if (!o->out_path)
        return vt_usage_error("missing -o OUT.vts");
    for (int k = 0; k < o->input_count; k++)
        if (vt_output_path_is_stdio(o->inputs[k]))
            return vt_usage_error("an input cannot be standard input ('-'): name the store (./- "
                                  "for a file named -)");
    return -1;
}

/* ---- checks: geometry, layer tables, mode ---- */

static int check_geometry(const struct merge *m, int k, struct vts_error *err)
{
    const struct vts_geometry *a = vts_store_geometry(m->in[0]), *b = vts_store_geometry(m->in[k]);
    const char *names[] = {"width",     "height",          "tile_content_px",
                           "border_px", "tile_payload_px", "level_count",
                           "flags"};
    const uint32_t va[] = {a->width,     a->height,          a->tile_content_px,
                           a->border_px, a->tile_payload_px, a->level_count,
                           a->flags};
    const uint32_t vb[] = {b->width,     b->height,          b->tile_content_px,
                           b->border_px, b->tile_payload_px, b->level_count,
                           b->flags};
    for (size_t i = 0; i < sizeof va / sizeof va[0]; i++)
        if (va[i] != vb[i])
            return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': %s %u != %u in '%s'",
                                m->o->inputs[k], names[i], vb[i], va[i], m->o->inputs[0]);
    return 0;
}

/* Describes the first field in which two layer entries differ into out ("" when equal). */
static void layer_difference(const struct vts_layer *a, const struct vts_layer *b, char *out,
                             size_t cap)
{
    char ca[5], cb[5];
    vts_codec_name(a->codec, ca);
    vts_codec_name(b->codec, cb);
    out[0] = '\0';
    if (a->codec != b->codec)
        snprintf(out, cap, "codec %s != %s", cb, ca);
    else if (a->channels != b->channels)
        snprintf(out, cap, "channels %u != %u", b->channels, a->channels);
    else if (a->sample != b->sample)
        snprintf(out, cap, "sample %s != %s", vts_sample_name(b->sample),
                 vts_sample_name(a->sample));
    else if (a->colour != b->colour)
        snprintf(out, cap, "colour %s != %s", vts_colour_name(b->colour),
                 vts_colour_name(a->colour));
    else if (a->flags != b->flags || a->codec_param != b->codec_param)
        snprintf(out, cap, "%s %u != %u", a->flags != b->flags ? "flags" : "codec_param",
                 a->flags != b->flags ? b->flags : b->codec_param,
                 a->flags != b->flags ? a->flags : a->codec_param);
    else if (strncmp(a->name, b->name, VTS_LAYER_NAME_BYTES) != 0)
        snprintf(out, cap, "name '%s' != '%s'", b->name, a->name);
}

static bool same_layer_table(const struct vts_store *a, const struct vts_store *b)
{
    char diff[128];
    if (vts_store_geometry(a)->layer_count != vts_store_geometry(b)->layer_count)
        return false;
    for (uint32_t i = 0; i < vts_store_geometry(a)->layer_count; i++) {
        layer_difference(vts_store_layer(a, i), vts_store_layer(b, i), diff, sizeof diff);
        if (diff[0])
            return false;
    }
    return true;
}

/* Layers mode: every layer name once, at most VTS_MAX_LAYERS layers in all. */
static int check_layer_names(const struct merge *m, struct vts_error *err)
{
    uint32_t total = 0;
    char diff[128];
    for (int k = 0; k < m->o->input_count; k++) {
        const struct vts_geometry *g = vts_store_geometry(m->in[k]);
        total += g->layer_count;
        for (uint32_t i = 0; i < g->layer_count; i++)
            for (int j = 0; j <= k; j++)
                for (uint32_t l = 0; l < (j < k ? vts_store_geometry(m->in[j])->layer_count : i);
                     l++) {
                    const struct vts_layer *a = vts_store_layer(m->in[j], l);
                    const struct vts_layer *b = vts_store_layer(m->in[k], i);
                    if (strncmp(a->name, b->name, VTS_LAYER_NAME_BYTES) != 0)
                        continue;
                    layer_difference(a, b, diff, sizeof diff);
                    return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                        "layer name '%s' is in both '%s' and '%s'%s%s%s", a->name,
                                        m->o->inputs[j], m->o->inputs[k],
                                        diff[0] ? " (as shards, their layers differ: " : "", diff,
                                        diff[0] ? ")" : "");
                }
    }
    if (total > VTS_MAX_LAYERS)
        return vt_error_set(err, VTS_ERR_LIMIT, "the inputs have %u layers in all, more than %u",
                            total, VTS_MAX_LAYERS);
    return 0;
}

static int set_metadata(struct merge *m, bool shards, struct vts_error *err)
{
    bool single_build = shards && vt_shard_merge_is_single_build(&m->set);
    size_t len = 0, cap = 1;
    int rc = 0;
    for (uint32_t i = 0; rc == 0 && i < vts_store_meta_count(m->in[0]); i++) {
        const char *key = vts_store_meta_key(m->in[0], i);
        if (single_build && strcmp(key, VT_SHARD_RANGE_KEY) == 0) { /* the union, as "range" */
            char range[VTS_MAX_LAYERS * 40];
            int any = vt_shard_merge_range(&m->set, range, sizeof range);
            if (any < 0)
                rc = vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': bad %s metadata", m->o->inputs[0],
                                  VT_SHARD_RANGE_KEY);
            else if (any)
                rc = vts_writer_set_meta(m->out, "range", range, err);
        } else if (!single_build || !vt_shard_merge_drops_key(key, m->shard_build))
            rc = vts_writer_set_meta(m->out, key, vts_store_meta_value(m->in[0], i), err);
    }
    if (rc != 0 || single_build) {
        if (single_build)
            vt_log(VT_LOG_INFO, "the inputs are shards 1..%d of one build: metadata of the build",
                   m->o->input_count);
        return rc;
    }
    for (int k = 0; k < m->o->input_count; k++)
        cap += strlen(m->o->inputs[k]) + 1;
    char *sources = malloc(cap);
    if (!sources)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for metadata");
    for (int k = 0; k < m->o->input_count; k++)
        len += (size_t)snprintf(sources + len, cap - len, "%s%s", k ? " " : "", m->o->inputs[k]);
    rc = vts_writer_set_meta(m->out, "merge.sources", sources, err);
    free(sources);
    return rc;
}

/* ---- copying tiles ---- */

/* Visits every tile of the first input's geometry: shards mode (k < 0) takes the payload of the
 * first input that stores it (any other input that stores it must hold the same bytes; none:
 * empty, unless the coarse levels of a shard build come later), layers mode copies it from input
 * k to output layer base + layer. */
static int copy_tiles(struct merge *m, int k, uint32_t base, uint64_t *done, struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(m->in[k < 0 ? 0 : k]);
    uint64_t index = 0;
    int rc = 0, owner = k;
    uint32_t layers = k < 0 ? m->copy_layers : g->layer_count;
    for (uint32_t layer = 0; layer < layers && rc == 0; layer++)
        for (uint32_t level = 0; level < g->level_count && rc == 0; level++) {
            struct vts_level L;
            vts_store_level(m->in[k < 0 ? 0 : k], level, &L);
            for (uint32_t ty = 0; ty < L.tiles_y && rc == 0; ty++)
                for (uint32_t tx = 0; tx < L.tiles_x && rc == 0; tx++, index++) {
                    size_t len = 0;
                    if (k < 0)
                        rc = vt_shard_merge_tile(&m->set, index, layer, level, tx, ty, m->buf,
                                                 m->buf_cap, &owner, &len, err);
                    else if (vts_store_entry(m->in[k], index)->length > 0)
                        rc = vt_shard_merge_read(&m->set, k, layer, level, tx, ty, m->buf[0],
                                                 m->buf_cap, &len, err);
                    if (rc == 0 && !(m->shard_build && owner < 0))
                        rc = vts_writer_put(m->out, base + layer, level, tx, ty, m->buf[0], len,
                                            err);
                    vt_progress_update(&m->progress, ++*done);
                }
        }
    return rc;
}

static int create_writer(struct merge *m, bool shards, struct vts_error *err)
{
    struct vts_geometry g = *vts_store_geometry(m->in[0]);
    struct vts_layer layers[VTS_MAX_LAYERS];
    g.layer_count = 0;
    for (int k = 0; k < (shards ? 1 : m->o->input_count); k++)
        for (uint32_t i = 0;
             i < (shards ? m->copy_layers : vts_store_geometry(m->in[k])->layer_count); i++)
            layers[g.layer_count++] = *vts_store_layer(m->in[k], i);
    m->out = vts_writer_create(m->o->out_path, &g, layers, err);
    if (m->out)
        vts_writer_set_max_bytes(m->out, m->o->max_store);
    return m->out ? 0 : err->status;
}

/* ---- the coarse levels of a vt-tiles --shard set ---- */

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

/* ---- the coarse levels of a vt-tiles --layout --shard set ---- */

static int emit_atlas_tile(void *user, unsigned worker, uint32_t slot, uint32_t level, uint32_t tx,
                           uint32_t ty, const struct vt_image *payload, struct vts_error *err)
{
    struct merge *m = user;
    return vt_tile_sink_put(m->sink, worker, slot, level, tx, ty, payload, err);
}

static int no_texture(void *user, const char *path, struct vt_source *out, struct vts_error *err)
{
    (void)user;
    (void)out;
    return vt_error_set(err, VTS_ERR_ARG, "'%s': the merge reads no texture", path);
}

/* The layout the shards read (metadata "layout", as they named it; the same size and time). */
static int read_shards_layout(const struct merge *m, struct vt_layout *lay, struct vts_error *err)
{
    const char *path = vts_store_meta_find(m->in[0], "layout");
    const char *id = vts_store_meta_find(m->in[0], VT_SHARD_INPUT_KEY);
    char now[96];
    struct stat st;
    if (!path || !id)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': an atlas shard without layout metadata",
                            m->o->inputs[0]);
    if (stat(path, &st) != 0)
        return vt_error_set(err, VTS_ERR_IO,
                            "'%s': the shards' layout is not there (run vt-merge where the path "
                            "the shards recorded leads to it)",
                            path);
    snprintf(now, sizeof now, "size=%lld mtime=%lld", (long long)st.st_size,
             (long long)st.st_mtime);
    if (strcmp(now, id) != 0)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "'%s' changed since the shards read it (%s, now %s)", path, id, now);
    return vt_layout_read(path, NULL, lay, err);
}

/* The levels above the shards' carried level K, from their carried payloads (lib/compose:
 * vt_atlas_build_part): the single build's tiles, encoded as the shards recorded. */
static int build_atlas_coarse(struct merge *m, struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(m->in[0]);
    unsigned level, quality, sub, best, index, count;
    int used = 0;
    if (sscanf(vts_store_meta_find(m->in[0], VT_SHARD_BUILD_KEY),
               "carry=atlas level=%u quality=%u subsampling=%u best=%u%n", &level, &quality, &sub,
               &best, &used) != 4 ||
        vts_store_meta_find(m->in[0], VT_SHARD_BUILD_KEY)[used] != '\0' ||
        vt_shard_parse(vts_store_meta_find(m->in[0], VT_SHARD_KEY), &index, &count))
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': not a well-formed atlas shard (%s)",
                            m->o->inputs[0], VT_SHARD_BUILD_KEY);
    struct vt_layout lay;
    int rc = read_shards_layout(m, &lay, err);
    uint32_t slots[VT_LAYOUT_MAX_LAYERS];
    struct vt_atlas_layer_format formats[VT_LAYOUT_MAX_LAYERS];
    struct vt_tile_sink_layer sinks[VT_LAYOUT_MAX_LAYERS];
    if (rc == 0 && (lay.width != g->width || lay.height != g->height ||
                    lay.tile_content != g->tile_content_px || lay.border != g->border_px ||
                    m->copy_layers > VT_LAYOUT_MAX_LAYERS))
        rc = vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': the shards are not of this layout",
                          vts_store_meta_find(m->in[0], "layout"));
    for (uint32_t s = 0; rc == 0 && s < m->copy_layers; s++) {
        const struct vts_layer *L = vts_store_layer(m->in[0], s);
        int li = vt_layout_layer_index(&lay, L->name);
        bool alpha = L->channels == 2 || L->channels == 4;
        slots[s] = (uint32_t)li;
        formats[s] =
            (struct vt_atlas_layer_format){.channels = L->channels,
                                           .colour_channels = L->channels - (alpha ? 1u : 0u),
                                           .alpha = alpha,
                                           .colour = L->colour,
                                           .sample = L->sample};
        const struct vt_codec *codec = vt_codec_by_fourcc(L->codec);
        sinks[s] = (struct vt_tile_sink_layer){
            codec,
            {(int)quality, codec ? vt_tile_sink_effort(codec, best != 0) : 0, (int)sub},
            L->channels,
            L->sample};
        if (li < 0 || !codec)
            rc = vt_error_set(err, VTS_ERR_BAD_INPUT,
                              "'%s': layer '%s' is not one of the layout's, or its codec is not "
                              "available",
                              m->o->inputs[0], L->name);
    }
    char dir[VT_PATH_MAX];
    if (rc == 0)
        rc = vt_output_path_scratch_dir(m->o->out_path, dir, sizeof dir, err);
    struct vt_atlas_build_options bo = {.layout = &lay,
                                        .layers = slots,
                                        .layer_count = m->copy_layers,
                                        .level_count = g->level_count,
                                        .threads = m->o->threads,
                                        .temp_dir = m->o->temp_dir ? m->o->temp_dir : dir,
                                        .open = no_texture,
                                        .progress = coarse_progress,
                                        .progress_user = m,
                                        .part = {0, count, true, formats}};
    struct vt_atlas_build *b = rc == 0 ? vt_atlas_build_create(&bo, err) : NULL;
    if (rc == 0 && !b)
        rc = err->status;
    if (rc == 0 && vt_atlas_build_level_count(b) != g->level_count)
        rc = vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': level count %u, the layout gives %u",
                          m->o->inputs[0], g->level_count, vt_atlas_build_level_count(b));
    if (rc == 0 && vt_atlas_build_carried_level(b) != level)
        rc = vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': carried level %u, expected %u",
                          m->o->inputs[0], level, vt_atlas_build_carried_level(b));
    if (rc != 0 || !vt_atlas_build_carries(b)) { /* the shards made every level */
        vt_atlas_build_destroy(b);
        vt_layout_release(&lay);
        return rc;
    }
    for (int k = 0; rc == 0 && k < m->o->input_count; k++) {
        vt_shard_parse(vts_store_meta_find(m->in[k], VT_SHARD_KEY), &index, &count);
        uint32_t px, py;
        size_t len = 0;
        if (!vt_atlas_build_part_tile(b, index - 1, &px, &py))
            continue; /* a part past the atlas: nothing */
        rc = vt_shard_merge_read(&m->set, k, m->copy_layers, level, px, py, m->buf[0], m->buf_cap,
                                 &len, err);
        if (rc == 0 && len == 0)
            rc = vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': no carried data (level %u tile %u,%u)",
                              m->o->inputs[k], level, px, py);
        struct vts_error why = {0};
        if (rc == 0 && vt_atlas_build_put_carry(b, index - 1, m->buf[0], len, &why))
            rc = vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': %s", m->o->inputs[k], why.message);
    }
    if (rc == 0 && !(m->sink = vt_tile_sink_create(m->out, g->tile_payload_px, sinks,
                                                   m->copy_layers, m->o->threads, 0, err)))
        rc = err->status;
    if (rc == 0) {
        vt_log(VT_LOG_INFO, "building levels %u..%u of the atlas from the shards' level %u",
               level + 1, g->level_count - 1, level);
        vt_progress_start(&m->progress, "coarse levels", "tiles", vt_atlas_build_tile_count(b));
        rc = vt_atlas_build_tiles(b, emit_atlas_tile, m, err);
        vt_progress_end(&m->progress);
    }
    vt_atlas_build_destroy(b);
    vt_layout_release(&lay);
    return rc;
}

/* Builds the levels above the shards' first pass (with wrap) or the tiles along their seams
 * (without) from their carried texels, with the options the shards recorded (lib/pyramid:
 * vt_shard_merge, vt_pyramid_resume, vt_shard_seams): the same bytes as the single build's passes,
 * encoded with the codec and effort the shards recorded. */
static int build_coarse(struct merge *m, struct vts_error *err)
{
    if (m->atlas)
        return build_atlas_coarse(m, err);
    const struct vts_layer *L = vts_store_layer(m->in[0], 0);
    struct vt_pyramid_options po;
    struct vt_source_info input;
    struct vt_shard_build sb;
    int rc = vt_shard_merge_options(&m->set, &po, &input, &sb, err);
    if (rc)
        return rc;
    struct vt_tile_sink_layer sink_layer = {
        vt_codec_by_fourcc(L->codec),
        {L->codec == VTS_CODEC_JPEG ? (int)L->codec_param : 0, (int)sb.effort, (int)sb.subsampling},
        L->channels,
        L->sample};
    if (!sink_layer.codec)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "'%s': codec of layer 0 is not available",
                            m->o->inputs[0]);
    char dir[VT_PATH_MAX];
    rc = vt_output_path_scratch_dir(m->o->out_path, dir, sizeof dir, err);
    if (rc != 0)
        return rc;
    po.threads = m->o->threads;
    po.temp_dir = m->o->temp_dir ? m->o->temp_dir : dir;
    po.emit = emit_coarse_tile;
    po.progress = coarse_progress;
    po.user = m;
    struct vt_pyramid_plan plan;
    vt_pyramid_plan(&po, &plan);
    if (!plan.has_next) /* the shards' first pass made every level */
        return 0;
    struct vt_pyramid_resume *resume = NULL;
    if (!(m->sink = vt_tile_sink_create(m->out, vts_store_geometry(m->in[0])->tile_payload_px,
                                        &sink_layer, 1, po.threads, 0, err)))
        return err->status;
    if (sb.seams) { /* the shards built the levels above but along their seams */
        uint64_t tiles = vt_shard_merge_seam_tiles(&m->set, &po);
        vt_log(VT_LOG_INFO, "building the %llu tiles along the seams of levels %u..%u",
               (unsigned long long)tiles, plan.levels_per_pass + 1, po.level_count - 1);
        vt_progress_start(&m->progress, "seams", "tiles", tiles);
        rc = vt_shard_merge_seams(&m->set, &po, err);
        vt_progress_end(&m->progress);
        return rc;
    }
    if (!(resume = vt_shard_merge_assemble(&m->set, &po, err)))
        return err->status;
    vt_log(VT_LOG_INFO, "building levels %u..%u from the shards' level %u (%ux%u)",
           plan.levels_per_pass + 1, po.level_count - 1, plan.levels_per_pass, plan.carry_width,
           plan.carry_height);
    vt_progress_start(&m->progress, "coarse levels", "tiles", vt_pyramid_tile_count(&po));
    rc = vt_pyramid_resume_run(resume, err);
    vt_progress_end(&m->progress);
    vt_pyramid_resume_destroy(resume);
    return rc;
}

static int merge(struct merge *m, struct vts_error *err)
{
    bool shards = true;
    uint64_t done = 0, total = 0;
    int rc = 0;
    for (int k = 0; k < m->o->input_count; k++) {
        if (!(m->in[k] = vts_open(m->o->inputs[k], err)))
            return err->status;
        m->shard_build = m->shard_build || vts_store_meta_find(m->in[k], VT_SHARD_BUILD_KEY);
    }
    m->set = (struct vt_shard_merge){m->in, (const char *const *)m->o->inputs, m->o->input_count};
    if (m->shard_build) /* vt-tiles --shard: all the shards of one build, or nothing */
        rc = vt_shard_merge_check(&m->set, err);
    if (rc == 0 && m->shard_build)
        m->atlas =
            strncmp(vts_store_meta_find(m->in[0], VT_SHARD_BUILD_KEY), "carry=atlas ", 12) == 0;
    for (int k = 0; k < m->o->input_count && rc == 0; k++) {
        rc = check_geometry(m, k, err);
        shards = shards && same_layer_table(m->in[0], m->in[k]);
        total += vts_store_tile_count(m->in[k]);
        m->buf_cap = vts_store_max_payload(m->in[k]) > m->buf_cap ? vts_store_max_payload(m->in[k])
                                                                  : m->buf_cap;
    }
    m->copy_layers = vts_store_geometry(m->in[0])->layer_count - (m->shard_build ? 1 : 0);
    if (rc == 0 && m->shard_build && (!shards || (m->copy_layers != 1 && !m->atlas)))
        rc = vt_error_set(err, VTS_ERR_BAD_INPUT,
                          "the shards' layer tables differ or are not vt-tiles --shard's");
    if (rc == 0 && !shards)
        rc = check_layer_names(m, err);
    if (rc == 0 && (!(m->buf[0] = malloc(m->buf_cap + 1)) || !(m->buf[1] = malloc(m->buf_cap + 1))))
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory for tile buffers");
    if (rc == 0)
        rc = create_writer(m, shards, err);
    if (rc != 0)
        return rc;
    if (shards)
        vt_log(VT_LOG_INFO, "merging %d inputs as shards (same geometry and layers)",
               m->o->input_count);
    else
        vt_log(VT_LOG_INFO, "merging the layers of %d inputs", m->o->input_count);
    total = shards ? vts_store_tile_count(m->in[0]) / vts_store_geometry(m->in[0])->layer_count *
                         m->copy_layers
                   : total;
    vt_progress_start(&m->progress, "merging", "tiles", total);
    if (shards)
        rc = copy_tiles(m, -1, 0, &done, err);
    for (int k = 0, base = 0; !shards && rc == 0 && k < m->o->input_count; k++) {
        rc = copy_tiles(m, k, (uint32_t)base, &done, err);
        base += (int)vts_store_geometry(m->in[k])->layer_count;
    }
    vt_progress_end(&m->progress);
    if (rc == 0 && m->shard_build)
        rc = build_coarse(m, err);
    if (rc == 0)
        rc = set_metadata(m, shards, err);
    return rc == 0 ? vts_writer_finish(m->out, err) : rc;
}

static int run(const struct vt_merge_options *o)
{
    struct vts_error err = {0};
    struct merge m = {.o = o, .in = calloc((size_t)o->input_count, sizeof *m.in)};
    int rc = m.in ? merge(&m, &err) : vt_error_set(&err, VTS_ERR_NOMEM, "out of memory");
    if (rc == 0) {
        struct vts_writer_stats st;
        vts_writer_stats(m.out, &st);
        vt_log(VT_LOG_INFO,
               "wrote '%s': %llu tiles stored (%llu shared), %llu empty, %llu payload bytes",
               o->out_path, (unsigned long long)st.tiles_stored,
               (unsigned long long)st.tiles_shared, (unsigned long long)st.tiles_empty,
               (unsigned long long)st.unique_bytes);
    } else {
        vt_log(VT_LOG_ERROR, "%s", err.message);
    }
    vt_tile_sink_destroy(m.sink);
    vts_writer_destroy(m.out);
    for (int k = 0; m.in && k < o->input_count; k++)
        vts_close(m.in[k]);
    free(m.in);
    free(m.buf[0]);
    free(m.buf[1]);
    return rc == 0 ? VT_EXIT_OK : VT_EXIT_BAD_INPUT;
}

int main(int argc, char **argv)
{
    struct vt_merge_options o;
    vt_tool_init("vt-merge");
    vt_output_path_use_stdio(); /* -o - */
    vt_atomic_file_cleanup_on_signals();
    int rc = parse_options(argc, argv, &o);
    if (rc >= 0)
        return rc;
    if ((rc = vt_refuse_terminal(o.out_path, STDOUT_FILENO, "a store")) >= 0)
        return rc;
    if (vt_output_path_is_stdio(o.out_path))
        vt_log_alias(VT_PATH_STDIO, VT_STDOUT_NAME);
    if ((rc = vt_check_output(o.out_path, (const char *const *)o.inputs, (size_t)o.input_count)) >=
        0)
        return rc;
    return run(&o);
}
