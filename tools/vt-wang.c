/* vt-wang SAMPLE -o PACK.vts: a Wang tile pack made from a sample texture (docs/cli/vt-wang.md,
 * docs/wang.md). The tiles come from lib/wang; the pack image is tiled into a store through the
 * pyramid and the tile sink as vt-tiles does (with wrap: the pack tiles seamlessly). */
#include <getopt.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tool_common.h"
#include "vt_codec.h"
#include "vt_image_input.h"
#include "vt_output_path.h"
#include "vt_pool.h"
#include "vt_pyramid.h"
#include "vt_tile_sink.h"
#include "vt_version.h"
#include "vt_wang.h"
#include "vts_writer.h"

static const char usage_text[] =
    "usage: vt-wang SAMPLE -o PACK.vts [options]\n"
    "Makes a Wang tile set from a sample texture (one patch per edge colour, tiles stitched along\n"
    "minimum-error cuts) and writes it packed for hardware filtering (Wei's TileIndex) as a store\n"
    "with its mip levels; vt-view --wang draws an arbitrarily large texture from it.\n"
    "  -o, --output PACK.vts    the pack (required)\n"
    "      --tile N             Wang tile edge in texels, even, 8..4096 (default 256)\n"
    "      --colours KhxKv      edge colours of horizontal (N, S) and vertical (W, E) edges,\n"
    "                           1..16 each (default 2x2: 16 tiles)\n"
    "      --corners            corner-coloured tiles instead (K^4 tiles, --colours KxK)\n"
    "      --seed N             patch positions and hash permutation (default 1)\n"
    "      --hash N             entries of the hash permutation, 1..65536: the output repeats\n"
    "                           every N tiles (default 4096)\n"
    "      --shuffle N          tiles in an arbitrary order (seed N; Wei's figure 5: filtering\n"
    "                           across tile edges then reads wrong neighbours)\n"
    "      --store-tile N       store tile payload edge, 8..1024 (default 256)\n"
    "      --border N           store tile border texels, 0..64 (default 4)\n"
    "      --filter NAME        mip filter: box | triangle | lanczos3 | kaiser (default box)\n"
    "      --codec NAME         raw | png | jpeg | bc1 | bc3 | auto (default auto: jpeg)\n"
    "      --quality Q          jpeg quality 1..100 (default 90)\n"
    "  -j, --threads N          worker threads (default: all cores)\n"
    "  -q, --quiet              errors only\n"
    "  -v, --verbose            more messages\n"
    "  -h, --help               this help;    --version  version\n";

enum {
    OPT_TILE = 256,
    OPT_COLOURS,
    OPT_CORNERS,
    OPT_SEED,
    OPT_HASH,
    OPT_SHUFFLE,
    OPT_STORE_TILE,
    OPT_BORDER,
    OPT_FILTER,
    OPT_CODEC,
    OPT_QUALITY,
    OPT_VERSION
};

static const struct option long_options[] = {{"output", required_argument, 0, 'o'},
                                             {"tile", required_argument, 0, OPT_TILE},
                                             {"colours", required_argument, 0, OPT_COLOURS},
                                             {"corners", no_argument, 0, OPT_CORNERS},
                                             {"seed", required_argument, 0, OPT_SEED},
                                             {"hash", required_argument, 0, OPT_HASH},
                                             {"shuffle", required_argument, 0, OPT_SHUFFLE},
                                             {"store-tile", required_argument, 0, OPT_STORE_TILE},
                                             {"border", required_argument, 0, OPT_BORDER},
                                             {"filter", required_argument, 0, OPT_FILTER},
                                             {"codec", required_argument, 0, OPT_CODEC},
                                             {"quality", required_argument, 0, OPT_QUALITY},
                                             {"threads", required_argument, 0, 'j'},
                                             {"quiet", no_argument, 0, 'q'},
                                             {"verbose", no_argument, 0, 'v'},
                                             {"help", no_argument, 0, 'h'},
                                             {"version", no_argument, 0, OPT_VERSION},
                                             {0, 0, 0, 0}};

struct options {
    const char *input, *output, *codec_name;
    struct vt_wang_params wang;
    uint32_t hash_n, store_tile, border, quality, threads;
    enum vt_filter_kind filter;
};

/* Returns -1 to continue, or an exit status. */
static int parse_options(int argc, char **argv, struct options *o)
{
    *o = (struct options){.codec_name = "auto",
                          .wang = {256, 2, 2, false, 1, false, 0},
                          .hash_n = 4096,
                          .store_tile = 256,
                          .border = 4,
                          .quality = 90,
                          .threads = vt_pool_cpu_count(),
                          .filter = VT_FILTER_BOX};
    int c, status;
    uint32_t seed;
    opterr = 0;
    while ((c = vt_getopt_long(argc, argv, ":o:j:qvh", long_options)) != -1) {
        switch (c) {
        case 'o':
            o->output = optarg;
            break;
        case OPT_TILE:
            if (vt_parse_u32(optarg, 8, 4096, &o->wang.tile_px) || o->wang.tile_px % 2)
                return vt_usage_error("--tile must be an even 8..4096, not '%s'", optarg);
            break;
        case OPT_COLOURS:
            if (vt_parse_u32_pair(optarg, 'x', 1, VTS_WANG_MAX_COLOURS, &o->wang.kh, &o->wang.kv))
                return vt_usage_error("--colours must be KhxKv with 1..%u each, not '%s'",
                                      VTS_WANG_MAX_COLOURS, optarg);
            break;
        case OPT_CORNERS:
            o->wang.corners = true;
            break;
        case OPT_SEED:
            if (vt_parse_u32(optarg, 0, UINT32_MAX, &seed))
                return vt_usage_error("--seed must be 0..%u, not '%s'", UINT32_MAX, optarg);
            o->wang.seed = seed;
            break;
        case OPT_HASH:
            if (vt_parse_u32(optarg, 1, VTS_WANG_MAX_HASH, &o->hash_n))
                return vt_usage_error("--hash must be 1..%u, not '%s'", VTS_WANG_MAX_HASH, optarg);
            break;
        case OPT_SHUFFLE:
            if (vt_parse_u32(optarg, 0, UINT32_MAX, &seed))
                return vt_usage_error("--shuffle must be 0..%u, not '%s'", UINT32_MAX, optarg);
            o->wang.shuffle = true;
            o->wang.shuffle_seed = seed;
            break;
        case OPT_STORE_TILE:
            if (vt_parse_u32(optarg, 8, 1024, &o->store_tile))
                return vt_usage_error("--store-tile must be 8..1024, not '%s'", optarg);
            break;
        case OPT_BORDER:
            if (vt_parse_u32(optarg, 0, 64, &o->border))
                return vt_usage_error("--border must be 0..64, not '%s'", optarg);
            break;
        case OPT_FILTER:
            if (vt_filter_parse(optarg, &o->filter))
                return vt_usage_error(
                    "--filter must be box, triangle, lanczos3 or kaiser, not '%s'", optarg);
            break;
        case OPT_CODEC:
            o->codec_name = optarg;
            break;
        case OPT_QUALITY:
            if (vt_parse_u32(optarg, 1, 100, &o->quality))
                return vt_usage_error("--quality must be 1..100, not '%s'", optarg);
            break;
        case 'j':
            if (vt_parse_u32(optarg, 1, 256, &o->threads))
                return vt_usage_error("--threads must be 1..256, not '%s'", optarg);
            break;
        default:
            if ((status = vt_common_option(c, OPT_VERSION, usage_text, argv)) >= 0)
                return status;
        }
    }
    if (optind >= argc)
        return vt_usage_error("missing SAMPLE");
    if (optind + 1 < argc)
        return vt_usage_error("too many arguments");
    o->input = argv[optind];
    if (!o->output)
        return vt_usage_error("missing -o PACK.vts");
    if (o->wang.corners && o->wang.kh != o->wang.kv)
        return vt_usage_error("--corners needs one colour count (--colours KxK), not %ux%u",
                              o->wang.kh, o->wang.kv);
    uint32_t cols, rows;
    vt_wang_grid(&o->wang, &cols, &rows);
    if ((uint64_t)cols * rows * o->wang.tile_px * o->wang.tile_px > VT_WANG_MAX_PACK_TEXELS)
        return vt_usage_error("--colours %ux%u%s with --tile %u make a pack of %ux%u tiles, more "
                              "than 2^30 texels",
                              o->wang.kh, o->wang.kv, o->wang.corners ? " --corners" : "",
                              o->wang.tile_px, cols, rows);
    if (o->store_tile <= 2 * o->border)
        return vt_usage_error("--store-tile %u leaves no content with --border %u", o->store_tile,
                              o->border);
    return vt_check_output(o->output, &o->input, 1);
}

/* The sample, whole, as 8-bit texels. */
static int read_sample(const char *path, struct vt_image *img, struct vts_error *err)
{
    struct vt_source src;
    struct vt_input_limits limits = {1ull << 28};
    int rc = vt_image_input_open(path, &limits, &src, err);
    if (rc)
        return rc;
    if (src.info.sample != VTS_SAMPLE_U8)
        rc =
            vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': the sample must have 8-bit samples, not %s",
                         path, vts_sample_name(src.info.sample));
    if (rc == 0)
        rc = vt_image_alloc(img, src.info.width, src.info.height, src.info.channels, VTS_SAMPLE_U8,
                            err);
    if (rc == 0)
        rc = vt_source_read(&src, 0, 0, img, err);
    vt_source_close(&src);
    return rc;
}

/* The pack image as the pyramid's source (any region, any thread: a copy). */
static int pack_read(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst, struct vts_error *err)
{
    const struct vt_image *pack = ctx;
    (void)err;
    for (uint32_t r = 0; r < dst->height; r++)
        memcpy(vt_image_at(dst, 0, r), vt_image_at(pack, x, y + r),
               (size_t)dst->width * vt_image_texel_bytes(pack));
    return 0;
}

static void pack_close(void *ctx)
{
    (void)ctx;
}

static const struct vt_source_ops pack_ops = {pack_read, pack_close};

struct run {
    struct vt_tile_sink *sink;
};

static int emit_tile(void *user, unsigned worker, uint32_t level, uint32_t tx, uint32_t ty,
                     const struct vt_image *payload, struct vts_error *err)
{
    struct run *r = user;
    return vt_tile_sink_put(r->sink, worker, 0, level, tx, ty, payload, err);
}

static int set_metadata(struct vts_writer *w, const struct options *o, const char *codec,
                        const uint32_t *order, struct vts_error *err)
{
    uint32_t cols, rows;
    vt_wang_grid(&o->wang, &cols, &rows);
    char colours[32], tile[16], grid[32], seed[24];
    snprintf(colours, sizeof colours, "%ux%u", o->wang.kh, o->wang.kv);
    snprintf(tile, sizeof tile, "%u", o->wang.tile_px);
    snprintf(grid, sizeof grid, "%ux%u", cols, rows);
    snprintf(seed, sizeof seed, "%" PRIu64, o->wang.seed);
    const char *pairs[][2] = {{"tool", "vt-wang"},
                              {"tool.version", VT_VERSION_STRING},
                              {"source", o->input},
                              {"filter", vt_filter_name(o->filter)},
                              {"codec", codec},
                              {"wrap", "yes"},
                              {VT_WANG_KEY_KIND, o->wang.corners ? "corner" : "edge"},
                              {VT_WANG_KEY_COLOURS, colours},
                              {VT_WANG_KEY_TILE, tile},
                              {VT_WANG_KEY_GRID, grid},
                              {VT_WANG_KEY_SEED, seed}};
    for (size_t i = 0; i < sizeof pairs / sizeof pairs[0]; i++) {
        int rc = vts_writer_set_meta(w, pairs[i][0], pairs[i][1], err);
        if (rc)
            return rc;
    }
    uint32_t *perm = malloc(o->hash_n * sizeof *perm);
    char *hash = perm && vts_wang_permutation(o->wang.seed, o->hash_n, perm) == 0
                     ? vt_wang_hash_format(perm, o->hash_n)
                     : NULL;
    char *ord = order ? vt_wang_hash_format(order, cols * rows) : NULL; /* same format */
    int rc = !hash || (order && !ord) ? vt_error_set(err, VTS_ERR_NOMEM, "out of memory") : 0;
    if (rc == 0)
        rc = vts_writer_set_meta(w, VT_WANG_KEY_HASH, hash, err);
    if (rc == 0 && ord)
        rc = vts_writer_set_meta(w, VT_WANG_KEY_ORDER, ord, err);
    free(perm);
    free(hash);
    free(ord);
    return rc;
}

/* Tiles the pack image into the store (the pyramid with wrap, the tile sink). */
static int write_store(const struct options *o, struct vt_image *pack, const uint32_t *order,
                       struct vts_error *err)
{
    const char *name =
        vt_tile_sink_codec_name(o->codec_name, VTS_SAMPLE_U8, false, VTS_COLOUR_SRGB);
    const struct vt_codec *codec = vt_codec_find(name);
    if (!codec)
        return vt_error_set(err, VTS_ERR_ARG, "codec '%s' is not available", name);
    uint32_t content = o->store_tile - 2 * o->border;
    struct vts_geometry g = {pack->width,
                             pack->height,
                             content,
                             o->border,
                             o->store_tile,
                             0,
                             1,
                             VTS_STORE_WRAP_X | VTS_STORE_WRAP_Y};
    g.level_count = vts_full_level_count(g.width, g.height, content);
    int rc = codec->check(g.tile_payload_px, pack->channels, VTS_SAMPLE_U8, err);
    if (rc)
        return rc;
    struct vts_layer layer = {
        codec->fourcc, (uint8_t)pack->channels, VTS_SAMPLE_U8, VTS_COLOUR_SRGB, 0, 0, {0}};
    layer.codec_param = codec->fourcc == VTS_CODEC_JPEG ? o->quality : 0;
    snprintf(layer.name, sizeof layer.name, "diffuse");
    struct vt_codec_params params = {(int)o->quality, vt_tile_sink_effort(codec, false), 420};
    struct vt_tile_sink_layer sl = {codec, params, pack->channels, VTS_SAMPLE_U8};
    struct run r = {NULL};
    struct vts_writer *w = vts_writer_create(o->output, &g, &layer, err);
    if (!w)
        return err->status;
    r.sink = vt_tile_sink_create(w, g.tile_payload_px, &sl, 1, o->threads, 0, err);
    char dir[VT_PATH_MAX];
    rc = r.sink ? vt_output_path_scratch_dir(o->output, dir, sizeof dir, err) : err->status;
    struct vt_source src[256];
    struct vt_source *ptrs[256];
    for (unsigned i = 0; i < o->threads; i++) {
        src[i] = (struct vt_source){{pack->width, pack->height, pack->channels, VTS_SAMPLE_U8,
                                     VTS_COLOUR_SRGB, false, false, false, 0, 0, "memory"},
                                    &pack_ops,
                                    pack,
                                    "pack"};
        ptrs[i] = &src[i];
    }
    struct vt_pyramid_options po = {.width = g.width,
                                    .height = g.height,
                                    .tile_content_px = content,
                                    .border_px = g.border_px,
                                    .level_count = g.level_count,
                                    .filter = o->filter,
                                    .colour = VTS_COLOUR_SRGB,
                                    .wrap = true,
                                    .out_channels = pack->channels,
                                    .out_sample = VTS_SAMPLE_U8,
                                    .threads = o->threads,
                                    .temp_dir = dir,
                                    .emit = emit_tile,
                                    .user = &r};
    if (rc == 0)
        rc = vt_pyramid_build(ptrs, &po, err);
    if (rc == 0)
        rc = set_metadata(w, o, codec->name, order, err);
    if (rc == 0)
        rc = vts_writer_finish(w, err);
    if (rc == 0) {
        struct vts_writer_stats st;
        vts_writer_stats(w, &st);
        vt_log(VT_LOG_INFO, "wrote '%s': pack %ux%u texels, %u levels, %llu payload bytes",
               o->output, g.width, g.height, g.level_count, (unsigned long long)st.unique_bytes);
    }
    vt_tile_sink_destroy(r.sink);
    vts_writer_destroy(w);
    return rc;
}

static double seconds_since(const struct timespec *t0)
{
    struct timespec t1;
    clock_gettime(CLOCK_MONOTONIC, &t1);
    return (double)(t1.tv_sec - t0->tv_sec) + (double)(t1.tv_nsec - t0->tv_nsec) / 1e9;
}

static int run(const struct options *o)
{
    struct vts_error err = {0};
    struct vt_image sample = {0}, pack = {0};
    uint32_t cols, rows, *order = NULL;
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    vt_wang_grid(&o->wang, &cols, &rows);
    int rc = read_sample(o->input, &sample, &err);
    if (rc == 0 && o->wang.shuffle && !(order = malloc((size_t)cols * rows * sizeof *order)))
        rc = vt_error_set(&err, VTS_ERR_NOMEM, "out of memory");
    if (rc == 0 && (rc = vt_wang_build(&sample, &o->wang, &pack, order, &err)) != 0 &&
        rc == VTS_ERR_ARG) {
        char m[sizeof err.message];
        snprintf(m, sizeof m, "%s", err.message);
        vt_error_set(&err, VTS_ERR_BAD_INPUT, "'%s': %s", o->input, m);
    }
    double synth = seconds_since(&t0);
    if (rc == 0)
        rc = write_store(o, &pack, order, &err);
    if (rc == 0)
        vt_log(VT_LOG_INFO, "%ux%u tiles of %u texels: tiles %.2f s, store %.2f s", cols, rows,
               o->wang.tile_px, synth, seconds_since(&t0) - synth);
    else
        vt_log(VT_LOG_ERROR, "%s", err.message);
    vt_image_release(&sample);
    vt_image_release(&pack);
    free(order);
    return rc ? VT_EXIT_BAD_INPUT : VT_EXIT_OK;
}

int main(int argc, char **argv)
{
    vt_tool_init("vt-wang");
    struct options o;
    int status = parse_options(argc, argv, &o);
    if (status >= 0)
        return status;
    return run(&o);
}
