/* vt-view: OpenGL viewer of a .vts virtual-texture store (2D pan/zoom, or 3D over a .vt.obj), in a
 * GLFW window or headless through EGL surfaceless. See docs/cli/vt-view.md and docs/viewer.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "tool_common.h"
#include "vt_atomic_file.h"
#include "vt_output_path.h"
#include "vts_clipmap.h"
#include "vtv_app.h"
#include "vtv_ramp.h"
#include "vtv_terrain.h"
#include "vtv_wang.h"

static const char usage_text[] =
    "usage: vt-view STORE.vts [SCENE.vt.obj] [options]\n"
    "       vt-view COLOUR.vts --terrain ELEVATION.vts[:LAYER] | :LAYER [options]\n"
    "       vt-view --wang PACK.vts [--extent MxN] [--origin X,Y] [--tilemap | --reference]\n"
    "Shows a virtual-texture store through a page table and a tile cache: 2D (pan/zoom over the\n"
    "whole texture) without a scene, 3D with a .vt.obj scene.\n"
    "  --headless            render offscreen (EGL surfaceless) instead of a window\n"
    "  --size WxH            frame size (default 1024x768)\n"
    "  --camera FILE         camera per frame: 2D 'CX CY ZOOM', 3D 'EX EY EZ TX TY TZ FOVY'\n"
    "  --orbit N             3D: N frames around the scene's bounding box\n"
    "  --frames N            frames to render (headless default 30; window: 0 = until closed)\n"
    "  --screenshot OUT.png  write the last frame (- for standard output, not a terminal)\n"
    "  --stats OUT.json      write per-frame statistics (- for standard output)\n"
    "  --feedback-scale 1/K  resolution of the tile-determination pass (default 1/4)\n"
    "  --filtering MODE      bilinear (default), trilinear or anisoN (N = 2..16 taps along the\n"
    "                        footprint, trilinear between levels; at most twice the store's border),\n"
    "                        or nearest (nearest level, nearest texel: the default for a store\n"
    "                        built with a selection, filter=nearest|mode|min|max or colour=index)\n"
    "  --debug MODE          none (default), levels (colour by level used), tiles (outlines)\n"
    "  --cache N             physical cache size in tiles (default 256)\n"
    "  --uploads N           tile uploads per frame at most (default 32)\n"
    "  --ram-cache N         decoded tiles kept in RAM beyond the physical cache (default: as\n"
    "                        --cache; 0 = none): evicted tiles come back without a read\n"
    "  --prefetch on|off     read the next finer tiles and the neighbours of wanted tiles\n"
    "                        ahead into the RAM cache (default on)\n"
    "  --reads N             with --sync: tiles read from the store per frame at most\n"
    "                        (default 0 = no limit), the I/O budget of a deterministic run\n"
    "  --lod-bias auto|N     levels added to the level of detail: auto (default) raises it\n"
    "                        while the wanted tiles outgrow --cache, N (0..16) fixes it\n"
    "  -j, --threads N       loader threads (default 2)\n"
    "  --sync                load tiles on the render thread (deterministic statistics)\n"
    "  --reference           render with one plain mipmapped GL texture (level 0 of the store)\n"
    "  --reference-scene ORIGINAL.obj\n"
    "                        with --reference: draw the scene before vt-offset with its own\n"
    "                        textures and MTL instead, same camera and shading\n"
    "  --layer NAME|INDEX    layer to show (default 0); in 3D, every face shows it unlit\n"
    "                        (default: the materials of the scene's MTL, each map from its\n"
    "                        layer, shaded)\n"
    "  --light X,Y,Z         direction towards the directional light (default 0.3,0.8,0.5)\n"
    "  --light-colour R,G,B  its colour, linear (default 0.85,0.85,0.85)\n"
    "  --ambient R,G,B       ambient light, linear (default 0.15,0.15,0.15)\n"
    "  --range MIN:MAX       show the layer's values MIN..MAX as 0..1 (default: the store's\n"
    "                        range metadata, else 0..1 for u8 and u16 layers and the range of\n"
    "                        the coarsest level for float layers)\n"
    "  --ramp NAME|none      one-channel layers through a colour ramp: dusk, heat, grey, or none\n"
    "                        (default: dusk for one-channel u16/f16/f32 layers, else none); index:\n"
    "                        a distinct colour per value of a one-channel u8/u16 layer (default\n"
    "                        for a colour=index store)\n"
    "  --bc-upload auto|off  BC1..BC5 tiles: upload the blocks compressed when the GL has S3TC\n"
    "                        or RGTC (auto, default) or decode them on the CPU (off)\n"
    "  --wang PACK.vts       draw a Wang pack (vt-wang) with TileTex: an output of --extent\n"
    "                        tiles from its top-left corner, trilinear; with --reference the\n"
    "                        same output assembled on the CPU in one mipmapped texture\n"
    "  --extent MxN          with --wang: tiles across and down the frame, 1..65536 (default\n"
    "                        8x8)\n"
    "  --origin X,Y          with --wang: the output tile at the frame's top-left corner,\n"
    "                        0..4294967295 each (default 0,0)\n"
    "  --tilemap             with --wang: look tiles up in a precomputed map of the hash (one\n"
    "                        fetch; hash sizes up to 4096) instead of evaluating it\n"
    "  --terrain ELEVATION.vts[:LAYER] | :LAYER\n"
    "                        3D: a grid over the whole store displaced by the elevation layer\n"
    "                        (default: the first one-channel layer; :LAYER: one of STORE.vts),\n"
    "                        draped with STORE.vts and lit; float layers as stored, u8/u16\n"
    "                        through the store's layer.N.scale and layer.N.offset\n"
    "  --terrain-grid G      vertices across and down the grid, 2..4096 (default 512)\n"
    "  --terrain-exaggeration F\n"
    "                        heights times F, 0..1000 (default 1)\n"
    "  --clipmap N           clipmap mode (2D or --terrain): per level an N x N window of\n"
    "                        tiles (1..256) around the paging centre in one texture array\n"
    "                        layer, updated toroidally, instead of the page table (no --cache,\n"
    "                        --ram-cache, --uploads, --prefetch, --reads, --feedback-scale,\n"
    "                        --reference)\n"
    "  --budget BYTES        with --clipmap: bytes uploaded per frame at most, suffix K or M\n"
    "                        (default 4M; at least one tile: C x C x texel bytes)\n"
    "  --clipmap-centre X,Y  with --clipmap: fix the paging centre at level-0 texel X,Y\n"
    "                        (default: the camera's centre; --terrain: the texel under the eye)\n"
    "  -q, --quiet           errors only\n"
    "  -v, --verbose         more messages\n"
    "  -h, --help            this help;    --version  version\n"
    "Window keys: arrows/WASD pan, +/- or wheel zoom, drag pan/orbit, F filtering, G debug view,\n"
    "Esc/Q quit.\n";

enum {
    OPT_HEADLESS = 256,
    OPT_SIZE,
    OPT_CAMERA,
    OPT_ORBIT,
    OPT_FRAMES,
    OPT_SCREENSHOT,
    OPT_STATS,
    OPT_FEEDBACK,
    OPT_FILTERING,
    OPT_DEBUG,
    OPT_CACHE,
    OPT_UPLOADS,
    OPT_RAM_CACHE,
    OPT_PREFETCH,
    OPT_READS,
    OPT_SYNC,
    OPT_REFERENCE,
    OPT_REFERENCE_SCENE,
    OPT_LAYER,
    OPT_BC_UPLOAD,
    OPT_LIGHT,
    OPT_LIGHT_COLOUR,
    OPT_AMBIENT,
    OPT_LOD_BIAS,
    OPT_RANGE,
    OPT_RAMP,
    OPT_WANG,
    OPT_EXTENT,
    OPT_ORIGIN,
    OPT_TILEMAP,
    OPT_TERRAIN,
    OPT_TERRAIN_GRID,
    OPT_TERRAIN_EXAGGERATION,
    OPT_CLIPMAP,
    OPT_BUDGET,
    OPT_CLIPMAP_CENTRE,
    OPT_VERSION,
};

/* "X,Y,Z": three finite numbers in [lo, hi]. */
static int parse_vec3(const char *s, double lo, double hi, float out[3])
{
    const char *p = s;
    for (int k = 0; k < 3; k++) {
        char *end;
        double v = strtod(p, &end);
        if (end == p || !isfinite(v) || v < lo || v > hi || *end != (k < 2 ? ',' : '\0'))
            return -1;
        out[k] = (float)v;
        p = end + 1;
    }
    return 0;
}

/* "-": standard output for one of --screenshot and --stats (a PNG not to a terminal), never an
 * input. Returns an exit status, or -1 to go on. */
static int check_stdio(const struct vtv_options *o)
{
    const char *inputs[] = {o->store_path, o->obj_path, o->camera_path, o->reference_scene};
    for (size_t i = 0; i < sizeof inputs / sizeof inputs[0]; i++)
        if (vt_output_path_is_stdio(inputs[i]))
            return vt_usage_error(
                "inputs cannot be standard input ('-'): name the file (./- for a file named -)");
    bool shot = vt_output_path_is_stdio(o->screenshot), stats = vt_output_path_is_stdio(o->stats);
    if (shot && stats)
        return vt_usage_error("--screenshot and --stats cannot both be standard output ('-')");
    int status = vt_refuse_terminal(o->screenshot, STDOUT_FILENO, "a PNG");
    if (status < 0 && (shot || stats))
        vt_log_alias(VT_PATH_STDIO, VT_STDOUT_NAME);
    return status;
}

/* "BYTES" with an optional K or M suffix (1024-based), 1 .. 2^40. */
static int parse_bytes(const char *s, uint64_t *out)
{
    char *end;
    if (*s < '0' || *s > '9')
        return -1;
    unsigned long long v = strtoull(s, &end, 10);
    unsigned shift = *end == 'K' ? 10 : *end == 'M' ? 20 : 0;
    if (shift)
        end++;
    if (*end || end == s || v == 0 || v > (1ull << 40) >> shift)
        return -1;
    *out = (uint64_t)v << shift;
    return 0;
}

/* "X,Y": two finite numbers (level-0 texels). */
static int parse_centre(const char *s, double out[2])
{
    char *end;
    out[0] = strtod(s, &end);
    if (end == s || *end != ',' || !isfinite(out[0]))
        return -1;
    const char *p = end + 1;
    out[1] = strtod(p, &end);
    if (end == p || *end || !isfinite(out[1]) || fabs(out[0]) > 1e12 || fabs(out[1]) > 1e12)
        return -1;
    return 0;
}

/* --clipmap's conflicts (docs/cli/vt-view.md): the page table's own options are refused, as are
 * the modes it does not draw yet. pt_option: the first page-table option given, or NULL. */
static int check_clipmap(const struct vtv_options *o, bool clip_opt, const char *pt_option)
{
    if (!o->clipmap)
        return clip_opt ? vt_usage_error("--budget and --clipmap-centre need --clipmap N") : -1;
    if (o->reference)
        return vt_usage_error("--clipmap and --reference exclude each other");
    if (o->obj_path)
        return vt_usage_error(
            "--clipmap draws the 2D view and --terrain: a 3D scene (SCENE.vt.obj) is not yet "
            "supported");
    if (pt_option)
        return vt_usage_error("%s is a page-table option: not with --clipmap", pt_option);
    if (o->aniso > 1)
        return vt_usage_error("--clipmap filters bilinear, trilinear or nearest: not anisoN");
    return -1;
}

/* --wang PACK.vts: its own checks, then vtv_wang_run(). */
static int run_wang(struct vtv_options *o, int rest, bool frames_set)
{
    if (!o->wang_path)
        return vt_usage_error("--extent, --origin and --tilemap need --wang PACK.vts");
    if (rest > 0)
        return vt_usage_error("--wang takes no STORE or SCENE argument");
    if (o->camera_path || o->orbit || o->reference_scene || o->layer_name || o->stats)
        return vt_usage_error(
            "--wang draws its extent: no --camera, --orbit, --reference-scene, --layer or --stats");
    if (o->clipmap)
        return vt_usage_error("--clipmap and --wang exclude each other");
    if (o->wang_tilemap && o->reference)
        return vt_usage_error("--tilemap and --reference exclude each other");
    if (!o->extent_x)
        o->extent_x = o->extent_y = 8;
    if (!frames_set)
        o->frames = o->headless ? 1 : 0;
    if (o->headless && o->frames == 0)
        return vt_usage_error("--frames 0 needs a window (no --headless)");
    o->store_path = o->wang_path;
    int status = check_stdio(o);
    if (status >= 0)
        return status;
    status = vt_check_output(o->screenshot, &o->wang_path, 1);
    return status >= 0 ? status : vtv_wang_run(o);
}

int main(int argc, char **argv)
{
    vt_tool_init("vt-view");
    vt_output_path_use_stdio(); /* --screenshot -, --stats - */
    vt_atomic_file_cleanup_on_signals();
    static const struct option longopts[] = {
        {"headless", no_argument, NULL, OPT_HEADLESS},
        {"size", required_argument, NULL, OPT_SIZE},
        {"camera", required_argument, NULL, OPT_CAMERA},
        {"orbit", required_argument, NULL, OPT_ORBIT},
        {"frames", required_argument, NULL, OPT_FRAMES},
        {"screenshot", required_argument, NULL, OPT_SCREENSHOT},
        {"stats", required_argument, NULL, OPT_STATS},
        {"feedback-scale", required_argument, NULL, OPT_FEEDBACK},
        {"filtering", required_argument, NULL, OPT_FILTERING},
        {"debug", required_argument, NULL, OPT_DEBUG},
        {"cache", required_argument, NULL, OPT_CACHE},
        {"uploads", required_argument, NULL, OPT_UPLOADS},
        {"ram-cache", required_argument, NULL, OPT_RAM_CACHE},
        {"prefetch", required_argument, NULL, OPT_PREFETCH},
        {"reads", required_argument, NULL, OPT_READS},
        {"threads", required_argument, NULL, 'j'},
        {"sync", no_argument, NULL, OPT_SYNC},
        {"reference", no_argument, NULL, OPT_REFERENCE},
        {"reference-scene", required_argument, NULL, OPT_REFERENCE_SCENE},
        {"layer", required_argument, NULL, OPT_LAYER},
        {"bc-upload", required_argument, NULL, OPT_BC_UPLOAD},
        {"light", required_argument, NULL, OPT_LIGHT},
        {"light-colour", required_argument, NULL, OPT_LIGHT_COLOUR},
        {"ambient", required_argument, NULL, OPT_AMBIENT},
        {"lod-bias", required_argument, NULL, OPT_LOD_BIAS},
        {"range", required_argument, NULL, OPT_RANGE},
        {"ramp", required_argument, NULL, OPT_RAMP},
        {"wang", required_argument, NULL, OPT_WANG},
        {"extent", required_argument, NULL, OPT_EXTENT},
        {"origin", required_argument, NULL, OPT_ORIGIN},
        {"tilemap", no_argument, NULL, OPT_TILEMAP},
        {"terrain", required_argument, NULL, OPT_TERRAIN},
        {"terrain-grid", required_argument, NULL, OPT_TERRAIN_GRID},
        {"terrain-exaggeration", required_argument, NULL, OPT_TERRAIN_EXAGGERATION},
        {"clipmap", required_argument, NULL, OPT_CLIPMAP},
        {"budget", required_argument, NULL, OPT_BUDGET},
        {"clipmap-centre", required_argument, NULL, OPT_CLIPMAP_CENTRE},
        {"quiet", no_argument, NULL, 'q'},
        {"verbose", no_argument, NULL, 'v'},
        {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, OPT_VERSION},
        {NULL, 0, NULL, 0},
    };
    struct vtv_options o;
    vtv_options_default(&o);
    bool frames_set = false, origin_set = false; /* origin_set: any --wang option */
    bool terrain_set = false;                    /* --terrain-grid or --terrain-exaggeration */
    bool clip_opt = false;                       /* --budget or --clipmap-centre */
    const char *pt_option = NULL;                /* a page-table option given */
    int common;
    opterr = 0;
    int c;
    while ((c = vt_getopt_long(argc, argv, ":hj:qv", longopts)) != -1) {
        switch (c) {
        case OPT_HEADLESS:
            o.headless = true;
            break;
        case OPT_SIZE:
            if (vt_parse_u32_pair(optarg, 'x', 16, 8192, &o.width, &o.height) != 0)
                return vt_usage_error("--size '%s': expected WxH, 16..8192 each", optarg);
            break;
        case OPT_CAMERA:
            o.camera_path = optarg;
            break;
        case OPT_ORBIT:
            if (vt_parse_u32(optarg, 1, 1000000, &o.orbit) != 0)
                return vt_usage_error("--orbit '%s': expected a frame count >= 1", optarg);
            break;
        case OPT_FRAMES:
            if (vt_parse_u32(optarg, 0, 10000000, &o.frames) != 0)
                return vt_usage_error("--frames '%s': expected a number", optarg);
            frames_set = true;
            break;
        case OPT_SCREENSHOT:
            o.screenshot = optarg;
            break;
        case OPT_STATS:
            o.stats = optarg;
            break;
        case OPT_FEEDBACK:
            pt_option = "--feedback-scale";
            if (strncmp(optarg, "1/", 2) != 0 || vt_parse_u32(optarg + 2, 1, 16, &o.feedback_div))
                return vt_usage_error("--feedback-scale '%s': expected 1/K with K in 1..16",
                                      optarg);
            break;
        case OPT_FILTERING:
            o.aniso = 1;
            o.nearest = strcmp(optarg, "nearest") == 0;
            if (strcmp(optarg, "bilinear") == 0 || o.nearest)
                o.trilinear = false;
            else if (strcmp(optarg, "trilinear") == 0)
                o.trilinear = true;
            else if (strncmp(optarg, "aniso", 5) == 0 && !vt_parse_u32(optarg + 5, 2, 16, &o.aniso))
                o.trilinear = true;
            else
                return vt_usage_error(
                    "--filtering '%s': expected bilinear, trilinear or anisoN (N in 2..16), or nearest",
                    optarg);
            break;
        case OPT_DEBUG:
            if (strcmp(optarg, "none") == 0)
                o.debug = 0;
            else if (strcmp(optarg, "levels") == 0)
                o.debug = 1;
            else if (strcmp(optarg, "tiles") == 0)
                o.debug = 2;
            else
                return vt_usage_error("--debug '%s': expected none, levels or tiles", optarg);
            break;
        case OPT_CACHE:
            pt_option = "--cache";
            if (vt_parse_u32(optarg, 2, 65536, &o.cache_tiles) != 0)
                return vt_usage_error("--cache '%s': expected 2..65536 tiles", optarg);
            break;
        case OPT_UPLOADS:
            pt_option = "--uploads";
            if (vt_parse_u32(optarg, 1, 65536, &o.uploads) != 0)
                return vt_usage_error("--uploads '%s': expected 1..65536", optarg);
            break;
        case OPT_RAM_CACHE:
            pt_option = "--ram-cache";
            if (vt_parse_u32(optarg, 0, 1u << 20, &o.ram_tiles) != 0)
                return vt_usage_error("--ram-cache '%s': expected 0..1048576 tiles", optarg);
            break;
        case OPT_PREFETCH:
            pt_option = "--prefetch";
            if (strcmp(optarg, "on") == 0)
                o.prefetch = true;
            else if (strcmp(optarg, "off") == 0)
                o.prefetch = false;
            else
                return vt_usage_error("--prefetch '%s': expected on or off", optarg);
            break;
        case OPT_READS:
            pt_option = "--reads";
            if (vt_parse_u32(optarg, 0, 65536, &o.reads) != 0)
                return vt_usage_error("--reads '%s': expected 0..65536", optarg);
            break;
        case 'j':
            if (vt_parse_u32(optarg, 1, 64, &o.threads) != 0)
                return vt_usage_error("--threads '%s': expected 1..64", optarg);
            break;
        case OPT_SYNC:
            o.sync = true;
            break;
        case OPT_REFERENCE:
            o.reference = true;
            break;
        case OPT_REFERENCE_SCENE:
            o.reference_scene = optarg;
            break;
        case OPT_LAYER:
            o.layer_name = optarg;
            break;
        case OPT_BC_UPLOAD:
            if (strcmp(optarg, "auto") == 0)
                o.no_bc_upload = false;
            else if (strcmp(optarg, "off") == 0)
                o.no_bc_upload = true;
            else
                return vt_usage_error("--bc-upload '%s': expected auto or off", optarg);
            break;
        case OPT_LIGHT:
            if (parse_vec3(optarg, -1e6, 1e6, o.light_dir) != 0 ||
                fabsf(o.light_dir[0]) + fabsf(o.light_dir[1]) + fabsf(o.light_dir[2]) == 0.0f)
                return vt_usage_error("--light '%s': expected X,Y,Z, not all 0", optarg);
            break;
        case OPT_LIGHT_COLOUR:
            if (parse_vec3(optarg, 0, 1e6, o.light_colour) != 0)
                return vt_usage_error("--light-colour '%s': expected R,G,B >= 0", optarg);
            break;
        case OPT_AMBIENT:
            if (parse_vec3(optarg, 0, 1e6, o.ambient) != 0)
                return vt_usage_error("--ambient '%s': expected R,G,B >= 0", optarg);
            break;
        case OPT_LOD_BIAS: {
            char *end;
            double b = strtod(optarg, &end);
            o.auto_lod = strcmp(optarg, "auto") == 0;
            if (!o.auto_lod && (end == optarg || *end || !(b >= 0 && b <= 16)))
                return vt_usage_error("--lod-bias '%s': expected auto or 0..16", optarg);
            o.lod_bias = o.auto_lod ? 0.0f : (float)b;
            break;
        }
        case OPT_RANGE: {
            char *end, *mid;
            double lo = strtod(optarg, &mid), hi = 0;
            bool ok = mid != optarg && *mid == ':';
            if (ok)
                hi = strtod(mid + 1, &end);
            ok = ok && end != mid + 1 && *end == '\0' && isfinite(lo) && isfinite(hi) && lo < hi &&
                 fabs(lo) <= 3e38 && fabs(hi) <= 3e38 && (float)lo < (float)hi;
            if (!ok)
                return vt_usage_error("--range '%s': expected MIN:MAX, finite numbers, MIN < MAX",
                                      optarg);
            o.has_range = true;
            o.range[0] = (float)lo;
            o.range[1] = (float)hi;
            break;
        }
        case OPT_RAMP: {
            enum vtv_ramp_kind k;
            o.index = strcmp(optarg, "index") == 0;
            if (o.index)
                break;
            if (!vtv_ramp_parse(optarg, &k))
                return vt_usage_error("--ramp '%s': expected dusk, heat, grey, index or none",
                                      optarg);
            o.ramp = (int)k;
            break;
        }
        case OPT_WANG:
            o.wang_path = optarg;
            break;
        case OPT_EXTENT:
            if (vt_parse_u32_pair(optarg, 'x', 1, 65536, &o.extent_x, &o.extent_y) != 0)
                return vt_usage_error("--extent '%s': expected MxN tiles, 1..65536 each", optarg);
            break;
        case OPT_TILEMAP:
            o.wang_tilemap = true;
            origin_set = true; /* a --wang option */
            break;
        case OPT_ORIGIN:
            if (vt_parse_u32_pair(optarg, ',', 0, UINT32_MAX, &o.origin_x, &o.origin_y) != 0)
                return vt_usage_error("--origin '%s': expected X,Y tiles", optarg);
            origin_set = true;
            break;
        case OPT_TERRAIN:
            o.terrain = optarg;
            break;
        case OPT_TERRAIN_GRID:
            if (vt_parse_u32(optarg, 2, VTV_TERRAIN_GRID_MAX, &o.terrain_grid) != 0)
                return vt_usage_error("--terrain-grid '%s': expected 2..%u vertices", optarg,
                                      VTV_TERRAIN_GRID_MAX);
            terrain_set = true;
            break;
        case OPT_TERRAIN_EXAGGERATION: {
            char *end;
            o.terrain_exaggeration = strtod(optarg, &end);
            if (end == optarg || *end || !(o.terrain_exaggeration >= 0) ||
                o.terrain_exaggeration > 1000)
                return vt_usage_error("--terrain-exaggeration '%s': expected 0..1000", optarg);
            terrain_set = true;
            break;
        }
        case OPT_CLIPMAP:
            if (vt_parse_u32(optarg, 1, VTS_CLIPMAP_MAX_N, &o.clipmap) != 0)
                return vt_usage_error("--clipmap '%s': expected a window of 1..%d tiles", optarg,
                                      VTS_CLIPMAP_MAX_N);
            break;
        case OPT_BUDGET:
            if (parse_bytes(optarg, &o.budget) != 0)
                return vt_usage_error("--budget '%s': expected bytes, 1..2^40, suffix K or M",
                                      optarg);
            clip_opt = true;
            break;
        case OPT_CLIPMAP_CENTRE:
            if (parse_centre(optarg, o.clipmap_centre) != 0)
                return vt_usage_error("--clipmap-centre '%s': expected X,Y level-0 texels", optarg);
            o.clipmap_centre_set = clip_opt = true;
            break;
        default:
            if ((common = vt_common_option(c, OPT_VERSION, usage_text, argv)) >= 0)
                return common;
        }
    }
    int rest = argc - optind;
    if (terrain_set && !o.terrain)
        return vt_usage_error("--terrain-grid and --terrain-exaggeration need --terrain");
    if (o.terrain && (o.wang_path || o.extent_x || origin_set))
        return vt_usage_error("--terrain and --wang exclude each other");
    if (o.terrain && rest == 2)
        return vt_usage_error("--terrain draws its own grid: no SCENE.vt.obj");
    if (o.terrain && o.reference_scene)
        return vt_usage_error("--terrain and --reference-scene exclude each other");
    if (o.wang_path || o.extent_x || origin_set)
        return run_wang(&o, rest, frames_set);
    if (rest < 1 || rest > 2)
        return vt_usage_error(rest < 1 ? "missing STORE.vts" : "too many arguments");
    o.store_path = argv[optind];
    o.obj_path = rest == 2 ? argv[optind + 1] : NULL;
    int status = check_clipmap(&o, clip_opt, pt_option);
    if (status >= 0)
        return status;
    if (o.orbit && !o.obj_path && !o.terrain)
        return vt_usage_error("--orbit needs a scene (SCENE.vt.obj) or --terrain");
    if (o.orbit && o.camera_path)
        return vt_usage_error("--orbit and --camera exclude each other");
    if (o.reference_scene && (!o.reference || !o.obj_path))
        return vt_usage_error("--reference-scene needs --reference and a scene (SCENE.vt.obj)");
    if (o.reads && !o.sync)
        return vt_usage_error("--reads needs --sync (the loader threads read as fast as they can)");
    if (!frames_set)
        o.frames = o.headless ? (o.orbit ? o.orbit : 30) : 0;
    if (o.headless && o.frames == 0)
        return vt_usage_error("--frames 0 needs a window (no --headless)");
    status = check_stdio(&o);
    if (status >= 0)
        return status;
    /* before any work: no output is an input (nor the screenshot the statistics); --stats - is
     * standard output, not an input "-" */
    bool stats_out = vt_output_path_is_stdio(o.stats);
    char terrain[1024] = "";
    const char *terrain_path = NULL, *terrain_layer;
    if (o.terrain && snprintf(terrain, sizeof terrain, "%s", o.terrain) < (int)sizeof terrain)
        vtv_terrain_parse(terrain, &terrain_path, &terrain_layer); /* the store's path part */
    const char *inputs[] = {o.store_path,      o.obj_path,   o.camera_path,
                            o.reference_scene, terrain_path, stats_out ? NULL : o.stats};
    status = vt_check_output(o.screenshot, inputs, 6);
    if (status < 0)
        status = vt_check_output(o.stats, inputs, 5);
    if (status < 0 && stats_out && o.screenshot)
        status = vt_check_output(o.stats, &o.screenshot, 1);
    if (status >= 0)
        return status;
    return vtv_app_run(&o);
}
