/* vt-export: one layer of a .vts store written as Deep Zoom, IIIF level-0 or XYZ tiles that web
 * viewers read, with an optional OpenSeadragon page. The work is in formats/export. Reference:
 * docs/cli/vt-export.md. */
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tool_common.h"
#include "vt_codec.h"
#include "vt_error.h"
#include "vt_export.h"
#include "vt_filter.h"
#include "vt_pool.h"
#include "vts.h"

struct options {
    const char *in_path, *out_dir, *format, *layer, *name, *iiif_id, *osd_js;
    enum vt_export_layout layout;
    uint32_t quality, tile_px, overlap_px, threads;
    bool has_quality, has_tile, has_overlap, html, force;
};

enum {
    OPT_LAYOUT = 256,
    OPT_FORMAT,
    OPT_QUALITY,
    OPT_LAYER,
    OPT_TILE_SIZE,
    OPT_OVERLAP,
    OPT_NAME,
    OPT_IIIF_ID,
    OPT_HTML,
    OPT_OSD,
    OPT_FORCE,
    OPT_VERSION
};

static const struct option long_options[] = {{"output", required_argument, NULL, 'o'},
                                             {"layout", required_argument, NULL, OPT_LAYOUT},
                                             {"format", required_argument, NULL, OPT_FORMAT},
                                             {"quality", required_argument, NULL, OPT_QUALITY},
                                             {"layer", required_argument, NULL, OPT_LAYER},
                                             {"tile-size", required_argument, NULL, OPT_TILE_SIZE},
                                             {"overlap", required_argument, NULL, OPT_OVERLAP},
                                             {"name", required_argument, NULL, OPT_NAME},
                                             {"iiif-id", required_argument, NULL, OPT_IIIF_ID},
                                             {"html", no_argument, NULL, OPT_HTML},
                                             {"openseadragon", required_argument, NULL, OPT_OSD},
                                             {"force", no_argument, NULL, OPT_FORCE},
                                             {"threads", required_argument, NULL, 'j'},
                                             {"quiet", no_argument, NULL, 'q'},
                                             {"verbose", no_argument, NULL, 'v'},
                                             {"help", no_argument, NULL, 'h'},
                                             {"version", no_argument, NULL, OPT_VERSION},
                                             {NULL, 0, NULL, 0}};

static void usage(void)
{
    fputs(
        "usage: vt-export STORE.vts -o DIR [--layout dzi|iiif|xyz] [options]\n"
        "Write one layer of a .vts store as the tiles web viewers read: Deep Zoom, IIIF level-0\n"
        "static tiles or XYZ, in PNG or JPEG. DIR appears only when complete.\n"
        "\n"
        "  -o, --output DIR      the folder to write (built as DIR.tmp-XXXXXX, renamed at the\n"
        "                        end); refused when it exists and is not empty, unless --force\n"
        "      --layout L        dzi: NAME.dzi + NAME_files/LEVEL/X_Y.EXT (level 0 is 1x1);\n"
        "                        iiif: info.json (Image API 3.0, level 0) +\n"
        "                        REGION/SIZE/0/default.EXT; xyz: Z/X/Y.EXT, tiles padded\n"
        "                        with zeros (default dzi)\n"
        "      --format F        png | jpeg (default: jpeg for 8-bit grey or RGB, else png;\n"
        "                        png for a store built with --filter nearest|mode|min|max)\n"
        "      --quality Q       jpeg quality, integer 1..100 (default 85)\n"
        "      --layer L         the layer, by number or name (default 0)\n"
        "      --tile-size N     edge of a tile without overlap, integer 1..4096 (default: the\n"
        "                        store's tile content edge)\n"
        "      --overlap N       dzi: texels each tile repeats from its neighbours, integer\n"
        "                        0..256, at most the tile size (default 1)\n"
        "      --name NAME       dzi: the descriptor's name, letters, digits, '.', '_', '-'\n"
        "                        (default: the store's file name without .vts)\n"
        "      --iiif-id URL     iiif: the \"id\" of info.json, the URL DIR is served at\n"
        "                        (default: DIR as given)\n"
        "      --html            also write DIR/index.html, which opens the export with\n"
        "                        OpenSeadragon from a copy of openseadragon.min.js next to it\n"
        "      --openseadragon FILE  the openseadragon.min.js to copy (default: $VT_OPENSEADRAGON,\n"
        "                        else the one scripts/setup installs under ~/.cache/vtpipe/npm)\n"
        "      --force           replace DIR when it exists (never when it holds STORE)\n"
        "  -j, --threads N       worker threads, integer 1..256 (default: all cores)\n"
        "  -q, --quiet           print errors only\n"
        "  -v, --verbose         print more (repeatable: info, then debug)\n"
        "  -h, --help            print this help and exit\n"
        "      --version         print the version and exit\n"
        "\n"
        "Texels are the store's, exactly (PNG); levels coarser than the store's coarsest are\n"
        "made from it with a box filter in the layer's colour space. u16 layers give 16-bit\n"
        "PNG or, as JPEG, 8-bit rounded; f16 and f32 layers are refused. JPEG refuses alpha.\n"
        "Exit status: 0 ok, 1 bad input (unreadable or corrupt store, a layer that cannot be\n"
        "exported, output not written, interrupted), 2 bad usage.\n",
        stdout);
}

static int parse_value(int c, struct options *o)
{
    if (c == OPT_LAYOUT) {
        if (vt_export_layout_parse(optarg, &o->layout) != 0)
            return vt_usage_error("--layout must be dzi, iiif or xyz, not '%s'", optarg);
    } else if (c == OPT_QUALITY) {
        o->has_quality = true;
        if (vt_parse_u32(optarg, 1, 100, &o->quality) != 0)
            return vt_usage_error("--quality must be 1..100, not '%s'", optarg);
    } else if (c == OPT_TILE_SIZE) {
        o->has_tile = true;
        if (vt_parse_u32(optarg, 1, VT_EXPORT_MAX_TILE, &o->tile_px) != 0)
            return vt_usage_error("--tile-size must be 1..%u, not '%s'", VT_EXPORT_MAX_TILE,
                                  optarg);
    } else if (c == OPT_OVERLAP) {
        o->has_overlap = true;
        if (vt_parse_u32(optarg, 0, VT_EXPORT_MAX_OVERLAP, &o->overlap_px) != 0)
            return vt_usage_error("--overlap must be 0..%u, not '%s'", VT_EXPORT_MAX_OVERLAP,
                                  optarg);
    } else if (c == 'j') {
        if (vt_parse_u32(optarg, 1, 256, &o->threads) != 0)
            return vt_usage_error("-j must be 1..256, not '%s'", optarg);
    } else {
        return -1;
    }
    return 0;
}

/* Returns an exit code when main should stop now (help, version, usage error), else -1. */
static int parse_options(int argc, char **argv, struct options *o)
{
    int c, rc, verbosity = VT_LOG_WARN;
    *o = (struct options){.quality = 85, .overlap_px = 1, .threads = vt_pool_cpu_count()};
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
        } else if (c == 'o' || c == OPT_FORMAT || c == OPT_LAYER || c == OPT_NAME ||
                   c == OPT_IIIF_ID || c == OPT_OSD) {
            const char **slot[] = {&o->out_dir, &o->format,  &o->layer,
                                   &o->name,    &o->iiif_id, &o->osd_js};
            int i = c == 'o'           ? 0
                    : c == OPT_FORMAT  ? 1
                    : c == OPT_LAYER   ? 2
                    : c == OPT_NAME    ? 3
                    : c == OPT_IIIF_ID ? 4
                                       : 5;
            *slot[i] = optarg;
        } else if (c == OPT_HTML || c == OPT_FORCE) {
            *(c == OPT_HTML ? &o->html : &o->force) = true;
        } else if ((rc = parse_value(c, o)) >= 0) {
            if (rc != 0)
                return rc;
        } else {
            return vt_usage_getopt_error(c, argv);
        }
    }
    vt_log_set_level(verbosity);
    if (optind < argc)
        o->in_path = argv[optind++];
    if (optind < argc)
        return vt_usage_error("unexpected argument '%s' (one STORE.vts at a time)", argv[optind]);
    return -1;
}

static bool name_ok(const char *s)
{
    if (!*s || strcmp(s, ".") == 0 || strcmp(s, "..") == 0)
        return false;
    for (; *s; s++)
        if (!strchr("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-", *s))
            return false;
    return true;
}

static int validate_options(const struct options *o)
{
    if (!o->in_path)
        return vt_usage_error("missing STORE.vts argument");
    if (!o->out_dir || !o->out_dir[0])
        return vt_usage_error("missing -o DIR");
    if (o->format && strcmp(o->format, "png") != 0 && strcmp(o->format, "jpeg") != 0)
        return vt_usage_error("--format must be png or jpeg, not '%s'", o->format);
    if (o->has_quality && o->format && strcmp(o->format, "jpeg") != 0)
        return vt_usage_error("--quality applies to --format jpeg only");
    if (o->has_overlap && o->layout != VT_EXPORT_DZI)
        return vt_usage_error("--overlap applies to --layout dzi only");
    if (o->name && o->layout != VT_EXPORT_DZI)
        return vt_usage_error("--name applies to --layout dzi only");
    if (o->iiif_id && o->layout != VT_EXPORT_IIIF)
        return vt_usage_error("--iiif-id applies to --layout iiif only");
    if (o->osd_js && !o->html)
        return vt_usage_error("--openseadragon applies with --html only");
    if (o->name && !name_ok(o->name))
        return vt_usage_error("--name '%s': use letters, digits, '.', '_' and '-'", o->name);
    return 0;
}

/* The layer named or numbered by o->layer; -1 (after a message) when the store has none. */
static int find_layer(const struct options *o, const struct vts_store *store, uint32_t *layer)
{
    uint32_t n = vts_store_geometry(store)->layer_count;
    *layer = 0;
    if (!o->layer)
        return 0;
    if (vt_parse_u32(o->layer, 0, UINT32_MAX, layer) == 0 && *layer < n)
        return 0;
    for (uint32_t i = 0; i < n; i++) {
        if (strcmp(vts_store_layer(store, i)->name, o->layer) == 0) {
            *layer = i;
            return 0;
        }
    }
    vt_usage_error("'%s' has no layer '%s' (layers 0..%u)", o->in_path, o->layer, n - 1);
    return -1;
}

/* The store's file name without its directory and .vts. */
static void default_name(const char *path, char *buf, size_t cap)
{
    const char *base = strrchr(path, '/');
    snprintf(buf, cap, "%s", base ? base + 1 : path);
    size_t n = strlen(buf);
    if (n > 4 && strcmp(buf + n - 4, ".vts") == 0)
        buf[n - 4] = 0;
    if (!name_ok(buf))
        snprintf(buf, cap, "image");
}

static int find_osd(const struct options *o, char *buf, size_t cap)
{
    const char *env = getenv("VT_OPENSEADRAGON"), *home = getenv("HOME");
    if (o->osd_js)
        snprintf(buf, cap, "%s", o->osd_js);
    else if (env && *env)
        snprintf(buf, cap, "%s", env);
    else
        snprintf(buf, cap,
                 "%s/.cache/vtpipe/npm/node_modules/openseadragon/build/openseadragon/"
                 "openseadragon.min.js",
                 home ? home : "");
    if (access(buf, R_OK) == 0)
        return 0;
    vt_log(VT_LOG_ERROR,
           "--html needs openseadragon.min.js: '%s' cannot be read (scripts/setup installs it; "
           "or give --openseadragon FILE)",
           buf);
    return -1;
}

static volatile sig_atomic_t interrupted;

static void on_signal(int sig)
{
    interrupted = sig;
}

struct progress_ctx {
    struct vt_progress line;
    bool started;
};

static int on_progress(void *ctx, uint64_t done, uint64_t total)
{
    struct progress_ctx *p = ctx;
    if (!p->started) {
        vt_progress_start(&p->line, "exporting", "tiles", total);
        p->started = true;
    }
    vt_progress_update(&p->line, done);
    return interrupted != 0;
}

/* Fills the export's parameters from the options and the store. */
static int make_params(const struct options *o, const struct vts_store *store,
                       struct vt_export_params *p, char *name, size_t name_cap)
{
    const struct vts_geometry *g = vts_store_geometry(store);
    if (find_layer(o, store, &p->layer) != 0)
        return VT_EXIT_USAGE;
    const struct vts_layer *l = vts_store_layer(store, p->layer);
    /* a store reduced by a selection (filter=mode, min...) holds exact values: png keeps them */
    enum vt_filter_kind filter;
    bool exact = vt_filter_parse(vts_store_meta_find(store, "filter"), &filter) == 0 &&
                 vt_filter_is_selection(filter);
    bool jpeg_ok = l->sample == VTS_SAMPLE_U8 && (l->channels == 1 || l->channels == 3) && !exact;
    const char *format = o->format ? o->format : jpeg_ok ? "jpeg" : "png";
    if (o->has_quality && strcmp(format, "jpeg") != 0)
        return vt_usage_error("--quality applies to jpeg tiles only (layer %u exports as png)",
                              p->layer);
    p->layout = o->layout;
    p->codec = vt_codec_find(format);
    p->codec_params.quality = (int)o->quality;
    p->tile_px = o->has_tile ? o->tile_px : g->tile_content_px;
    p->overlap_px = o->layout == VT_EXPORT_DZI ? o->overlap_px : 0;
    default_name(o->in_path, name, name_cap);
    p->name = o->name ? o->name : name;
    p->iiif_id = o->iiif_id ? o->iiif_id : o->out_dir;
    p->threads = o->threads;
    if (o->overlap_px > p->tile_px && o->layout == VT_EXPORT_DZI)
        return vt_usage_error("--overlap %u is larger than the tile size %u", o->overlap_px,
                              p->tile_px);
    return 0;
}

static int export_store(const struct options *o, const struct vts_store *store)
{
    struct vt_export_params p = {0};
    struct progress_ctx progress = {0};
    struct vt_export_dir dir;
    struct vts_error err = {0};
    char name[256], osd[4096];
    int rc = make_params(o, store, &p, name, sizeof name);
    if (rc != 0)
        return rc;
    if (o->html && find_osd(o, osd, sizeof osd) != 0)
        return VT_EXIT_BAD_INPUT;
    p.progress = on_progress;
    p.progress_ctx = &progress;
    rc = vt_export_check(store, &p, &err);
    if (rc == 0)
        rc = vt_export_dir_create(&dir, o->out_dir, o->force, o->in_path, &err);
    if (rc != 0) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        return VT_EXIT_BAD_INPUT;
    }
    rc = vt_export_run(store, &p, dir.tmp_path, &err);
    if (progress.started)
        vt_progress_end(&progress.line);
    if (rc == 0 && o->html)
        rc = vt_export_write_html(store, &p, dir.tmp_path, osd, &err);
    if (rc == 0)
        rc = vt_export_dir_commit(&dir, &err);
    if (rc != 0) {
        vt_export_dir_abort(&dir);
        if (interrupted)
            vt_log(VT_LOG_ERROR, "interrupted: nothing written to '%s'", o->out_dir);
        else
            vt_log(VT_LOG_ERROR, "%s", err.message);
        return VT_EXIT_BAD_INPUT;
    }
    vt_log(VT_LOG_WARN, "wrote '%s': %llu %s tiles, layer %u '%s', %s layout%s", o->out_dir,
           (unsigned long long)vt_export_tile_count(store, &p), p.codec->name, p.layer,
           vts_store_layer(store, p.layer)->name,
           o->layout == VT_EXPORT_DZI    ? "dzi"
           : o->layout == VT_EXPORT_IIIF ? "iiif"
                                         : "xyz",
           o->html ? ", index.html" : "");
    return VT_EXIT_OK;
}

int main(int argc, char **argv)
{
    struct options o;
    struct vts_error err = {0};
    vt_tool_init("vt-export");
    int rc = parse_options(argc, argv, &o);
    if (rc >= 0)
        return rc;
    if ((rc = validate_options(&o)) != 0)
        return rc;
    struct vts_store *store = vts_open(o.in_path, &err);
    if (!store) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        return VT_EXIT_BAD_INPUT;
    }
    signal(SIGINT, on_signal);
    signal(SIGTERM, on_signal);
    signal(SIGHUP, on_signal);
    rc = export_store(&o, store);
    vts_close(store);
    if (interrupted) {
        signal(interrupted, SIG_DFL);
        raise(interrupted);
    }
    return rc;
}
