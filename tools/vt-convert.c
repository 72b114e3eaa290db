/* vt-convert: re-encodes the tiles of a .vts store with another codec, keeping its geometry, index
 * structure (empty and shared tiles) and metadata. Reference: docs/cli/vt-convert.md. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tool_common.h"
#include "vt_atomic_file.h"
#include "vt_codec.h"
#include "vt_error.h"
#include "vt_filter.h"
#include "vt_output_path.h"
#include "vt_pool.h"
#include "vt_tile_sink.h"
#include "vts.h"
#include "vts_writer.h"

struct options {
    const char *in_path, *out_path, *codec_name;
    uint32_t quality, subsampling, layer, threads;
    uint64_t max_store;
    bool has_quality, has_subsampling, has_mode, has_layer, best;
};

enum {
    OPT_CODEC = 256,
    OPT_QUALITY,
    OPT_SUBSAMPLING,
    OPT_MODE,
    OPT_LAYER,
    OPT_MAX_STORE,
    OPT_VERSION
};

static const struct option long_options[] = {
    {"output", required_argument, NULL, 'o'},
    {"codec", required_argument, NULL, OPT_CODEC},
    {"quality", required_argument, NULL, OPT_QUALITY},
    {"subsampling", required_argument, NULL, OPT_SUBSAMPLING},
    {"mode", required_argument, NULL, OPT_MODE},
    {"layer", required_argument, NULL, OPT_LAYER},
    {"max-store-size", required_argument, NULL, OPT_MAX_STORE},
    {"threads", required_argument, NULL, 'j'},
    {"quiet", no_argument, NULL, 'q'},
    {"verbose", no_argument, NULL, 'v'},
    {"help", no_argument, NULL, 'h'},
    {"version", no_argument, NULL, OPT_VERSION},
    {NULL, 0, NULL, 0}};

static void usage(void)
{
    fputs(
        "usage: vt-convert IN.vts -o OUT.vts --codec CODEC [options]\n"
        "Re-encode the tiles of a .vts store with another codec. Geometry, empty tiles, shared\n"
        "payloads and metadata are kept; the conversion is added to the metadata as convert.N.\n"
        "\n"
        "  -o, --output FILE     the store to write (replaced only when complete); - for\n"
        "                        standard output (not a terminal; spooled in $TMPDIR, then\n"
        "                        copied)\n"
        "      --codec NAME      raw | png | jpeg | bc1 | bc3 | bc4 | bc5 (required)\n"
        "      --quality Q       jpeg quality, integer 1..100 (default 85)\n"
        "      --subsampling S   jpeg chroma subsampling, 420 | 444 (default 420)\n"
        "      --mode fast|best  png compression or bc1..bc5 encoder (default fast)\n"
        "      --layer N         convert only layer N (integer, 0..layers-1) and copy the others\n"
        "                        byte for byte (default: convert every layer)\n"
        "      --max-store-size S  refuse to write more tile bytes than S (suffix K, M, G, T;\n"
        "                        default 2T)\n"
        "  -j, --threads N       worker threads, integer 1..256 (default: all cores)\n"
        "  -q, --quiet           print errors only\n"
        "  -v, --verbose         print more (repeatable: info, then debug)\n"
        "  -h, --help            print this help and exit\n"
        "      --version         print the version and exit\n"
        "\n"
        "Samples: u16 tiles become u8 for jpeg and bc1..bc5 (rounded, with a warning); f16 and\n"
        "f32 tiles convert to raw only. jpeg refuses alpha; bc1..bc5 need a tile payload that\n"
        "is a multiple of 4; bc4 takes 1 channel, bc5 2 or a 3-channel normal map (z rebuilt).\n"
        "Re-encoding lossy tiles (jpeg, bc1..bc5) with a lossy codec warns.\n"
        "A store built with --filter nearest|mode|min|max (exact values) converts to png or\n"
        "raw only, keeping its sample type.\n"
        "The output is the same for every -j.\n"
        "Exit status: 0 ok, 1 bad input (unreadable or corrupt store, a tile that does not\n"
        "decode, a layer the codec cannot store, output not written), 2 bad usage (including a\n"
        "layer the store does not have).\n",
        stdout);
}

/* Returns an exit code when main should stop now (help, version, usage error), else -1. */
static int parse_options(int argc, char **argv, struct options *o)
{
    int c, verbosity = VT_LOG_WARN;
    *o = (struct options){.quality = 85,
                          .subsampling = 420,
                          .threads = vt_pool_cpu_count(),
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
        } else if (c == OPT_CODEC) {
            o->codec_name = optarg;
        } else if (c == OPT_QUALITY) {
            o->has_quality = true;
            if (vt_parse_u32(optarg, 1, 100, &o->quality) != 0)
                return vt_usage_error("--quality must be 1..100, not '%s'", optarg);
        } else if (c == OPT_SUBSAMPLING) {
            o->has_subsampling = true;
            if (strcmp(optarg, "420") != 0 && strcmp(optarg, "444") != 0)
                return vt_usage_error("--subsampling must be 420 or 444, not '%s'", optarg);
            o->subsampling = (uint32_t)atoi(optarg);
        } else if (c == OPT_MODE) {
            o->has_mode = true;
            if (strcmp(optarg, "fast") != 0 && strcmp(optarg, "best") != 0)
                return vt_usage_error("--mode must be fast or best, not '%s'", optarg);
            o->best = strcmp(optarg, "best") == 0;
        } else if (c == OPT_LAYER) {
            o->has_layer = true;
            if (vt_parse_u32(optarg, 0, UINT32_MAX, &o->layer) != 0)
                return vt_usage_error("--layer: '%s' is not a layer number", optarg);
        } else if (c == OPT_MAX_STORE) {
            if (vt_parse_size(optarg, &o->max_store) != 0 || o->max_store == 0)
                return vt_usage_error("--max-store-size: '%s' is not a size like 500G", optarg);
        } else if (c == 'j') {
            if (vt_parse_u32(optarg, 1, 256, &o->threads) != 0)
                return vt_usage_error("-j must be 1..256, not '%s'", optarg);
        } else {
            return vt_usage_getopt_error(c, argv);
        }
    }
    vt_log_set_level(verbosity);
    if (optind < argc)
        o->in_path = argv[optind++];
    if (optind < argc)
        return vt_usage_error("unexpected argument '%s' (one IN.vts at a time)", argv[optind]);
    return -1;
}

static int validate_options(const struct options *o, const struct vt_codec **codec)
{
    if (!o->in_path)
        return vt_usage_error("missing IN.vts argument");
    if (vt_output_path_is_stdio(o->in_path))
        return vt_usage_error("IN cannot be standard input ('-'): name the store (./- for a file "
                              "named -)");
    if (!o->out_path)
        return vt_usage_error("missing -o OUT.vts");
    if (!o->codec_name)
        return vt_usage_error("missing --codec (raw, png, jpeg, bc1, bc3, bc4, bc5)");
    if (!(*codec = vt_codec_find(o->codec_name)))
        return vt_usage_error("codec '%s' is not available (raw, png, jpeg, bc1, bc3, bc4, bc5)",
                              o->codec_name);
    uint32_t fourcc = (*codec)->fourcc;
    bool jpeg = fourcc == VTS_CODEC_JPEG;
    if ((o->has_quality || o->has_subsampling) && !jpeg)
        return vt_usage_error("%s applies to --codec jpeg only",
                              o->has_quality ? "--quality" : "--subsampling");
    if (o->has_mode && fourcc != VTS_CODEC_PNG && fourcc != VTS_CODEC_BC1 &&
        fourcc != VTS_CODEC_BC3 && fourcc != VTS_CODEC_BC4 && fourcc != VTS_CODEC_BC5)
        return vt_usage_error("--mode applies to --codec png and bc1..bc5 only");
    return 0;
}

/* ---- planning: what each layer becomes ---- */

struct layer_plan {
    const struct vt_codec *src_codec; /* NULL: the layer is copied byte for byte */
    struct vts_layer out;             /* the output's layer table entry */
};

struct worker {
    unsigned char *payload, *encoded; /* read and encode buffers */
    void *decoded, *narrowed;         /* the decoded tile; its u8 version for u16 -> u8 */
};

struct run {
    const struct options *o;
    const struct vt_codec *codec;
    struct vt_codec_params params;
    struct vts_store *in;
    struct vts_writer *out;
    struct layer_plan plans[VTS_MAX_LAYERS];
    struct vts_level levels[VTS_MAX_LEVELS];
    uint64_t tiles_per_layer, next_job, job_count, done; /* done: atomic */
    size_t payload_cap, tile_cap, encoded_cap;           /* per-worker buffer sizes */
    struct worker *workers;
    struct vt_progress progress;
};

/* Decides the output sample type and layer entry of a layer to convert; fails with the codec's
 * reason when it cannot store the layer. */
static int plan_layer(struct run *r, uint32_t layer, bool *lossy_warned, struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(r->in);
    const struct vts_layer *in = vts_store_layer(r->in, layer);
    struct layer_plan *p = &r->plans[layer];
    struct vts_error why = {0};
    char codec[5];
    uint32_t sample = in->sample, px = g->tile_payload_px;
    vts_codec_name(in->codec, codec);
    if (!(p->src_codec = vt_codec_by_fourcc(in->codec)))
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "'%s': layer %u uses codec '%s', which this build cannot decode",
                            vts_store_name(r->in), layer, codec);
    int rc = r->codec->check(px, in->channels, sample, &why);
    if (rc != 0 && sample == VTS_SAMPLE_U16 &&
        r->codec->check(px, in->channels, VTS_SAMPLE_U8, NULL) == 0) {
        sample = VTS_SAMPLE_U8;
        rc = 0;
        vt_log(VT_LOG_WARN, "'%s' layer %u: u16 samples stored as u8 for %s (rounded)",
               vts_store_name(r->in), layer, r->codec->name);
    }
    if (rc != 0)
        return vt_error_set(err, rc, "'%s' layer %u '%s' (%u channels, %s): %s",
                            vts_store_name(r->in), layer, in->name, in->channels,
                            vts_sample_name(in->sample), why.message);
    enum vt_filter_kind filter; /* a selection's values are exact: keep them so */
    if (vt_filter_parse(vts_store_meta_find(r->in, "filter"), &filter) == 0 &&
        vt_filter_is_selection(filter) && (!r->codec->lossless || sample != in->sample))
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "'%s' layer %u '%s': built with --filter %s (exact values), which %s "
                            "would change; use png or raw",
                            vts_store_name(r->in), layer, in->name, vt_filter_name(filter),
                            r->codec->name);
    if (!p->src_codec->lossless && !r->codec->lossless && !*lossy_warned) {
        vt_log(VT_LOG_WARN, "'%s' layer %u: re-encoding lossy %s tiles as %s loses quality twice",
               vts_store_name(r->in), layer, p->src_codec->name, r->codec->name);
        *lossy_warned = true;
    }
    p->out.codec = r->codec->fourcc;
    p->out.sample = (uint8_t)sample;
    p->out.codec_param = r->codec->fourcc == VTS_CODEC_JPEG ? r->o->quality : 0;
    size_t bytes = vts_layer_tile_bytes(g, in);
    size_t bound = r->codec->encoded_bound(px, px, in->channels, sample);
    r->tile_cap = bytes > r->tile_cap ? bytes : r->tile_cap;
    r->encoded_cap = bound > r->encoded_cap ? bound : r->encoded_cap;
    return 0;
}

static int plan(struct run *r, struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(r->in);
    bool lossy_warned = false;
    for (uint32_t level = 0; level < g->level_count; level++)
        vts_store_level(r->in, level, &r->levels[level]);
    r->tiles_per_layer = vts_geometry_tiles_per_layer(g);
    r->job_count = vts_store_tile_count(r->in);
    r->payload_cap = (size_t)vts_store_max_payload(r->in) + 1;
    for (uint32_t layer = 0; layer < g->layer_count; layer++) {
        r->plans[layer].out = *vts_store_layer(r->in, layer);
        if (r->o->has_layer && layer != r->o->layer)
            continue;
        int rc = plan_layer(r, layer, &lossy_warned, err);
        if (rc != 0)
            return rc;
    }
    return 0;
}

/* ---- the tile jobs ---- */

static void job_position(const struct run *r, uint64_t job, uint32_t *layer, uint32_t *level,
                         uint32_t *tx, uint32_t *ty)
{
    uint64_t t = job % r->tiles_per_layer;
    uint32_t l = 0;
    while (l + 1 < vts_store_geometry(r->in)->level_count && r->levels[l + 1].first_tile <= t)
        l++;
    t -= r->levels[l].first_tile;
    *layer = (uint32_t)(job / r->tiles_per_layer);
    *level = l;
    *tx = (uint32_t)(t % r->levels[l].tiles_x);
    *ty = (uint32_t)(t / r->levels[l].tiles_x);
}

/* u16 -> u8 with rounding: v8 = (v16 * 255 + 32767) / 65535. */
static void narrow_u16(const struct vt_image *src, struct vt_image *dst)
{
    size_t samples = (size_t)src->width * src->height * src->channels;
    const uint16_t *s = src->pixels;
    uint8_t *d = dst->pixels;
    for (size_t i = 0; i < samples; i++)
        d[i] = (uint8_t)(((uint32_t)s[i] * 255u + 32767u) / 65535u);
}

/* Decodes w->payload (len bytes) and encodes it into w->encoded; *len becomes the new length. */
static int transcode(const struct run *r, uint32_t layer, struct worker *w, size_t *len,
                     struct vts_error *err)
{
    const struct layer_plan *p = &r->plans[layer];
    uint32_t px = vts_store_geometry(r->in)->tile_payload_px, ch = p->out.channels;
    uint32_t in_sample = vts_store_layer(r->in, layer)->sample;
    struct vt_image src = {
        px, px, ch, in_sample, (size_t)px * ch * vts_sample_bytes(in_sample), w->decoded};
    int rc = p->src_codec->decode(w->payload, *len, &src, err);
    if (rc != 0)
        return rc;
    struct vt_image dst = src;
    if (p->out.sample != in_sample) {
        dst = (struct vt_image){px, px, ch, p->out.sample, (size_t)px * ch, w->narrowed};
        narrow_u16(&src, &dst);
    }
    return r->codec->encode(&dst, &r->params, w->encoded, r->encoded_cap, len, err);
}

static bool next_job(void *ctx, uint64_t *job)
{
    struct run *r = ctx;
    if (r->next_job >= r->job_count)
        return false;
    *job = r->next_job++;
    return true;
}

static int do_job(void *ctx, unsigned worker, uint64_t job, struct vts_error *err)
{
    struct run *r = ctx;
    struct worker *w = &r->workers[worker];
    struct vts_error why = {0};
    uint32_t layer, level, tx, ty;
    size_t len = 0;
    job_position(r, job, &layer, &level, &tx, &ty);
    int rc = vts_store_read(r->in, layer, level, tx, ty, w->payload, r->payload_cap, &len, 0, &why);
    bool convert = rc == 0 && len > 0 && r->plans[layer].src_codec;
    if (convert)
        rc = transcode(r, layer, w, &len, &why);
    if (rc == 0)
        rc = vts_writer_put(r->out, layer, level, tx, ty, convert ? w->encoded : w->payload, len,
                            &why);
    __atomic_add_fetch(&r->done, 1, __ATOMIC_RELAXED);
    if (rc == 0)
        return 0;
    return vt_error_set(err, rc, "'%s': layer %u level %u tile %u,%u: %s", vts_store_name(r->in),
                        layer, level, tx, ty,
                        rc == VTS_ERR_CHECKSUM ? "payload checksum mismatch" : why.message);
}

static int on_progress(void *ctx)
{
    struct run *r = ctx;
    vt_progress_update(&r->progress, __atomic_load_n(&r->done, __ATOMIC_RELAXED));
    return 0;
}

static int alloc_workers(struct run *r, struct vts_error *err)
{
    if (!(r->workers = calloc(r->o->threads, sizeof *r->workers)))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for workers");
    for (unsigned i = 0; i < r->o->threads; i++) {
        struct worker *w = &r->workers[i];
        w->payload = malloc(r->payload_cap);
        w->encoded = malloc(r->encoded_cap + 1);
        w->decoded = malloc(r->tile_cap + 1);
        w->narrowed = malloc(r->tile_cap + 1);
        if (!w->payload || !w->encoded || !w->decoded || !w->narrowed)
            return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for tile buffers");
    }
    return 0;
}

static void free_workers(struct run *r)
{
    for (unsigned i = 0; r->workers && i < r->o->threads; i++) {
        free(r->workers[i].payload);
        free(r->workers[i].encoded);
        free(r->workers[i].decoded);
        free(r->workers[i].narrowed);
    }
    free(r->workers);
}

/* Copies the input's metadata and adds convert.N (N one above the highest convert.N there):
 * "<codec>[ q<quality>[ 444]][ best] from <old codecs, '+' joined>[, layer N]". */
static int set_metadata(struct run *r, struct vts_error *err)
{
    char key[32], value[256], name[5];
    uint32_t n = 1, v;
    int rc = 0, len;
    for (uint32_t i = 0; rc == 0 && i < vts_store_meta_count(r->in); i++) {
        const char *k = vts_store_meta_key(r->in, i);
        if (strncmp(k, "convert.", 8) == 0 && vt_parse_u32(k + 8, 1, UINT32_MAX - 1, &v) == 0)
            n = v >= n ? v + 1 : n;
        rc = vts_writer_set_meta(r->out, k, vts_store_meta_value(r->in, i), err);
    }
    len = snprintf(value, sizeof value, "%s", r->codec->name);
    if (r->codec->fourcc == VTS_CODEC_JPEG)
        len += snprintf(value + len, sizeof value - (size_t)len, " q%u%s", r->o->quality,
                        r->o->subsampling == 444 ? " 444" : "");
    len += snprintf(value + len, sizeof value - (size_t)len, "%s from", r->o->best ? " best" : "");
    for (uint32_t layer = 0, first = 1; layer < vts_store_geometry(r->in)->layer_count; layer++) {
        const struct vts_layer *l = vts_store_layer(r->in, layer);
        bool seen = false;
        for (uint32_t j = 0; j < layer && !seen; j++)
            seen = r->plans[j].src_codec && vts_store_layer(r->in, j)->codec == l->codec;
        if (!r->plans[layer].src_codec || seen || len >= (int)sizeof value - 6)
            continue;
        vts_codec_name(l->codec, name);
        len += snprintf(value + len, sizeof value - (size_t)len, "%s%s", first ? " " : "+", name);
        first = 0;
    }
    if (r->o->has_layer && len < (int)sizeof value)
        snprintf(value + len, sizeof value - (size_t)len, ", layer %u", r->o->layer);
    snprintf(key, sizeof key, "convert.%u", n);
    return rc != 0 ? rc : vts_writer_set_meta(r->out, key, value, err);
}

static int convert(struct run *r, struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(r->in);
    struct vts_layer layers[VTS_MAX_LAYERS];
    int rc = plan(r, err);
    if (rc == 0)
        rc = alloc_workers(r, err);
    if (rc != 0)
        return rc;
    for (uint32_t layer = 0; layer < g->layer_count; layer++)
        layers[layer] = r->plans[layer].out;
    if (!(r->out = vts_writer_create(r->o->out_path, g, layers, err)))
        return err->status;
    vts_writer_set_max_bytes(r->out, r->o->max_store);
    struct vt_pool_fns fns = {next_job, do_job, on_progress};
    vt_progress_start(&r->progress, "converting", "tiles", r->job_count);
    rc = vt_pool_run(r->o->threads, &fns, r, err);
    vt_progress_end(&r->progress);
    if (rc == 0)
        rc = set_metadata(r, err);
    if (rc == 0)
        rc = vts_writer_finish(r->out, err);
    if (rc == 0) {
        struct vts_writer_stats st;
        vts_writer_stats(r->out, &st);
        vt_log(
            VT_LOG_INFO,
            "wrote '%s': %llu tiles stored (%llu shared), %llu empty, %llu payload bytes (input: %llu bytes)",
            r->o->out_path, (unsigned long long)st.tiles_stored,
            (unsigned long long)st.tiles_shared, (unsigned long long)st.tiles_empty,
            (unsigned long long)st.unique_bytes, (unsigned long long)vts_store_file_size(r->in));
    }
    return rc;
}

static int run(const struct options *o, const struct vt_codec *codec)
{
    struct vts_error err = {0};
    struct run r = {.o = o, .codec = codec};
    r.params = (struct vt_codec_params){(int)o->quality, vt_tile_sink_effort(codec, o->best),
                                        (int)o->subsampling};
    if (!(r.in = vts_open(o->in_path, &err))) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        return VT_EXIT_BAD_INPUT;
    }
    uint32_t layer_count = vts_store_geometry(r.in)->layer_count;
    int status = VT_EXIT_BAD_INPUT;
    if (o->has_layer && o->layer >= layer_count) {
        status = vt_usage_error("layer %u is outside '%s' (layers 0..%u)", o->layer, o->in_path,
                                layer_count - 1);
    } else if (convert(&r, &err) == 0) {
        status = VT_EXIT_OK;
    } else {
        vt_log(VT_LOG_ERROR, "%s", err.message);
    }
    vts_writer_destroy(r.out);
    free_workers(&r);
    vts_close(r.in);
    return status;
}

int main(int argc, char **argv)
{
    struct options o;
    const struct vt_codec *codec = NULL;
    vt_tool_init("vt-convert");
    vt_output_path_use_stdio(); /* -o - */
    vt_atomic_file_cleanup_on_signals();
    int rc = parse_options(argc, argv, &o);
    if (rc >= 0)
        return rc;
    rc = validate_options(&o, &codec);
    if (rc != 0)
        return rc;
    if ((rc = vt_refuse_terminal(o.out_path, STDOUT_FILENO, "a store")) >= 0)
        return rc;
    if (vt_output_path_is_stdio(o.out_path))
        vt_log_alias(VT_PATH_STDIO, VT_STDOUT_NAME);
    /* OUT may be IN itself (documented; scripts/vt.mk converts layer after layer in place): IN is
     * read through the open store and replaced only by the complete new one. A directory is not,
     * nor standard output when it is IN (written into, not replaced: the old bytes would stay
     * past the new store's end). */
    const char *inputs[] = {o.in_path};
    size_t input_count = vt_output_path_is_stdio(o.out_path) ? 1 : 0;
    if ((rc = vt_check_output(o.out_path, inputs, input_count)) >= 0)
        return rc;
    return run(&o, codec);
}
