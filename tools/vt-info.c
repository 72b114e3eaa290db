/* vt-info: describes a .vts tile store, verifies its tiles, or extracts a tile or level as PNG.
 * Reference (options, output fields, JSON keys): docs/cli/vt-info.md. */
#include <ctype.h>
#include <errno.h>
#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/mman.h>
#include <unistd.h>

#include "tool_common.h"
#include "vt_atomic_file.h"
#include "vt_georef_file.h"
#include "vt_level_stats.h"
#include "vt_output_path.h"
#include "vt_shard.h"
#include "vt_stdin_spool.h"
#include "vt_store_georef.h"
#include "vt_store_stats.h"
#include "vt_tile_reader.h"
#include "vt_wang_pack.h"
#include "vts.h"

#define EXTRACT_MAX_TEXELS (1ull << 32) /* --extract refuses larger images */

struct options {
    const char *store_path;
    const char *out_path; /* -o */
    bool json, verify, extract, stats, has_tile, has_layer;
    uint32_t level, tile_x, tile_y, layer; /* --extract, --tile, --layer */
    bool wang_region;                      /* --wang-region X,Y,W,H */
    uint64_t wang_x, wang_y;
    uint32_t wang_w, wang_h;
};

enum { OPT_JSON = 256, OPT_VERIFY, OPT_EXTRACT, OPT_STATS, OPT_TILE, OPT_LAYER, OPT_VERSION };
enum { OPT_WANG = 512 }; /* --wang-region */

static const struct option long_options[] = {{"json", no_argument, NULL, OPT_JSON},
                                             {"verify", no_argument, NULL, OPT_VERIFY},
                                             {"extract", required_argument, NULL, OPT_EXTRACT},
                                             {"stats", no_argument, NULL, OPT_STATS},
                                             {"tile", required_argument, NULL, OPT_TILE},
                                             {"layer", required_argument, NULL, OPT_LAYER},
                                             {"wang-region", required_argument, NULL, OPT_WANG},
                                             {"output", required_argument, NULL, 'o'},
                                             {"quiet", no_argument, NULL, 'q'},
                                             {"verbose", no_argument, NULL, 'v'},
                                             {"help", no_argument, NULL, 'h'},
                                             {"version", no_argument, NULL, OPT_VERSION},
                                             {NULL, 0, NULL, 0}};

static void usage(void)
{
    fputs("usage: vt-info [-q|-v] [--json | --verify] STORE\n"
          "       vt-info --stats [--layer N] [--json] STORE\n"
          "       vt-info --extract LEVEL [--tile X,Y] [--layer N] -o OUT.png STORE\n"
          "Describe, check or extract from a .vts virtual-texture store.\n"
          "\n"
          "Modes (default: print a summary of STORE on stdout):\n"
          "      --json           print the summary as JSON on stdout (keys: docs/cli/vt-info.md)\n"
          "      --verify         read every stored tile, check its CRC-32C and decode it;\n"
          "                       exit 1 naming the first bad tile\n"
          "      --stats          per layer, level and channel: min, max, mean, stddev of the\n"
          "                       texels (u8/u16 codes, f16/f32 values; borders left out;\n"
          "                       empty tiles count as zeros); with --json as JSON\n"
          "      --extract LEVEL  write level LEVEL (integer, 0..levels-1) as a PNG, or a TIFF\n"
          "                       when -o ends in .tif/.tiff; needs -o\n"
          "Extract options:\n"
          "      --tile X,Y       write only tile X,Y (integers, 0..tiles-1 of LEVEL) with its\n"
          "                       border; default: the whole level stitched without borders\n"
          "      --layer N        layer to extract (integer, 0..layers-1; default 0); with\n"
          "                       --stats the one layer to describe (default: all)\n"
          "      --wang-region X,Y,W,H\n"
          "                       a Wang pack (vt-wang): write W x H texels (1..16384 each) of\n"
          "                       the virtual output at X,Y (texels of LEVEL) instead (PNG)\n"
          "  -o, --output FILE    PNG to write (replaced only when complete); - for standard\n"
          "                       output (not a terminal)\n"
          "General:\n"
          "  -q, --quiet          print errors only\n"
          "  -v, --verbose        print more (repeatable: info, then debug)\n"
          "  -h, --help           print this help and exit\n"
          "      --version        print the version and exit\n"
          "\n"
          "STORE - reads the store from standard input (copied to a temporary file first;\n"
          "'<stdin>' in messages and the summary).\n"
          "Summary: 'shared' counts stored tiles whose payload an earlier tile (in index order)\n"
          "already uses; 'bytes' counts each payload once. Bits per texel = 8 * payload bytes /\n"
          "texels of all stored tiles (payload edge^2 each, borders included, all levels and\n"
          "layers). Compression ratio = raw size of the stored tiles (payload edge^2 * channels *\n"
          "sample bytes each) / payload bytes.\n"
          "PNG: u8 -> 8-bit, u16 -> 16-bit, f16/f32 -> 16-bit clamped to [0,1] (with a warning);\n"
          "TIFF (deflate): u8 -> 8-bit, u16 -> 16-bit, f16/f32 -> 32-bit float, values kept;\n"
          "1-4 channels -> gray, gray+alpha, RGB, RGBA; empty tiles are zero (transparent black).\n"
          "Exit status: 0 ok, 1 bad input (unreadable or corrupt store, bad tile, output not\n"
          "written), 2 bad usage (including a level, tile or layer the store does not have).\n",
          stdout);
}

/* "X,Y,W,H" of --wang-region. */
static int parse_wang_region(const char *s, struct options *o)
{
    unsigned long long x, y;
    unsigned w, h;
    char tail;
    if (sscanf(s, "%llu,%llu,%u,%u%c", &x, &y, &w, &h, &tail) != 4 || !isdigit((unsigned char)*s) ||
        w < 1 || h < 1 || w > 16384 || h > 16384 || x > UINT32_MAX * 65536ull ||
        y > UINT32_MAX * 65536ull)
        return -1;
    o->wang_region = true;
    o->wang_x = x;
    o->wang_y = y;
    o->wang_w = w;
    o->wang_h = h;
    return 0;
}

/* Returns an exit code when main should stop now (help, version, usage error), else -1. */
static int parse_options(int argc, char **argv, struct options *o)
{
    int c, verbosity = VT_LOG_WARN;
    *o = (struct options){0};
    opterr = 0;
    while ((c = vt_getopt_long(argc, argv, ":hqvo:", long_options)) != -1) {
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
        } else if (c == OPT_JSON) {
            o->json = true;
        } else if (c == OPT_VERIFY) {
            o->verify = true;
        } else if (c == OPT_STATS) {
            o->stats = true;
        } else if (c == OPT_EXTRACT) {
            o->extract = true;
            if (vt_parse_u32(optarg, 0, UINT32_MAX, &o->level) != 0)
                return vt_usage_error("--extract: '%s' is not a level number", optarg);
        } else if (c == OPT_TILE) {
            o->has_tile = true;
            if (vt_parse_u32_pair(optarg, ',', 0, UINT32_MAX, &o->tile_x, &o->tile_y) != 0)
                return vt_usage_error("--tile: '%s' is not X,Y (two tile numbers)", optarg);
        } else if (c == OPT_WANG) {
            if (parse_wang_region(optarg, o) != 0)
                return vt_usage_error("--wang-region: '%s' is not X,Y,W,H (W, H in 1..16384)",
                                      optarg);
        } else if (c == OPT_LAYER) {
            o->has_layer = true;
            if (vt_parse_u32(optarg, 0, UINT32_MAX, &o->layer) != 0)
                return vt_usage_error("--layer: '%s' is not a layer number", optarg);
        } else {
            return vt_usage_getopt_error(c, argv);
        }
    }
    vt_log_set_level(verbosity);
    if (optind < argc)
        o->store_path = argv[optind++];
    if (optind < argc)
        return vt_usage_error("unexpected argument '%s' (one STORE at a time)", argv[optind]);
    return -1;
}

/* The image format an output name asks for by its extension, when it is neither PNG nor TIFF
 * (which --extract writes): a .jpg that holds a PNG misleads every program that trusts the name. */
static const char *other_image_format(const char *path)
{
    static const char *const names[][2] = {
        {".jpg", "JPEG"}, {".jpeg", "JPEG"}, {".exr", "OpenEXR"}, {".webp", "WebP"},
        {".bmp", "BMP"},  {".gif", "GIF"},   {".tga", "TGA"},     {".dds", "DDS"},
        {".ktx", "KTX"},  {".ktx2", "KTX2"}};
    const char *dot = strrchr(path, '.');
    if (!dot || strchr(dot, '/'))
        return NULL;
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (strcasecmp(dot, names[i][0]) == 0)
            return names[i][1];
    return NULL;
}

/* True when the output is named .tif or .tiff (--extract then writes a TIFF). */
static bool wants_tiff(const char *path)
{
    const char *dot = strrchr(path, '.');
    return dot && !strchr(dot, '/') &&
           (strcasecmp(dot, ".tif") == 0 || strcasecmp(dot, ".tiff") == 0);
}

static int validate_options(const struct options *o)
{
    if (!o->store_path)
        return vt_usage_error("missing STORE argument");
    if (o->json * !o->stats + o->verify + o->extract + o->stats > 1)
        return vt_usage_error(
            "--json, --verify, --extract and --stats are separate modes: give one (--stats "
            "takes --json)");
    if (!o->extract && (o->has_tile || (o->has_layer && !o->stats) || o->out_path))
        return vt_usage_error("%s needs --extract", o->has_tile    ? "--tile"
                                                    : o->has_layer ? "--layer"
                                                                   : "-o");
    if (o->extract && !o->out_path)
        return vt_usage_error("--extract needs -o OUT.png");
    if (o->wang_region && (!o->extract || o->has_tile || o->has_layer || wants_tiff(o->out_path)))
        return vt_usage_error("--wang-region needs --extract LEVEL and a PNG, without --tile and "
                              "--layer");
    const char *format = o->extract ? other_image_format(o->out_path) : NULL;
    if (format)
        return vt_usage_error(
            "-o '%s': --extract writes PNG or TIFF, not %s: name the output .png or .tif",
            o->out_path, format);
    return 0;
}

/* ---- summary, as text or JSON ---- */

/* Writes the names of the set bits of flags (names[i] for bit i < 2, else "bit<i>"), space
 * separated, into out; "" when none is set. */
static void flag_names(char *out, size_t cap, uint32_t flags, const char *const names[2])
{
    size_t len = 0;
    out[0] = '\0';
    for (unsigned bit = 0; bit < 32 && len < cap; bit++) {
        const char *name = bit < 2 ? names[bit] : NULL;
        if (!(flags & (1u << bit)))
            continue;
        if (name)
            len += (size_t)snprintf(out + len, cap - len, "%s%s", len ? " " : "", name);
        else
            len += (size_t)snprintf(out + len, cap - len, "%sbit%u", len ? " " : "", bit);
    }
}

static const char *const store_flag_names[2] = {"wrap-x", "wrap-y"};
static const char *const layer_flag_names[2] = {"premultiplied", NULL};

/* Prints text from the file (a layer name, a metadata value) on one line: control characters as
 * \xHH. */
static void print_escaped(const char *s)
{
    for (; *s; s++) {
        if ((unsigned char)*s < 0x20 || *s == 0x7f)
            printf("\\x%02x", (unsigned)(unsigned char)*s);
        else
            putchar(*s);
    }
}

static void print_counts(const char *level, const char *size, const char *tiles,
                         const struct vt_tile_counts *st)
{
    printf("  %5s %13s %9s %7llu %7llu %7llu %13llu\n", level, size, tiles,
           (unsigned long long)st->stored, (unsigned long long)st->empty,
           (unsigned long long)st->shared, (unsigned long long)st->bytes);
}

static void print_layer(const struct vts_store *s, const struct vt_store_stats *st, uint32_t layer)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    const struct vts_layer *l = vts_store_layer(s, layer);
    char flags[128], codec[5], level[16], size[32], tiles[32];
    vts_codec_name(l->codec, codec);
    flag_names(flags, sizeof flags, l->flags, layer_flag_names);
    printf("layer %u '", layer);
    print_escaped(l->name);
    printf("': %s, %u channels, %s, %s, flags %s\n", codec, l->channels, vts_sample_name(l->sample),
           vts_colour_name(l->colour), flags[0] ? flags : "none");
    printf("  level          size     tiles  stored   empty  shared         bytes\n");
    for (uint32_t i = 0; i < g->level_count; i++) {
        struct vts_level L;
        vts_store_level(s, i, &L);
        snprintf(level, sizeof level, "%u", i);
        snprintf(size, sizeof size, "%ux%u", L.width, L.height);
        snprintf(tiles, sizeof tiles, "%ux%u", L.tiles_x, L.tiles_y);
        print_counts(level, size, tiles, vt_store_stats_at(st, layer, i));
    }
    const struct vt_tile_counts *total = vt_store_stats_at(st, layer, g->level_count);
    snprintf(tiles, sizeof tiles, "%llu", (unsigned long long)total->tiles);
    print_counts("total", "", tiles, total);
}

/* The long lists of a Wang pack (wang.hash, wang.order): their first entries and count. Returns
 * false for other keys. */
static bool vt_wang_print_list(const char *key, const char *value)
{
    if (strcmp(key, VT_WANG_KEY_HASH) != 0 && strcmp(key, VT_WANG_KEY_ORDER) != 0)
        return false;
    size_t n = *value != '\0', shown = 0;
    for (const char *p = value; *p; p++)
        n += *p == ' ';
    for (const char *p = value; *p && shown < 8; p++) {
        shown += *p == ' ';
        if (shown < 8)
            putchar(*p);
    }
    printf("%s (%zu entries)", n > 8 ? " ..." : "", n);
    return true;
}

/* A Wang pack's parameters (vt-wang), or a warning when its metadata is bad. */
static void print_wang(const struct vts_store *s)
{
    struct vt_wang_info info;
    struct vts_error err = {0};
    if (!vt_wang_pack_is(s))
        return;
    if (vt_wang_pack_open(s, &info, &err) == 0)
        vt_wang_pack_print(&info);
    else
        vt_log(VT_LOG_WARN, "%s", err.message);
    vt_wang_info_release(&info);
}

static json_t *json_wang(const struct vts_store *s)
{
    struct vt_wang_info i;
    struct vts_error err = {0};
    json_t *o = NULL;
    if (vt_wang_pack_open(s, &i, &err) == 0)
        o = json_pack("{s:s, s:I, s:I, s:I, s:I, s:I, s:I, s:I, s:b}", "kind",
                      i.corners ? "corner" : "edge", "kh", (json_int_t)i.kh, "kv", (json_int_t)i.kv,
                      "tile_px", (json_int_t)i.tile_px, "cols", (json_int_t)i.cols, "rows",
                      (json_int_t)i.rows, "hash_entries", (json_int_t)i.hash_n, "repeat_px",
                      (json_int_t)i.hash_n * i.tile_px, "shuffled", i.order != NULL);
    else
        vt_log(VT_LOG_WARN, "%s", err.message);
    vt_wang_info_release(&i);
    return o ? o : json_null();
}

/* ---- georeferencing (docs/geospatial.md; vt_store_georef.h) ---- */

static void print_georef(const struct vts_store *s)
{
    struct vt_georef g;
    vt_store_georef(s, 0, &g);
    const double *t = g.transform;
    if (g.has_transform)
        printf(
            "georef:            origin %.17g, %.17g; texel %.17g x %.17g; rotation %.17g, %.17g\n",
            t[0], t[3], t[1], t[5], t[2], t[4]);
    if (g.crs_wkt) {
        char name[128];
        vt_store_crs_name(g.crs_wkt, name, sizeof name);
        printf("crs:               ");
        print_escaped(name);
        putchar('\n');
    }
    if (g.nodata) {
        printf("nodata:            ");
        print_escaped(g.nodata);
        putchar('\n');
    }
}

static void print_summary(const struct vts_store *s, const struct vt_store_stats *st)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    const struct vt_tile_counts *t = &st->total;
    unsigned major, minor;
    char flags[128];
    vts_store_version(s, &major, &minor);
    flag_names(flags, sizeof flags, g->flags, store_flag_names);
    printf("file:              %s\nformat version:    %u.%u\n", vts_store_name(s), major, minor);
    printf("size:              %u x %u texels\n", g->width, g->height);
    printf("tile:              %u content + 2 x %u border = %u payload texels\n",
           g->tile_content_px, g->border_px, g->tile_payload_px);
    printf("levels:            %u\nlayers:            %u\nflags:             %s\n", g->level_count,
           g->layer_count, flags[0] ? flags : "none");
    print_georef(s);
    for (uint32_t layer = 0; layer < g->layer_count; layer++)
        print_layer(s, st, layer);
    printf("tiles:             %llu stored, %llu empty, %llu shared\n",
           (unsigned long long)t->stored, (unsigned long long)t->empty,
           (unsigned long long)t->shared);
    printf("payload bytes:     %llu\nfile size:         %llu bytes\n", (unsigned long long)t->bytes,
           (unsigned long long)vts_store_file_size(s));
    if (isnan(st->bits_per_texel))
        printf("bits per texel:    n/a\ncompression ratio: n/a\n");
    else
        printf("bits per texel:    %.3f\ncompression ratio: %.3f\n", st->bits_per_texel,
               st->compression_ratio);
    printf("metadata:          %u entries\n", vts_store_meta_count(s));
    for (uint32_t i = 0; i < vts_store_meta_count(s); i++) {
        printf("  %s=", vts_store_meta_key(s, i));
        if (!vt_wang_print_list(vts_store_meta_key(s, i), vts_store_meta_value(s, i)))
            print_escaped(vts_store_meta_value(s, i));
        putchar('\n');
    }
    print_wang(s);
}

/* A JSON string of text from the file (layer names and metadata values are not checked for
 * UTF-8): as is when valid UTF-8, else with every byte >= 0x80 replaced by '?'. */
static json_t *json_text(const char *text)
{
    json_t *j = json_string(text);
    if (j)
        return j;
    char *copy = strdup(text);
    for (char *p = copy; p && *p; p++)
        *p = (unsigned char)*p >= 0x80 ? '?' : *p;
    j = copy ? json_string(copy) : NULL;
    free(copy);
    return j;
}

/* Sets the counters of st into obj (a new object when obj is NULL) and returns obj. */
static json_t *json_counts(json_t *obj, const struct vt_tile_counts *st)
{
    if (!obj)
        obj = json_object();
    json_object_set_new(obj, "tiles", json_integer((json_int_t)st->tiles));
    json_object_set_new(obj, "stored", json_integer((json_int_t)st->stored));
    json_object_set_new(obj, "empty", json_integer((json_int_t)st->empty));
    json_object_set_new(obj, "shared", json_integer((json_int_t)st->shared));
    json_object_set_new(obj, "bytes", json_integer((json_int_t)st->bytes));
    json_object_set_new(obj, "raw_bytes", json_integer((json_int_t)st->raw_bytes));
    return obj;
}

static json_t *json_flags(uint32_t flags, const char *const names[2])
{
    char text[128];
    json_t *array = json_array();
    flag_names(text, sizeof text, flags, names);
    for (char *name = strtok(text, " "); name; name = strtok(NULL, " "))
        json_array_append_new(array, json_string(name));
    return array;
}

static json_t *json_layer(const struct vts_store *s, const struct vt_store_stats *st,
                          uint32_t layer)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    const struct vts_layer *l = vts_store_layer(s, layer);
    char codec[5];
    json_t *levels = json_array();
    for (uint32_t i = 0; i < g->level_count; i++) {
        struct vts_level L;
        vts_store_level(s, i, &L);
        json_t *j = json_pack("{s:I, s:I, s:I, s:I, s:I}", "level", (json_int_t)i, "width",
                              (json_int_t)L.width, "height", (json_int_t)L.height, "tiles_x",
                              (json_int_t)L.tiles_x, "tiles_y", (json_int_t)L.tiles_y);
        json_array_append_new(levels, json_counts(j, vt_store_stats_at(st, layer, i)));
    }
    vts_codec_name(l->codec, codec);
    return json_pack("{s:I, s:o, s:s, s:I, s:s, s:s, s:o, s:I, s:o, s:o}", "index",
                     (json_int_t)layer, "name", json_text(l->name), "codec", codec, "channels",
                     (json_int_t)l->channels, "sample", vts_sample_name(l->sample), "colour",
                     vts_colour_name(l->colour), "flags", json_flags(l->flags, layer_flag_names),
                     "codec_param", (json_int_t)l->codec_param, "levels", levels, "totals",
                     json_counts(NULL, vt_store_stats_at(st, layer, g->level_count)));
}

/* gdalinfo -json's shape: geoTransform [6], coordinateSystem {wkt}, noDataValue; true when the
 * store has any (the JSON then prints reals with 17 digits). */
static bool json_georef(const struct vts_store *s, json_t *root)
{
    struct vt_georef g;
    vt_store_georef(s, 0, &g);
    if (g.has_transform) {
        json_t *a = json_array();
        for (int i = 0; i < 6; i++)
            json_array_append_new(a, json_real(g.transform[i]));
        json_object_set_new(root, "geoTransform", a);
    }
    if (g.crs_wkt)
        json_object_set_new(root, "coordinateSystem",
                            json_pack("{s:o}", "wkt", json_text(g.crs_wkt)));
    if (g.nodata) {
        char *end;
        double v = strtod(g.nodata, &end);
        json_object_set_new(root, "noDataValue",
                            end != g.nodata && !*end && isfinite(v) ? json_real(v)
                                                                    : json_text(g.nodata));
    }
    return g.has_transform || g.crs_wkt || g.nodata;
}

static int print_json(const struct vts_store *s, const struct vt_store_stats *st)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    unsigned major, minor;
    double bpt = st->bits_per_texel, ratio = st->compression_ratio;
    json_t *layers = json_array(), *meta = json_object();
    vts_store_version(s, &major, &minor);
    for (uint32_t layer = 0; layer < g->layer_count; layer++)
        json_array_append_new(layers, json_layer(s, st, layer));
    for (uint32_t i = 0; i < vts_store_meta_count(s); i++)
        json_object_set_new(meta, vts_store_meta_key(s, i), json_text(vts_store_meta_value(s, i)));
    json_t *totals = json_counts(NULL, &st->total);
    json_object_set_new(totals, "file_size", json_integer((json_int_t)vts_store_file_size(s)));
    json_object_set_new(totals, "bits_per_texel", isnan(bpt) ? json_null() : json_real(bpt));
    json_object_set_new(totals, "compression_ratio", isnan(ratio) ? json_null() : json_real(ratio));
    json_t *root =
        json_pack("{s:o, s:I, s:I, s:I, s:I, s:I, s:I, s:I, s:I, s:I, s:o, s:o, s:o, s:o}", "file",
                  json_text(vts_store_name(s)), "format_major", (json_int_t)major, "format_minor",
                  (json_int_t)minor, "width", (json_int_t)g->width, "height", (json_int_t)g->height,
                  "tile_content_px", (json_int_t)g->tile_content_px, "border_px",
                  (json_int_t)g->border_px, "tile_payload_px", (json_int_t)g->tile_payload_px,
                  "level_count", (json_int_t)g->level_count, "layer_count",
                  (json_int_t)g->layer_count, "flags", json_flags(g->flags, store_flag_names),
                  "layers", layers, "totals", totals, "metadata", meta);
    if (root && vt_wang_pack_is(s))
        json_object_set_new(root, "wang", json_wang(s));
    int digits = root && json_georef(s, root) ? 17 : 6;
    int rc = root ? json_dumpf(root, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(digits)) : -1;
    json_decref(root);
    if (rc != 0) {
        vt_log(VT_LOG_ERROR, "'%s': cannot write the JSON summary", vts_store_name(s));
        return VT_EXIT_BAD_INPUT;
    }
    putchar('\n');
    return VT_EXIT_OK;
}

static int run_summary(const struct vts_store *s, bool json)
{
    struct vt_store_stats st;
    struct vts_error err = {0};
    int rc = VT_EXIT_OK;
    if (vt_store_stats_init(&st, s, &err) != 0) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        rc = VT_EXIT_BAD_INPUT;
    } else if (json) {
        rc = print_json(s, &st);
    } else {
        print_summary(s, &st);
    }
    vt_store_stats_release(&st);
    return rc;
}

/* ---- --verify and --extract ---- */

/* True for the carried-texels layer of a vt-tiles --shard store. */
static bool is_shard_carry(const struct vts_store *s, uint32_t layer)
{
    const struct vts_layer *l = vts_store_layer(s, layer);
    return l && strcmp(l->name, VT_SHARD_LAYER_NAME) == 0 && vts_store_meta_find(s, VT_SHARD_KEY);
}

static int run_verify(const struct vts_store *s)
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
static int run_stats(const struct vts_store *s, const struct options *o)
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

/* Usage errors for a layer, level or tile the store does not have, giving the valid range. */
static int check_extract_range(const struct vts_store *s, const struct options *o)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    const char *name = vts_store_name(s);
    struct vts_level L;
    if (o->layer >= g->layer_count)
        return vt_usage_error("layer %u is outside '%s' (layers 0..%u)", o->layer, name,
                              g->layer_count - 1);
    if (o->level >= g->level_count)
        return vt_usage_error("level %u is outside '%s' (levels 0..%u)", o->level, name,
                              g->level_count - 1);
    vts_store_level(s, o->level, &L);
    if (o->has_tile && (o->tile_x >= L.tiles_x || o->tile_y >= L.tiles_y))
        return vt_usage_error("tile %u,%u is outside level %u of '%s' (tiles 0..%u,0..%u)",
                              o->tile_x, o->tile_y, o->level, name, L.tiles_x - 1, L.tiles_y - 1);
    uint32_t fit = o->level;
    for (; !o->has_tile && (uint64_t)L.width * L.height > EXTRACT_MAX_TEXELS; fit++)
        vts_store_level(s, fit + 1, &L); /* the last level fits in one tile */
    if (fit != o->level)
        return vt_usage_error(
            "level %u of '%s' has more than 2^32 texels, the most --extract writes: use level %u or coarser, or --tile",
            o->level, name, fit);
    return 0;
}

/* --extract LEVEL --wang-region X,Y,W,H: the virtual output of a Wang pack. */
static int run_wang_region(const struct vts_store *s, const struct options *o)
{
    struct vt_wang_info info;
    struct vts_error err = {0};
    int rc = vt_wang_pack_open(s, &info, &err);
    if (rc == 0 && o->level >= vts_store_geometry(s)->level_count) {
        vt_wang_info_release(&info);
        return vt_usage_error("level %u is outside '%s' (levels 0..%u)", o->level,
                              vts_store_name(s), vts_store_geometry(s)->level_count - 1);
    }
    if (rc == 0)
        rc = vt_wang_pack_write_region(s, &info, o->level, o->wang_x, o->wang_y, o->wang_w,
                                       o->wang_h, o->out_path, &err);
    vt_wang_info_release(&info);
    if (rc != 0) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        return VT_EXIT_BAD_INPUT;
    }
    vt_log(VT_LOG_INFO, "wrote '%s'", o->out_path);
    return VT_EXIT_OK;
}

/* An extract of a georeferenced store gets its position as sidecar files (docs/geospatial.md):
 * OUT.aux.xml and a world file, with the transform of the level (and tile) written. */
static int write_georef(const struct vts_store *s, const struct options *o)
{
    struct vt_georef g;
    vt_store_georef(s, o->layer, &g);
    if ((!g.has_transform && !g.crs_wkt) || vt_output_path_is_stdio(o->out_path))
        return VT_EXIT_OK;
    if (g.has_transform) {
        double t[6];
        memcpy(t, g.transform, sizeof t);
        const struct vts_geometry *geo = vts_store_geometry(s);
        int64_t x = 0, y = 0; /* a tile's payload starts at its border */
        if (o->has_tile) {
            x = (int64_t)o->tile_x * geo->tile_content_px - geo->border_px;
            y = (int64_t)o->tile_y * geo->tile_content_px - geo->border_px;
        }
        vt_georef_region(t, o->level, x, y, g.transform);
    }
    char world[VT_PATH_MAX];
    struct vts_error err = {0};
    if (vt_georef_file_write(o->out_path, &g, world, sizeof world, &err) != 0) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        return VT_EXIT_BAD_INPUT;
    }
    vt_log(VT_LOG_INFO, "wrote '%s.aux.xml'%s%s%s", o->out_path, world[0] ? " and '" : "", world,
           world[0] ? "'" : "");
    return VT_EXIT_OK;
}

static int run_extract(const struct vts_store *s, const struct options *o)
{
    if (o->wang_region)
        return run_wang_region(s, o);
    struct vt_tile_reader r;
    struct vts_error err = {0};
    struct vts_tile_entry e;
    int rc = check_extract_range(s, o);
    if (rc != 0)
        return rc;
    bool tiff = wants_tiff(o->out_path);
    rc = vt_tile_reader_init(&r, s, o->layer, &err);
    const char *nodata = vts_store_meta_find(s, "nodata"); /* empty tiles are nodata */
    char *end = NULL;
    if (nodata) {
        r.fill = strtod(nodata, &end);
        r.has_fill = end != nodata && !*end;
    }
    if (rc == 0 && !tiff && (r.img.sample == VTS_SAMPLE_F16 || r.img.sample == VTS_SAMPLE_F32))
        vt_log(VT_LOG_WARN,
               "layer %u holds %s samples: writing a 16-bit PNG clamped to [0,1] (a .tif output "
               "keeps the values)",
               o->layer, vts_sample_name(r.img.sample));
    if (rc == 0 && o->has_tile &&
        vts_store_tile(s, o->layer, o->level, o->tile_x, o->tile_y, &e, NULL) == 0 && e.length == 0)
        vt_log(VT_LOG_WARN, "tile %u,%u of level %u is empty: writing %s", o->tile_x, o->tile_y,
               o->level, r.has_fill ? "its nodata value" : "zeros");
    if (rc == 0)
        rc = vt_tile_reader_write_image(&r, o->level, o->has_tile, o->tile_x, o->tile_y,
                                        o->out_path, tiff, &err);
    vt_tile_reader_release(&r);
    if (rc != 0) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        return VT_EXIT_BAD_INPUT;
    }
    vt_log(VT_LOG_INFO, "wrote '%s'", o->out_path);
    return write_georef(s, o);
}

/* A store read from standard input: its spooled copy, mapped (vts_open_memory names it). */
struct stdin_store {
    void *map;
    size_t size;
};

/* Opens STORE; "-" is standard input, copied to a scratch file and mapped, named '<stdin>'
 * (the reader seeks). Returns NULL with the message in err. Unmap m after vts_close(). */
static struct vts_store *open_store(const char *path, struct stdin_store *m, struct vts_error *err)
{
    *m = (struct stdin_store){0};
    if (!vt_output_path_is_stdio(path))
        return vts_open(path, err);
    struct vt_stdin_spool spool;
    struct vts_store *s = NULL;
    if (vt_stdin_spool_read(&spool, err) != 0)
        goto out;
    if ((uint64_t)(size_t)spool.size != spool.size) {
        vt_error_set(err, VTS_ERR_LIMIT, "'%s' is too large to map", VT_STDIN_NAME);
        goto out;
    }
    void *map = mmap(NULL, (size_t)spool.size, PROT_READ, MAP_PRIVATE, spool.file.fd, 0);
    if (map == MAP_FAILED) {
        vt_error_set(err, VTS_ERR_IO, "cannot map '%s': %s", VT_STDIN_NAME, strerror(errno));
        goto out;
    }
    *m = (struct stdin_store){map, (size_t)spool.size};
    if (!(s = vts_open_memory(map, m->size, VT_STDIN_NAME, err))) {
        munmap(m->map, m->size);
        *m = (struct stdin_store){0};
    }
out:
    vt_stdin_spool_release(&spool); /* the mapping keeps the copy until munmap */
    return s;
}

static int run(const struct options *o)
{
    struct vts_error err = {0};
    struct stdin_store mapped;
    struct vts_store *s = open_store(o->store_path, &mapped, &err);
    int rc;
    if (!s) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        return VT_EXIT_BAD_INPUT;
    }
    vt_log(VT_LOG_DEBUG, "opened '%s': %llu index entries, %llu bytes", o->store_path,
           (unsigned long long)vts_store_tile_count(s), (unsigned long long)vts_store_file_size(s));
    if (o->verify)
        rc = run_verify(s);
    else if (o->stats)
        rc = run_stats(s, o);
    else if (o->extract)
        rc = run_extract(s, o);
    else
        rc = run_summary(s, o->json);
    vts_close(s);
    if (mapped.map)
        munmap(mapped.map, mapped.size);
    return rc;
}

int main(int argc, char **argv)
{
    struct options o;
    vt_tool_init("vt-info");
    vt_output_path_use_stdio();          /* STORE -, -o - */
    vt_atomic_file_cleanup_on_signals(); /* --extract writes through a temporary file */
    int rc = parse_options(argc, argv, &o);
    if (rc >= 0)
        return rc;
    rc = validate_options(&o);
    if (rc != 0)
        return rc;
    if ((rc = vt_refuse_terminal(o.store_path, STDIN_FILENO, "a store")) >= 0 ||
        (o.extract && (rc = vt_refuse_terminal(o.out_path, STDOUT_FILENO, "a PNG")) >= 0))
        return rc;
    if (o.extract && vt_output_path_is_stdio(o.out_path))
        vt_log_alias(VT_PATH_STDIO, VT_STDOUT_NAME);
    const char *inputs[] = {o.store_path};
    if (o.extract && (rc = vt_check_output(o.out_path, inputs, 1)) >= 0)
        return rc;
    rc = run(&o);
    if (fflush(stdout) != 0 || ferror(stdout)) {
        vt_log(VT_LOG_ERROR, "cannot write to standard output");
        return VT_EXIT_BAD_INPUT;
    }
    return rc;
}
