/* vt-info: describes a .vts tile store, verifies its tiles, or extracts a tile or level as PNG.
 * Reference (options, output fields, JSON keys): docs/cli/vt-info.md. This file: options, opening
 * the store (standard input too) and the dispatch to the parts of vti.h. */
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>
#include <sys/mman.h>
#include <unistd.h>

#include "tool_common.h"
#include "vt_atomic_file.h"
#include "vt_stdin_spool.h"
#include "vt_wang_pack.h"
#include "vti.h"

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
    if (o->wang_region &&
        (!o->extract || o->has_tile || o->has_layer || vti_wants_tiff(o->out_path)))
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
        rc = vti_run_verify(s);
    else if (o->stats)
        rc = vti_run_stats(s, o);
    else if (o->extract)
        rc = vti_run_extract(s, o);
    else
        rc = vti_run_summary(s, o->json);
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
