/* vt-tiles: out-of-core mip pyramid + bordered tiles from one image into a .vts store. Option
 * parsing and main; the single-image build is tools/vt-tiles/vt_tiles_image.c, the atlas build
 * (--layout) tools/vt-tiles/vt_tiles_layout.c. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tool_common.h"
#include "vt_atomic_file.h"
#include "vt_image_input.h"
#include "vt_output_path.h"
#include "vt_pool.h"
#include "vt_shard.h"
#include "vt_stdin_spool.h"
#include "vt_tiles_image.h"
#include "vt_tiles_layout.h"
#include "vts_writer.h"

struct options {
    const char *input, *output, *codec_name, *name, *temp_dir;
    uint32_t tile_size, border, quality, threads, colour, aniso, subsampling;
    bool border_set, colour_set, keep_content, wrap, best, tile_size_set;
    bool filter_set, index; /* --filter given; --colour index (data kept by a selection) */
    const char *layout, *layer,
        *export_atlas; /* --layout build (tools/vt-tiles/vt_tiles_layout.c) */
    enum vt_filter_kind filter;
    const char *filtering; /* bilinear, trilinear, anisoN */
    uint64_t max_pixels, max_store, cache_bytes;
    uint32_t shard, shard_count; /* --shard I/N (docs/sharding.md); 0 = whole build */
    bool band_layers;            /* --band-layers (docs/geospatial.md) */
    bool has_value_scale;        /* --value-scale or --value-offset given */
    double value_scale, value_offset;
};

static void usage(FILE *f)
{
    fprintf(
        f,
        "usage: vt-tiles INPUT -o OUT.vts [options]\n"
        "Builds every mip level of INPUT, cut into bordered tiles, into one .vts store.\n"
        "INPUT: TIFF/BigTIFF (tiled or striped), PNG, JPEG, EXR; other formats through OpenImageIO;\n"
        "- for standard input (copied to a temporary file first; '<stdin>' in messages).\n\n"
        "  -o, --output FILE        the store to write (replaced atomically); - for standard\n"
        "                           output (not a terminal; spooled in $TMPDIR, then copied)\n"
        "      --tile-size N        tile content edge in texels (without the border, as in\n"
        "                           vt-atlas and vt-export), 8..16384 (default 256)\n"
        "      --keep content|payload  which edge --tile-size gives: content (default: the\n"
        "                           stored payload is N + 2*border) or payload (the stored\n"
        "                           tile is N, content N - 2*border)\n"
        "      --border N           border texels per side, 0..64 (default: from --filtering\n"
        "                           and the codec: bilinear 1, trilinear 2, anisoN N/2;\n"
        "                           at least 4 for bc1..bc5)\n"
        "      --filtering MODE     bilinear | trilinear | aniso2..aniso16 (default trilinear)\n"
        "      --filter NAME        mip filter: box | triangle | lanczos3 | kaiser (default box),\n"
        "                           or a selection for data (exact values, lossless codecs):\n"
        "                           nearest | mode | min | max\n"
        "      --colour SPACE       srgb | linear | normal | data | index (default: srgb for\n"
        "                           8/16-bit images, linear for float; data with a selection;\n"
        "                           index: categorical data, --filter mode (default) or nearest)\n"
        "      --wrap               tiling texture: borders and filters wrap around\n"
        "      --codec NAME         raw | png | jpeg | bc1 | bc3 | bc4 | bc5 | auto | gpu (default\n"
        "                           auto: jpeg for opaque 8-bit colour, png for alpha, 16-bit,\n"
        "                           normal or data, raw for float; gpu: GPU blocks per layer,\n"
        "                           bc5 for normal maps and 2 channels, bc4 for 1, bc3 for\n"
        "                           alpha, bc1 otherwise)\n"
        "      --quality Q          jpeg quality 1..100 (default 85)\n"
        "      --subsampling S      jpeg chroma subsampling 420 | 444 (default 420)\n"
        "      --mode fast|best     bc1..bc5 encoder, png compression (default fast)\n"
        "      --name NAME          layer name (default diffuse)\n"
        "      --band-layers        one layer per band of the input (default: one per 4 bands,\n"
        "                           named from the band descriptions; docs/geospatial.md)\n"
        "      --value-scale S      the stored samples mean stored * S + O (metadata\n"
        "      --value-offset O     layer.N.scale and layer.N.offset, as GDAL's band scale\n"
        "                           and offset; e.g. u16 elevations; default 1 and 0)\n"
        "      --max-pixels N       refuse inputs with more texels (default 2^34)\n"
        "      --max-store-size S   refuse to write more tile bytes than S (suffix K, M, G, T;\n"
        "                           default 2T)\n"
        "      --cache-size S       --layout: decoded textures kept in memory (default 256M)\n"
        "      --temp-dir DIR       where pass images go (default: the output's directory)\n"
        "      --shard I/N          build part I of N (N a power of two) for vt-merge to join\n"
        "      --layout FILE        instead of INPUT: build the atlas FILE (vt-atlas) from its\n"
        "                           textures; tile size and border come from the layout\n"
        "      --layer NAME         with --layout: only this layer (default: every layer)\n"
        "      --export-atlas FILE  with --layout: also write level 0 as one .tif/.png\n"
        "  -j, --threads N          worker threads (default: all cores)\n"
        "  -q, --quiet              errors only;  -v, --verbose  more detail\n"
        "  -h, --help               this help;    --version  version\n");
}

static const struct option long_options[] = {{"output", required_argument, 0, 'o'},
                                             {"tile-size", required_argument, 0, 't'},
                                             {"keep", required_argument, 0, 'K'},
                                             {"border", required_argument, 0, 'b'},
                                             {"filtering", required_argument, 0, 'F'},
                                             {"filter", required_argument, 0, 'f'},
                                             {"colour", required_argument, 0, 'c'},
                                             {"wrap", no_argument, 0, 'w'},
                                             {"codec", required_argument, 0, 'C'},
                                             {"quality", required_argument, 0, 'Q'},
                                             {"subsampling", required_argument, 0, 'S'},
                                             {"mode", required_argument, 0, 'M'},
                                             {"name", required_argument, 0, 'N'},
                                             {"band-layers", no_argument, 0, 'B'},
                                             {"value-scale", required_argument, 0, 'y'},
                                             {"value-offset", required_argument, 0, 'Y'},
                                             {"max-pixels", required_argument, 0, 'P'},
                                             {"temp-dir", required_argument, 0, 'T'},
                                             {"max-store-size", required_argument, 0, 'Z'},
                                             {"cache-size", required_argument, 0, 'X'},
                                             {"shard", required_argument, 0, 'D'},
                                             {"layout", required_argument, 0, 'L'},
                                             {"layer", required_argument, 0, 'l'},
                                             {"export-atlas", required_argument, 0, 'E'},
                                             {"threads", required_argument, 0, 'j'},
                                             {"quiet", no_argument, 0, 'q'},
                                             {"verbose", no_argument, 0, 'v'},
                                             {"help", no_argument, 0, 'h'},
                                             {"version", no_argument, 0, 'V'},
                                             {0, 0, 0, 0}};

static int parse_colour(const char *s, uint32_t *out)
{
    static const char *const names[] = {"srgb", "linear", "normal", "data"};
    for (uint32_t i = 0; i < 4; i++)
        if (strcmp(s, names[i]) == 0) {
            *out = VTS_COLOUR_SRGB + i;
            return 0;
        }
    return -1;
}

/* --colour index and the selections (nearest, mode, min, max): an index is reduced by mode
 * (default) or nearest only; a selection applies to data (implied when --colour is not given)
 * and to single images. Returns -1 to continue, or an exit status. */
static int check_selection(struct options *o)
{
    bool selection = vt_filter_is_selection(o->filter);
    if (o->index && o->filter_set && o->filter != VT_FILTER_MODE && o->filter != VT_FILTER_NEAREST)
        return vt_usage_error("--colour index needs --filter mode or nearest (an index is never "
                              "interpolated), not '%s'",
                              vt_filter_name(o->filter));
    if (o->index && !o->filter_set)
        o->filter = VT_FILTER_MODE;
    if (!selection && !o->index)
        return -1;
    if (o->layout)
        return vt_usage_error("--filter %s does not apply to --layout (selections build single "
                              "images)",
                              vt_filter_name(o->filter));
    if (o->colour_set && o->colour != VTS_COLOUR_DATA)
        return vt_usage_error("--filter %s keeps exact values of data: use --colour data or "
                              "index, not %s",
                              vt_filter_name(o->filter), vts_colour_name(o->colour));
    o->colour = VTS_COLOUR_DATA;
    o->colour_set = true;
    return -1;
}

/* Returns -1 to continue, or an exit status. */
static int parse_options(int argc, char **argv, struct options *o)
{
    *o = (struct options){.tile_size = 256,
                          .keep_content = true,
                          .threads = vt_pool_cpu_count(),
                          .codec_name = "auto",
                          .name = "diffuse",
                          .filtering = "trilinear",
                          .quality = 85,
                          .subsampling = 420,
                          .max_pixels = VT_INPUT_DEFAULT_MAX_PIXELS,
                          .max_store = VT_DEFAULT_MAX_STORE};
    int c, status;
    uint32_t v;
    opterr = 0;
    while ((c = vt_getopt_long(argc, argv, ":o:j:qvh", long_options)) != -1) {
        switch (c) {
        case 'o':
            o->output = optarg;
            break;
        case 't':
            if (vt_parse_u32(optarg, 8, VTS_MAX_PAYLOAD_PX, &o->tile_size))
                return vt_usage_error("--tile-size must be 8..%u, not '%s'", VTS_MAX_PAYLOAD_PX,
                                      optarg);
            o->tile_size_set = true;
            break;
        case 'L':
            o->layout = optarg;
            break;
        case 'l':
            o->layer = optarg;
            break;
        case 'E':
            o->export_atlas = optarg;
            break;
        case 'K':
            if (strcmp(optarg, "content") && strcmp(optarg, "payload"))
                return vt_usage_error("--keep must be content or payload, not '%s'", optarg);
            o->keep_content = strcmp(optarg, "content") == 0;
            break;
        case 'b':
            if (vt_parse_u32(optarg, 0, 64, &o->border))
                return vt_usage_error("--border must be 0..64, not '%s'", optarg);
            o->border_set = true;
            break;
        case 'F':
            o->filtering = optarg;
            break;
        case 'f':
            if (vt_filter_parse(optarg, &o->filter))
                return vt_usage_error("unknown --filter '%s' (box, triangle, lanczos3, kaiser, "
                                      "nearest, mode, min, max)",
                                      optarg);
            o->filter_set = true;
            break;
        case 'c':
            o->index = strcmp(optarg, "index") == 0;
            if (o->index)
                o->colour = VTS_COLOUR_DATA; /* stored as data; the filter keeps the values */
            else if (parse_colour(optarg, &o->colour))
                return vt_usage_error("unknown --colour '%s' (srgb, linear, normal, data, index)",
                                      optarg);
            o->colour_set = true;
            break;
        case 'w':
            o->wrap = true;
            break;
        case 'C':
            o->codec_name = optarg;
            break;
        case 'Q':
            if (vt_parse_u32(optarg, 1, 100, &o->quality))
                return vt_usage_error("--quality must be 1..100, not '%s'", optarg);
            break;
        case 'S':
            if (vt_parse_u32(optarg, 420, 444, &v) || (v != 420 && v != 444))
                return vt_usage_error("--subsampling must be 420 or 444, not '%s'", optarg);
            o->subsampling = v;
            break;
        case 'M':
            if (strcmp(optarg, "fast") && strcmp(optarg, "best"))
                return vt_usage_error("--mode must be fast or best, not '%s'", optarg);
            o->best = strcmp(optarg, "best") == 0;
            break;
        case 'N':
            if (strlen(optarg) == 0 || strlen(optarg) >= VTS_LAYER_NAME_BYTES)
                return vt_usage_error("--name must have 1..%u bytes", VTS_LAYER_NAME_BYTES - 1);
            o->name = optarg;
            break;
        case 'B':
            o->band_layers = true;
            break;
        case 'y':
        case 'Y': {
            char *end;
            double d = strtod(optarg, &end);
            bool scale = c == 'y';
            if (end == optarg || *end || !isfinite(d) || (scale && d == 0))
                return vt_usage_error("--value-%s must be a finite number%s, not '%s'",
                                      scale ? "scale" : "offset", scale ? " other than 0" : "",
                                      optarg);
            if (!o->has_value_scale)
                o->value_scale = 1.0;
            *(scale ? &o->value_scale : &o->value_offset) = d;
            o->has_value_scale = true;
            break;
        }
        case 'P': {
            char *end;
            unsigned long long n = strtoull(optarg, &end, 10);
            if (*optarg < '0' || *optarg > '9' || *end || n == 0)
                return vt_usage_error("--max-pixels must be a positive number, not '%s'", optarg);
            o->max_pixels = n;
            break;
        }
        case 'Z':
            if (vt_parse_size(optarg, &o->max_store) || o->max_store == 0)
                return vt_usage_error("--max-store-size: '%s' is not a size like 500G", optarg);
            break;
        case 'X':
            if (vt_parse_size(optarg, &o->cache_bytes) || o->cache_bytes < (1u << 20))
                return vt_usage_error("--cache-size: '%s' is not a size of at least 1M", optarg);
            break;
        case 'T':
            o->temp_dir = optarg;
            break;
        case 'D':
            if (vt_shard_parse(optarg, &o->shard, &o->shard_count))
                return vt_usage_error(
                    "--shard must be I/N with N a power of two up to %u and I 1..N, not '%s'",
                    VT_SHARD_MAX_COUNT, optarg);
            break;
        case 'j':
            if (vt_parse_u32(optarg, 1, 256, &o->threads))
                return vt_usage_error("-j must be 1..256, not '%s'", optarg);
            break;
        case 'q':
            vt_log_set_level(VT_LOG_ERROR);
            break;
        case 'v':
            vt_log_set_level(vt_log_get_level() + 1);
            break;
        case 'h':
            usage(stdout);
            return VT_EXIT_OK;
        case 'V':
            vt_print_version(stdout);
            return VT_EXIT_OK;
        default:
            return vt_usage_getopt_error(c, argv);
        }
    }
    if (o->layout) {
        if (optind != argc)
            return vt_usage_error("--layout takes no INPUT ('%s')", argv[optind]);
        if (vt_output_path_is_stdio(o->layout))
            return vt_usage_error("--layout cannot be standard input ('-'): it names its textures "
                                  "relative to its own folder");
        if (o->wrap || o->colour_set)
            return vt_usage_error("--wrap and --colour do not apply to --layout");
        if (o->shard && o->export_atlas)
            return vt_usage_error("--shard and --export-atlas do not go together");
        if (o->band_layers)
            return vt_usage_error("--band-layers does not apply to --layout");
        if (o->has_value_scale)
            return vt_usage_error("--value-scale and --value-offset do not apply to --layout");
        if (vt_output_path_is_stdio(o->export_atlas))
            return vt_usage_error("--export-atlas cannot be standard output ('-'): its name "
                                  "(.png, .tif) gives the format");
        o->input = o->layout;
    } else {
        if (o->layer || o->export_atlas)
            return vt_usage_error("--layer and --export-atlas need --layout");
        if (optind != argc - 1)
            return vt_usage_error(optind >= argc ? "missing INPUT" : "more than one INPUT");
        o->input = argv[optind];
        if (o->shard && vt_output_path_is_stdio(o->input))
            return vt_usage_error("--shard needs INPUT to be a file, not standard input ('-'): "
                                  "every shard reads it");
    }
    if (!o->output && !(o->layout && o->export_atlas))
        return vt_usage_error("missing -o OUT.vts");
    if ((status = check_selection(o)) >= 0)
        return status;
    if (strcmp(o->filtering, "bilinear") == 0)
        o->aniso = 0;
    else if (strcmp(o->filtering, "trilinear") == 0)
        o->aniso = 1;
    else if (strncmp(o->filtering, "aniso", 5) || vt_parse_u32(o->filtering + 5, 2, 16, &o->aniso))
        return vt_usage_error(
            "--filtering must be bilinear, trilinear or aniso2..aniso16, not '%s'", o->filtering);
    return -1;
}

/* vt-tiles INPUT: the single-image build (tools/vt-tiles/vt_tiles_image.c); INPUT "-" is
 * standard input, copied to a scratch file first (the readers seek). */
static int run_image(const struct options *o)
{
    struct vt_stdin_spool spool = {0};
    if (vt_output_path_is_stdio(o->input)) {
        struct vts_error err = {0};
        if (vt_stdin_spool_read(&spool, &err) != 0) {
            vt_log(VT_LOG_ERROR, "%s", err.message);
            vt_stdin_spool_release(&spool);
            return VT_EXIT_BAD_INPUT;
        }
        vt_log_alias(spool.path, VT_STDIN_NAME); /* the readers name the copy */
        vt_log(VT_LOG_DEBUG, "read %llu bytes from '%s'", (unsigned long long)spool.size,
               spool.path);
    }
    struct vt_tiles_image_options io = {.input = spool.open ? spool.path : o->input,
                                        .input_name = spool.open ? VT_STDIN_NAME : o->input,
                                        .output = o->output,
                                        .codec_name = o->codec_name,
                                        .name = o->name,
                                        .temp_dir = o->temp_dir,
                                        .tile_size = o->tile_size,
                                        .border = o->border,
                                        .quality = o->quality,
                                        .threads = o->threads,
                                        .colour = o->colour,
                                        .aniso = o->aniso,
                                        .subsampling = o->subsampling,
                                        .border_set = o->border_set,
                                        .colour_set = o->colour_set,
                                        .index = o->index,
                                        .keep_content = o->keep_content,
                                        .wrap = o->wrap,
                                        .best = o->best,
                                        .filter = o->filter,
                                        .filtering = o->filtering,
                                        .max_pixels = o->max_pixels,
                                        .max_store = o->max_store,
                                        .shard = o->shard,
                                        .shard_count = o->shard_count,
                                        .band_layers = o->band_layers,
                                        .has_value_scale = o->has_value_scale,
                                        .value_scale = o->value_scale,
                                        .value_offset = o->value_offset};
    int status = vt_tiles_image_run(&io);
    vt_stdin_spool_release(&spool);
    return status;
}

/* vt-tiles --layout: the atlas build (tools/vt-tiles/vt_tiles_layout.c). */
static int run_layout(const struct options *o)
{
    struct vt_tiles_layout_options lo = {.layout = o->layout,
                                         .output = o->output,
                                         .layer = o->layer,
                                         .export_atlas = o->export_atlas,
                                         .codec_name = o->codec_name,
                                         .filtering = o->filtering,
                                         .quality = o->quality,
                                         .subsampling = o->subsampling,
                                         .best = o->best,
                                         .tile_size = o->tile_size,
                                         .tile_size_set = o->tile_size_set,
                                         .keep_content = o->keep_content,
                                         .border = o->border,
                                         .border_set = o->border_set,
                                         .filter = o->filter,
                                         .max_pixels = o->max_pixels,
                                         .max_store = o->max_store,
                                         .cache_bytes = o->cache_bytes,
                                         .temp_dir = o->temp_dir,
                                         .threads = o->threads,
                                         .shard = o->shard,
                                         .shard_count = o->shard_count};
    return vt_tiles_layout_run(&lo);
}

int main(int argc, char **argv)
{
    vt_tool_init("vt-tiles");
    vt_output_path_use_stdio(); /* INPUT -, -o - */
    vt_atomic_file_cleanup_on_signals();
    struct options o;
    int status = parse_options(argc, argv, &o);
    if (status >= 0)
        return status;
    if ((status = vt_refuse_terminal(o.input, STDIN_FILENO, "an image")) >= 0 ||
        (status = vt_refuse_terminal(o.output, STDOUT_FILENO, "a store")) >= 0)
        return status;
    if (vt_output_path_is_stdio(o.output))
        vt_log_alias(VT_PATH_STDIO, VT_STDOUT_NAME);
    /* --layout: the layout and its textures are checked once the layout is read; INPUT "-" is
     * checked before it is read (standard input redirected from the output) */
    const char *inputs[] = {o.input};
    if (!o.layout && (status = vt_check_output(o.output, inputs, 1)) >= 0)
        return status;
    return o.layout ? run_layout(&o) : run_image(&o);
}
