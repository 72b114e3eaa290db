/* vt-atlas: packs a scene's textures (per material, per layer) into a tile-aware atlas layout
 * (atlas.json) for vt-offset and vt-tiles --layout. See docs/cli/vt-atlas.md. */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tool_common.h"
#include "vt_atlas_place.h"
#include "vt_atlas_scene.h"
#include "vt_atomic_file.h"
#include "vt_error.h"
#include "vt_image_input.h"
#include "vt_layout.h"
#include "vt_version.h"

struct options {
    const char *output, *textures, *deps;
    char **inputs;
    uint32_t input_count;
    struct vt_atlas_place_options place;
    struct vt_atlas_scene_options scan;
    struct vt_input_limits input; /* --max-pixels, for the scan's open_texture() */
};

static void usage(FILE *f)
{
    fprintf(f,
            "usage: vt-atlas SCENE.obj... -o atlas.json [options]\n"
            "       vt-atlas --textures LIST -o atlas.json [options]\n"
            "       vt-atlas --grid RxC FILE... -o atlas.json [options]\n"
            "Packs the textures of the materials a scene's faces use (every layer: map_Kd, "
            "norm/bump,\n"
            "map_Ks, map_d, map_Ka, disp) into one tile-aware atlas layout.\n\n"
            "  -o, --output FILE        the atlas.json to write (replaced atomically)\n"
            "      --textures LIST      a file with one texture path per line instead of OBJ "
            "files\n"
            "      --grid RxC           FILE... are R rows x C columns of terrain pieces of one "
            "size,\n"
            "                           row-major from the top left, laid edge to edge\n"
            "      --tile-size N        tile content edge, a power of two 8..16384 (default 256)\n"
            "      --border N           tile border stored in the layout, 0..64 (default 4)\n"
            "      --max-size N         largest atlas edge in texels (default 1048576)\n"
            "      --gutter N           texels of a texture's own edge around each texture that "
            "shares\n"
            "                           a tile: 0 (none) or a power of two below the tile size "
            "(default 4)\n"
            "      --density            rescale textures to the median texel density (powers "
            "of two)\n"
            "      --max-scale S        density scales within 1/S..S, a power of two 1..65536 "
            "(default 4)\n"
            "      --wrap MODE          charts (moved by whole repeats) that leave one copy of "
            "their\n"
            "                           texture: auto (default: replicate small repeats, split "
            "large),\n"
            "                           replicate (copies, cropped), split (one copy that wraps; "
            "vt-offset\n"
            "                           cuts the faces on integer UV lines), report (an error)\n"
            "      --max-repeat N       most copies per direction with replicate, 1..65536 "
            "(default 16)\n"
            "      --missing MODE       missing texture: warn (default: a warning and the "
            "material's\n"
            "                           constant) | fail\n"
            "      --deps FILE          write a make rule 'OUT: every file read' to FILE\n"
            "      --max-textures N     most distinct texture files (default 1048576)\n"
            "      --max-pixels N       most texels per input image (default 2147483648)\n"
            "      --max-line-bytes N   longest OBJ/MTL/list line (default 1048576)\n"
            "  -q, --quiet              errors only;  -v, --verbose  more detail\n"
            "  -h, --help               this help;    --version  version\n");
}

static const struct option long_options[] = {{"output", required_argument, 0, 'o'},
                                             {"textures", required_argument, 0, 'T'},
                                             {"grid", required_argument, 0, 'g'},
                                             {"tile-size", required_argument, 0, 't'},
                                             {"border", required_argument, 0, 'b'},
                                             {"max-size", required_argument, 0, 'S'},
                                             {"gutter", required_argument, 0, 'G'},
                                             {"density", no_argument, 0, 'd'},
                                             {"max-scale", required_argument, 0, 's'},
                                             {"wrap", required_argument, 0, 'w'},
                                             {"max-repeat", required_argument, 0, 'r'},
                                             {"missing", required_argument, 0, 'm'},
                                             {"deps", required_argument, 0, 'D'},
                                             {"max-textures", required_argument, 0, 'X'},
                                             {"max-pixels", required_argument, 0, 'P'},
                                             {"max-line-bytes", required_argument, 0, 'L'},
                                             {"quiet", no_argument, 0, 'q'},
                                             {"verbose", no_argument, 0, 'v'},
                                             {"help", no_argument, 0, 'h'},
                                             {"version", no_argument, 0, 'V'},
                                             {0, 0, 0, 0}};

static bool is_pow2(uint32_t v)
{
    return v && !(v & (v - 1));
}

static int parse_choice(const char *s, const char *a, const char *b, bool *is_b)
{
    if (strcmp(s, a) && strcmp(s, b))
        return -1;
    *is_b = strcmp(s, b) == 0;
    return 0;
}

static void warn(void *user, const char *message)
{
    (void)user;
    vt_log(VT_LOG_WARN, "%s", message);
}

/* The scan's image opener: formats/input, within --max-pixels (user: struct vt_input_limits). */
static int open_texture(void *user, const char *path, struct vt_source *out, struct vts_error *err)
{
    return vt_image_input_open(path, user, out, err);
}

/* Parses one option; returns -1 to go on or an exit status. */
static int parse_option(int c, struct options *o)
{
    uint32_t v;
    bool b;
    switch (c) {
    case 'o':
        o->output = optarg;
        break;
    case 'T':
        o->textures = optarg;
        break;
    case 'g':
        if (vt_parse_u32_pair(optarg, 'x', 1, 65536, &o->place.grid_rows, &o->place.grid_cols))
            return vt_usage_error("--grid must be RxC (1..65536 each), not '%s'", optarg);
        break;
    case 't':
        if (vt_parse_u32(optarg, 8, 16384, &v) || !is_pow2(v))
            return vt_usage_error("--tile-size must be a power of two 8..16384, not '%s'", optarg);
        o->place.tile_content = v;
        break;
    case 'b':
        if (vt_parse_u32(optarg, 0, 64, &o->place.border))
            return vt_usage_error("--border must be 0..64, not '%s'", optarg);
        break;
    case 'S':
        if (vt_parse_u32(optarg, 8, 1u << 24, &o->place.max_edge))
            return vt_usage_error("--max-size must be 8..16777216, not '%s'", optarg);
        break;
    case 'G':
        if (vt_parse_u32(optarg, 0, 8192, &o->place.gutter) ||
            (o->place.gutter && !is_pow2(o->place.gutter)))
            return vt_usage_error("--gutter must be 0 or a power of two, not '%s'", optarg);
        break;
    case 'd':
        o->place.density = true;
        break;
    case 's':
        if (vt_parse_u32(optarg, 1, 65536, &v) || !is_pow2(v))
            return vt_usage_error("--max-scale must be a power of two 1..65536, not '%s'", optarg);
        o->place.max_scale = v;
        break;
    case 'w':
        if (strcmp(optarg, "auto") == 0)
            o->place.wrap = VT_ATLAS_WRAP_AUTO;
        else if (strcmp(optarg, "report") == 0)
            o->place.wrap = VT_ATLAS_WRAP_REPORT;
        else if (strcmp(optarg, "replicate") == 0)
            o->place.wrap = VT_ATLAS_WRAP_REPLICATE;
        else if (strcmp(optarg, "split") == 0)
            o->place.wrap = VT_ATLAS_WRAP_SPLIT;
        else
            return vt_usage_error("--wrap must be auto, report, replicate or split, not '%s'",
                                  optarg);
        break;
    case 'r':
        if (vt_parse_u32(optarg, 1, 65536, &o->place.max_repeat))
            return vt_usage_error("--max-repeat must be 1..65536, not '%s'", optarg);
        break;
    case 'm':
        if (strcmp(optarg, "skip") == 0) /* the name before 0.2 */
            b = true;
        else if (parse_choice(optarg, "fail", "warn", &b))
            return vt_usage_error("--missing must be warn or fail, not '%s'", optarg);
        o->scan.missing_skip = b;
        break;
    case 'D':
        o->deps = optarg;
        break;
    case 'X':
        if (vt_parse_u32(optarg, 1, UINT32_MAX, &o->scan.max_textures))
            return vt_usage_error("--max-textures must be 1..4294967295, not '%s'", optarg);
        break;
    case 'P': {
        char *end;
        unsigned long long p = strtoull(optarg, &end, 10);
        if (!*optarg || *end || *optarg == '-' || p == 0)
            return vt_usage_error("--max-pixels must be a positive number, not '%s'", optarg);
        o->input.max_pixels = p;
        break;
    }
    case 'L':
        if (vt_parse_u32(optarg, 16, 1u << 30, &v))
            return vt_usage_error("--max-line-bytes must be 16..1073741824, not '%s'", optarg);
        o->scan.max_line_bytes = v;
        break;
    case 'q':
        vt_log_set_level(VT_LOG_ERROR);
        break;
    case 'v':
        vt_log_set_level(vt_log_get_level() + 1);
        break;
    default:
        return vt_usage_error("unexpected option");
    }
    return -1;
}

static int parse_options(int argc, char **argv, struct options *o)
{
    *o = (struct options){.place = {.tile_content = 256,
                                    .border = 4,
                                    .max_edge = 1u << 20,
                                    .gutter = VT_ATLAS_DEFAULT_GUTTER,
                                    .max_scale = 4,
                                    .max_repeat = 16},
                          .scan = {.missing_skip = true,
                                   .max_textures = 1u << 20,
                                   .max_line_bytes = 1u << 20,
                                   .open = open_texture,
                                   .warn = warn},
                          .input = {.max_pixels = 1ull << 31}};
    int c;
    opterr = 0;
    while ((c = vt_getopt_long(argc, argv, ":o:qvh", long_options)) != -1) {
        if (c == '?' || c == ':')
            return vt_usage_getopt_error(c, argv);
        if (c == 'h') {
            usage(stdout);
            return VT_EXIT_OK;
        }
        if (c == 'V') {
            vt_print_version(stdout);
            return VT_EXIT_OK;
        }
        int rc = parse_option(c, o);
        if (rc >= 0)
            return rc;
    }
    o->inputs = argv + optind;
    o->input_count = (uint32_t)(argc - optind);
    bool grid = o->place.grid_rows != 0;
    if (!o->output)
        return vt_usage_error("no output: give -o atlas.json");
    if (o->textures && (o->input_count || grid))
        return vt_usage_error("--textures takes no other input and no --grid");
    if (!o->textures && !o->input_count)
        return vt_usage_error(grid ? "--grid needs its texture files" : "no input scene");
    if (grid && (uint64_t)o->place.grid_rows * o->place.grid_cols != o->input_count)
        return vt_usage_error(
            "--grid %ux%u needs %llu files, not %u", o->place.grid_rows, o->place.grid_cols,
            (unsigned long long)o->place.grid_rows * o->place.grid_cols, o->input_count);
    if (o->place.max_edge < o->place.tile_content)
        return vt_usage_error("--max-size %u is below the tile size %u", o->place.max_edge,
                              o->place.tile_content);
    if (o->place.gutter >= o->place.tile_content)
        return vt_usage_error("--gutter %u is not below the tile size %u", o->place.gutter,
                              o->place.tile_content);
    if (grid)
        o->scan.missing_skip = false; /* a grid needs every piece */
    o->place.output = o->output;
    o->place.generator = "vt-atlas " VT_VERSION_STRING;
    o->scan.open_user = &o->input;
    return -1;
}

/* Writes "target: dep dep..." with spaces (and other make specials) escaped. */
static int write_deps(struct vt_atomic_file *f, const char *target, char *const *deps, size_t n,
                      struct vts_error *err)
{
    size_t cap = 4096, len = 0;
    char *buf = malloc(cap);
    int rc = 0;
    for (size_t i = 0; i <= n && buf; i++) {
        const char *s = i == 0 ? target : deps[i - 1];
        size_t need = 2 * strlen(s) + 4;
        if (len + need > cap) {
            cap = 2 * (len + need);
            char *nb = realloc(buf, cap);
            if (!nb) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = nb;
        }
        if (i > 0)
            buf[len++] = ' ';
        for (; *s; s++) {
            if (*s == ' ' || *s == '\\' || *s == '#' || *s == ':')
                buf[len++] = '\\';
            if (*s == '$')
                buf[len++] = '$';
            buf[len++] = *s;
        }
        if (i == 0)
            buf[len++] = ':';
    }
    if (!buf)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    buf[len++] = '\n';
    rc = vt_atomic_file_pwrite(f, buf, len, 0, err);
    free(buf);
    return rc;
}

static void print_summary(const struct options *o, const struct vt_layout *l,
                          const struct vt_atlas_place_report *r, uint32_t texture_files)
{
    /* on stderr with the tool's prefix, as vt-offset's (-q silences it) */
    char layers[256] = "";
    for (uint32_t k = 0; k < l->layer_count; k++) {
        strncat(layers, k ? ", " : "", sizeof layers - strlen(layers) - 1);
        strncat(layers, l->layers[k].name, sizeof layers - strlen(layers) - 1);
    }
    char shared[160] = "";
    if (r->shared_cells)
        snprintf(shared, sizeof shared, "; %u materials share %u cell%s", r->shared,
                 r->shared_cells, r->shared_cells == 1 ? "" : "s");
    if (r->wang) /* pack materials: no entry (docs/wang.md) */
        snprintf(shared + strlen(shared), sizeof shared - strlen(shared),
                 "; %u Wang pack material%s (no entry)", r->wang, r->wang == 1 ? "" : "s");
    vt_log(
        VT_LOG_WARN,
        "wrote '%s': %u entries (%u constant, %u replicated, %u rescaled%s) from %u texture files; layers %s",
        o->output, l->entry_count, r->constant, r->replicated, r->scaled, shared, texture_files,
        layers);
    vt_log(VT_LOG_WARN, "atlas %ux%u (%ux%u tiles of %u), tiles used %llu, empty %llu, fill %.1f%%",
           l->width, l->height, r->pack.tiles_x, r->pack.tiles_y, l->tile_content,
           (unsigned long long)r->pack.tiles_used, (unsigned long long)r->pack.tiles_empty,
           100.0 * r->pack.fill_ratio);
    char area[96] = "";
    if (r->whole_area)
        snprintf(area, sizeof area, "; atlas area %.1f%% of whole textures",
                 100.0 * (double)l->width * l->height / (double)r->whole_area);
    vt_log(VT_LOG_WARN,
           "charts %u (%u moved by whole repeats); entries: %u fit, %u replicated, %u split "
           "(vt-offset cuts their faces), %u cropped%s",
           r->charts, r->moved_charts, r->fit, r->replicated, r->split, r->cropped, area);
    if (o->place.density)
        vt_log(VT_LOG_INFO, "target texel density %g texels per world unit^2 (median)",
               r->target_density);
}

/* -v: a material's alpha mode and why (docs/atlas-format.md, "Alpha modes"), unless it is none
 * for want of a d < 1, a map_d or a map_Kd with alpha. */
static void print_alpha(const struct vt_atlas_scene *scene, const struct vt_atlas_material *m)
{
    const char *mode = vt_layout_alpha_name(m->features.alpha);
    const struct vt_atlas_texture *t =
        m->texture[VT_ATLAS_DIFFUSE] >= 0 ? &scene->textures[m->texture[VT_ATLAS_DIFFUSE]] : NULL;
    switch (m->alpha_reason) {
    case VT_ATLAS_ALPHA_BY_MTL:
        vt_log(VT_LOG_INFO, "material '%s': alpha %s (vt_alpha)", m->name, mode);
        break;
    case VT_ATLAS_ALPHA_BY_D:
        vt_log(VT_LOG_INFO, "material '%s': alpha %s (d %g)", m->name, mode, m->features.d);
        break;
    case VT_ATLAS_ALPHA_BY_MAP_D:
        vt_log(VT_LOG_INFO, "material '%s': alpha %s (map_d)", m->name, mode);
        break;
    case VT_ATLAS_ALPHA_BY_TEXELS:
        if (t && t->alpha_scanned && t->alpha.read)
            vt_log(VT_LOG_INFO,
                   "material '%s': alpha %s (map_Kd '%s': %.3g%% clear, %.3g%% partial of the "
                   "%llu texels read of %llu)",
                   m->name, mode, t->path, 100.0 * t->alpha.clear / t->alpha.read,
                   100.0 * t->alpha.partial / t->alpha.read, (unsigned long long)t->alpha.read,
                   (unsigned long long)t->alpha.texels);
        break;
    default: /* none for want of anything else: not worth a line */
        break;
    }
}

/* -v: what was chosen for each material. */
static void print_choices(const struct vt_atlas_scene *scene, const struct vt_layout *l,
                          const struct vt_atlas_place_choice *c)
{
    if (vt_log_get_level() < VT_LOG_INFO || !c)
        return;
    for (uint32_t i = 0; i < scene->material_count; i++) {
        const struct vt_atlas_material *m = &scene->materials[i];
        if (m->wang) {
            vt_log(VT_LOG_INFO, "material '%s': wang, pack '%s' scale %g (no entry)", m->name,
                   m->wang, m->wang_scale);
            continue;
        }
        const struct vt_layout_entry *e = &l->entries[c[i].entry];
        print_alpha(scene, m);
        if (!m->has_uv || m->umax < m->umin) {
            vt_log(VT_LOG_INFO, "material '%s': %s, entry '%s'", m->name, c[i].how, e->name);
            continue;
        }
        vt_log(VT_LOG_INFO,
               "material '%s': %s, entry '%s' (%ux%u copies, %ux%u texels held); %u charts, "
               "u %g..%g v %g..%g as written, u %g..%g v %g..%g moved",
               m->name, c[i].how, e->name, c[i].repeat_u, c[i].repeat_v, c[i].crop_width,
               c[i].crop_height, m->charts, m->raw_umin, m->raw_umax, m->raw_vmin, m->raw_vmax,
               m->umin, m->umax, m->vmin, m->vmax);
    }
}

static int scan(const struct options *o, struct vt_atlas_scene *scene, struct vts_error *err)
{
    if (o->textures)
        return vt_atlas_scene_scan_list(scene, o->textures, &o->scan, err);
    if (o->place.grid_rows)
        return vt_atlas_scene_scan_files(scene, o->inputs, o->input_count, &o->scan, err);
    for (uint32_t i = 0; i < o->input_count; i++) {
        int rc = vt_atlas_scene_scan_obj(scene, o->inputs[i], &o->scan, err);
        if (rc)
            return rc;
    }
    return 0;
}

/* Neither atlas.json nor the --deps file may be one of the n files in inputs (nor the deps file
 * atlas.json). Returns -1 when they may be written, else the exit status. */
static int check_outputs(const struct options *o, const char *const *inputs, size_t n)
{
    int status = vt_check_output(o->output, inputs, n);
    if (status < 0 && o->deps) {
        const char *json[] = {o->output};
        if ((status = vt_check_output(o->deps, inputs, n)) < 0)
            status = vt_check_output(o->deps, json, 1);
    }
    return status;
}

static int run(const struct options *o)
{
    struct vt_atlas_scene scene = {0};
    struct vt_layout layout = {0};
    struct vt_atlas_place_report report;
    struct vt_atomic_file deps = {.fd = -1};
    struct vt_atlas_place_choice *choices = NULL;
    struct vts_error err = {0};
    int rc = scan(o, &scene, &err);
    /* the MTL files and textures are known once scanned: before anything is written */
    if (!rc && check_outputs(o, (const char *const *)scene.deps, scene.dep_count) >= 0) {
        rc = VTS_ERR_BAD_INPUT;
        goto out;
    }
    if (!rc &&
        !(choices = calloc(scene.material_count ? scene.material_count : 1, sizeof *choices)))
        rc = vt_error_set(&err, VTS_ERR_NOMEM, "out of memory");
    if (!rc)
        rc = vt_atlas_place_choices(&scene, &o->place, &layout, &report, choices, &err);
    if (!rc && o->deps) {
        rc = vt_atomic_file_create(&deps, o->deps, "tmp", VT_ATOMIC_FILE_SEQUENTIAL, &err);
        if (!rc)
            rc = write_deps(&deps, o->output, scene.deps, scene.dep_count, &err);
    }
    if (!rc)
        rc = vt_layout_write(o->output, &layout, &err);
    if (!rc && o->deps && (rc = vt_atomic_file_commit(&deps, &err))) {
        struct vt_output_target json;
        if (vt_output_path_resolve(o->output, &json, NULL) == 0 && json.kind == VT_OUTPUT_REGULAR)
            unlink(json.path); /* all or nothing (a device or FIFO stays) */
    }
    if (!rc) {
        print_choices(&scene, &layout, choices);
        print_summary(o, &layout, &report, scene.texture_count);
    } else
        vt_log(VT_LOG_ERROR, "%s", err.message);
out:
    if (deps.fd >= 0)
        vt_atomic_file_abort(&deps);
    free(choices);
    vt_layout_release(&layout);
    vt_atlas_scene_release(&scene);
    if (rc == VTS_ERR_ARG)
        return VT_EXIT_USAGE;
    return rc ? VT_EXIT_BAD_INPUT : VT_EXIT_OK;
}

int main(int argc, char **argv)
{
    vt_tool_init("vt-atlas");
    vt_atomic_file_cleanup_on_signals();
    struct options o;
    int rc = parse_options(argc, argv, &o);
    if (rc >= 0)
        return rc;
    if ((rc = check_outputs(&o, (const char *const *)o.inputs, o.input_count)) >= 0)
        return rc;
    const char *list[] = {o.textures};
    if (o.textures && (rc = check_outputs(&o, list, 1)) >= 0)
        return rc;
    return run(&o);
}
