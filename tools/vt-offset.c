/* vt-offset: rewrites the texture coordinates of an OBJ scene onto the atlas of a layout
 * (atlas.json), writing OUT.obj (each face keeps its material) and OUT.mtl (every material the
 * faces use, its constants and alpha mode, its maps naming the store's layers). Reference:
 * docs/cli/vt-offset.md; the engine is lib/offset/vt_offset.c. */
#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "tool_common.h"
#include "vt_atlas_place.h"
#include "vt_atomic_file.h"
#include "vt_error.h"
#include "vt_layout.h"
#include "vt_obj.h"
#include "vt_offset.h"
#include "vt_output_path.h"
#include "vt_uv_text.h"
#include "vt_version.h"

struct options {
    const char *obj_path;
    const char *layout_path;
    const char *out_path;
    const char *mtl_path; /* --mtl, or NULL */
    const char *store;    /* --store, or NULL */
    uint32_t digits;      /* --precision, 0: from the atlas size */
};

enum { OPT_VERSION = 256, OPT_STORE, OPT_MTL, OPT_PRECISION };

static const struct option long_options[] = {{"output", required_argument, NULL, 'o'},
                                             {"store", required_argument, NULL, OPT_STORE},
                                             {"mtl", required_argument, NULL, OPT_MTL},
                                             {"precision", required_argument, NULL, OPT_PRECISION},
                                             {"quiet", no_argument, NULL, 'q'},
                                             {"verbose", no_argument, NULL, 'v'},
                                             {"help", no_argument, NULL, 'h'},
                                             {"version", no_argument, NULL, OPT_VERSION},
                                             {NULL, 0, NULL, 0}};

static void usage(void)
{
    fputs(
        "usage: vt-offset SCENE.obj atlas.json -o OUT.obj [options]\n"
        "Put the texture coordinates (vt) of an OBJ scene onto the atlas of atlas.json (written\n"
        "by vt-atlas), in double precision. Every other line is copied unchanged.\n"
        "\n"
        "  -o, --output FILE   the OBJ to write (replaced only when complete); - for standard\n"
        "                      output (needs --mtl)\n"
        "      --mtl FILE      the MTL to write, named by OUT's mtllib line\n"
        "                      (default: OUT with .mtl instead of .obj; with -o -:\n"
        "                      required, and the mtllib line names it as given)\n"
        "      --store NAME    the store the MTL's maps name (NAME#layer), as written\n"
        "                      (default: OUT's file name with .vts instead of .obj, NAME.vts\n"
        "                      for NAME.vt.obj; with -o -, the MTL's with .vts instead of\n"
        "                      .mtl, NAME.vts for NAME.vt.mtl)\n"
        "      --precision N   decimal places of the written coordinates, 1..17 (default: the\n"
        "                      fewest keeping the round-off under 1e-4 texel of the atlas)\n"
        "  -q, --quiet         print errors only\n"
        "  -v, --verbose       print more\n"
        "  -h, --help          print this help and exit\n"
        "      --version       print the version and exit\n"
        "\n"
        "A vt shared by faces of different materials is written once per material (faces\n"
        "renumbered); usemtl lines are kept, and OUT.mtl has each material the faces use with\n"
        "its constants, its alpha mode (vt_alpha) and its maps as STORE#layer. Prints the worst round-off\n"
        "of the written coordinates in level-0 texels, as double and as float32, and warns when\n"
        "float32 loses more than 1/8 texel. V is up, as in OBJ (docs/cli/vt-offset.md).\n"
        "Exit status: 0 ok, 1 bad input (unreadable scene or atlas, bad index or number, a\n"
        "material the atlas lacks, UVs outside what it covers) or output not written, 2 bad\n"
        "usage.\n",
        stdout);
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
        } else if (c == OPT_MTL) {
            o->mtl_path = optarg;
        } else if (c == OPT_STORE) {
            o->store = optarg;
        } else if (c == OPT_PRECISION) {
            if (vt_parse_u32(optarg, 1, VT_UV_MAX_DIGITS, &o->digits) < 0)
                return vt_usage_error("--precision: '%s' is not a number in 1..%d", optarg,
                                      VT_UV_MAX_DIGITS);
        } else {
            return vt_usage_getopt_error(c, argv);
        }
    }
    vt_log_set_level(verbosity);
    if (argc - optind < 2)
        return vt_usage_error(argc == optind ? "missing SCENE.obj and atlas.json"
                                             : "missing atlas.json");
    if (argc - optind > 2)
        return vt_usage_error("unexpected argument '%s'", argv[optind + 2]);
    o->obj_path = argv[optind];
    o->layout_path = argv[optind + 1];
    if (!o->out_path)
        return vt_usage_error("missing -o OUT.obj");
    if (vt_output_path_is_stdio(o->mtl_path))
        return vt_usage_error("--mtl cannot be standard output ('-'): OUT's mtllib line names it");
    if (vt_output_path_is_stdio(o->out_path) && !o->mtl_path)
        return vt_usage_error("-o - needs --mtl FILE (the MTL's name derives from OUT's)");
    return -1;
}

/* ---- file names ---- */

static const char *base_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

/* path with its old_ext (".obj", ".mtl"; any case) replaced by ext, or ext appended;
 * malloc'ed. */
static char *with_extension(const char *path, const char *old_ext, const char *ext)
{
    size_t n = strlen(path);
    if (n > 4 && strcasecmp(path + n - 4, old_ext) == 0 && path[n - 5] != '/')
        n -= 4;
    char *out = malloc(n + strlen(ext) + 1);
    if (out) {
        memcpy(out, path, n);
        strcpy(out + n, ext);
    }
    return out;
}

/* --store's default: OUT's file name with .vts instead of .obj (.vt.obj: .vts); with OUT "-", the
 * MTL's with .vts instead of .mtl (.vt.mtl: .vts). malloc'ed; NULL when out of memory (or mtl_path
 * NULL). */
static char *default_store(const char *out_path, const char *mtl_path)
{
    char *s = NULL;
    if (!vt_output_path_is_stdio(out_path))
        s = with_extension(base_name(out_path), ".obj", ".vts");
    else if (mtl_path)
        s = with_extension(base_name(mtl_path), ".mtl", ".vts");
    /* NAME.vt.obj names NAME.vts, the store scripts/vt.mk builds next to it */
    size_t n = s ? strlen(s) : 0;
    if (n > 7 && strcasecmp(s + n - 7, ".vt.vts") == 0)
        memmove(s + n - 7, ".vts", 5);
    return s;
}

static bool same_directory(const char *a, const char *b)
{
    size_t da = (size_t)(base_name(a) - a), db = (size_t)(base_name(b) - b);
    return da == db && strncmp(a, b, da) == 0;
}

/* What OUT.obj's mtllib line says: the MTL's name when both lie in one directory, else its
 * absolute path; with OUT "-" (standard output, no directory), --mtl as given. malloc'ed, or
 * NULL with a message logged. */
static char *mtllib_text(const char *out_path, const char *mtl_path)
{
    if (vt_output_path_is_stdio(out_path))
        return strdup(mtl_path);
    if (same_directory(out_path, mtl_path) || mtl_path[0] == '/')
        return strdup(same_directory(out_path, mtl_path) ? base_name(mtl_path) : mtl_path);
    char cwd[PATH_MAX];
    if (!getcwd(cwd, sizeof cwd)) {
        vt_log(VT_LOG_ERROR, "cannot name '%s' from '%s': current directory unknown", mtl_path,
               out_path);
        return NULL;
    }
    size_t n = strlen(cwd) + strlen(mtl_path) + 2;
    char *out = malloc(n);
    if (out)
        snprintf(out, n, "%s/%s", cwd, mtl_path);
    return out;
}

/* ---- the outputs against the inputs ---- */

struct path_list {
    char **paths;
    size_t count, cap;
};

static int path_list_add(struct path_list *l, char *path)
{
    if (!path)
        return -1;
    if (l->count == l->cap) {
        size_t cap = l->cap ? l->cap * 2 : 8;
        char **p = realloc(l->paths, cap * sizeof *p);
        if (!p) {
            free(path);
            return -1;
        }
        l->paths = p;
        l->cap = cap;
    }
    l->paths[l->count++] = path;
    return 0;
}

static void path_list_release(struct path_list *l)
{
    for (size_t i = 0; i < l->count; i++)
        free(l->paths[i]);
    free(l->paths);
}

/* Adds the MTL files the mtllib lines of the OBJ name (each space-separated piece and the whole
 * rest, resolved as vt_obj does; names that are no file are skipped by the check). A plain read
 * of the file, no parse: an unreadable OBJ is reported by the rewrite. */
static int add_mtllibs(struct path_list *l, const char *obj_path)
{
    FILE *f = fopen(obj_path, "rb");
    if (!f)
        return 0;
    char *line = NULL;
    size_t cap = 0;
    int rc = 0;
    while (rc == 0 && getline(&line, &cap, f) >= 0) {
        char *s = line + strspn(line, " \t");
        if (strncmp(s, "mtllib", 6) != 0 || (s[6] != ' ' && s[6] != '\t'))
            continue;
        s += 6 + strspn(s + 6, " \t");
        s[strcspn(s, "\r\n")] = '\0';
        rc = path_list_add(l, vt_obj_resolve_path(obj_path, s));
        for (char *tok = strtok(s, " \t"); tok && rc == 0; tok = strtok(NULL, " \t"))
            rc = path_list_add(l, vt_obj_resolve_path(obj_path, tok));
    }
    if (rc == 0 && ferror(f)) { /* a read error is not the end of the file */
        vt_log(VT_LOG_ERROR, "cannot read '%s': %s", obj_path, strerror(errno));
        rc = 1;
    }
    free(line);
    fclose(f);
    return rc;
}

/* Before any work: neither OUT.obj nor OUT.mtl may be the scene, its MTL files or the layout,
 * nor OUT.mtl the same file as OUT.obj. Returns -1 when they may be written, else the exit
 * status. */
static int check_outputs(const struct options *o, const char *mtl_path)
{
    struct path_list l = {0};
    int status = VT_EXIT_BAD_INPUT;
    if (path_list_add(&l, strdup(o->out_path)) || path_list_add(&l, strdup(o->obj_path)) ||
        path_list_add(&l, strdup(o->layout_path))) {
        vt_log(VT_LOG_ERROR, "out of memory");
        goto out;
    }
    int rc = add_mtllibs(&l, o->obj_path);
    if (rc < 0)
        vt_log(VT_LOG_ERROR, "out of memory");
    if (rc)
        goto out;
    const char *const *inputs = (const char *const *)l.paths;
    /* With -o -, OUT.mtl is checked against what standard output is, not against paths[0] "-"
     * (as an input, "-" is standard input). */
    size_t skip = vt_output_path_is_stdio(o->out_path) ? 1 : 0;
    status = vt_check_output(o->out_path, inputs + 1, l.count - 1);
    if (status < 0 && skip)
        status = vt_check_output(o->out_path, &mtl_path, 1);
    if (status < 0)
        status = vt_check_output(mtl_path, inputs + skip, l.count - skip);
out:
    path_list_release(&l);
    return status;
}

/* ---- output ---- */

struct file_sink {
    struct vt_atomic_file file;
    unsigned long long offset;
};

static int sink_write(void *user, const void *data, size_t size, struct vts_error *err)
{
    struct file_sink *s = user;
    int rc = vt_atomic_file_pwrite(&s->file, data, size, s->offset, err);
    s->offset += size;
    return rc;
}

static int write_mtl(struct file_sink *mtl, const struct options *o, const struct vt_layout *layout,
                     const struct vt_offset_used *used, const char *store, struct vts_error *err)
{
    char text[4096];
    size_t n = (size_t)snprintf(text, sizeof text,
                                "written by vt-offset (vtpipe %s) from '%s' and '%s'\n"
                                "the store holds the %ux%u atlas; its layers:",
                                VT_VERSION_STRING, base_name(o->obj_path),
                                base_name(o->layout_path), layout->width, layout->height);
    for (uint32_t i = 0; i < layout->layer_count && n < sizeof text; i++)
        n += (size_t)snprintf(text + n, sizeof text - n, " %s (%s)", layout->layers[i].name,
                              layout->layers[i].map);
    struct vt_offset_sink sink = {sink_write, mtl};
    return vt_offset_write_mtl(layout, used, store, text, &sink, err);
}

static void report(const struct options *o, const char *mtl_path, const struct vt_layout *layout,
                   const struct vt_offset_stats *s)
{
    char wang[64] = ""; /* only with pack materials: other summaries stay as they were */
    if (s->vt_wang)
        snprintf(wang, sizeof wang, ", %llu vt of Wang pack materials as written",
                 (unsigned long long)s->vt_wang);
    vt_log(
        VT_LOG_WARN,
        "wrote '%s' and '%s': %llu vt on the atlas (%llu duplicated for other materials or moves, %llu unused kept)%s, %llu of %llu faces renumbered",
        o->out_path, mtl_path, (unsigned long long)s->vt_rewritten,
        (unsigned long long)s->vt_duplicated, (unsigned long long)s->vt_unused, wang,
        (unsigned long long)s->faces_rewritten, (unsigned long long)s->faces);
    if (s->charts_moved || s->faces_cut || s->faces_split)
        vt_log(
            VT_LOG_WARN,
            "%llu charts (%llu moved by whole repeats); %llu faces cut on integer UV lines into %llu pieces, %llu faces split next to cuts: %llu faces added, %llu v, %llu vt, %llu vn appended",
            (unsigned long long)s->charts, (unsigned long long)s->charts_moved,
            (unsigned long long)s->faces_cut, (unsigned long long)s->pieces,
            (unsigned long long)s->faces_split,
            (unsigned long long)(s->faces_written - s->faces_cut - s->faces_split),
            (unsigned long long)s->positions_added, (unsigned long long)s->vt_added,
            (unsigned long long)s->vn_added);
    vt_log(
        VT_LOG_WARN,
        "worst round-off on the %ux%u atlas: %.2g texel as written (%u decimals), %.2g texel as float32",
        layout->width, layout->height, s->max_error, s->digits, s->max_error_f32);
    vt_log(
        VT_LOG_INFO,
        "'%s': %llu lines, %llu vt statements, %llu faces (%llu without texture coordinates); coordinates written with %u decimals",
        o->obj_path, (unsigned long long)s->lines, (unsigned long long)s->vt_lines,
        (unsigned long long)s->faces, (unsigned long long)s->faces_without_vt, s->digits);
    if (vt_offset_f32_warning(s))
        vt_log(
            VT_LOG_WARN,
            "warning: float32 texture coordinates lose up to %.2g texel on this %ux%u atlas (vt on line %llu): read them as double",
            s->max_error_f32, layout->width, layout->height,
            (unsigned long long)s->max_error_f32_line);
}

/* The packs of the layout's pack materials relative to the MTL's folder (vt_wang paths are
 * resolved like a map's: against the MTL). */
static int wang_paths(struct vt_layout *layout, const char *mtl_path, struct vts_error *err)
{
    for (uint32_t i = 0; i < layout->wang_count; i++) {
        struct vt_layout_wang *w = &layout->wangs[i];
        char *rel = vt_atlas_place_relative_path(mtl_path, w->resolved);
        if (!rel)
            return vt_error_set(err, VTS_ERR_NOMEM, "out of memory (or no working directory)");
        free(w->pack);
        w->pack = rel;
    }
    return 0;
}

static int run(const struct options *o)
{
    struct vts_error err = {0};
    struct vt_layout layout = {0};
    struct vt_offset_used used = {0};
    struct file_sink obj = {.file.fd = -1}, mtl = {.file.fd = -1};
    char *mtl_path =
        o->mtl_path ? strdup(o->mtl_path) : with_extension(o->out_path, ".obj", ".mtl");
    char *store = o->store ? strdup(o->store) : default_store(o->out_path, mtl_path);
    char *mtllib = mtl_path ? mtllib_text(o->out_path, mtl_path) : NULL;
    int status = VT_EXIT_BAD_INPUT, rc;
    if (!mtl_path || !store || !mtllib) {
        vt_log(VT_LOG_ERROR, "out of memory");
        goto out;
    }
    if (strcmp(mtl_path, o->out_path) == 0) {
        status = vt_usage_error("--mtl names the output OBJ '%s'", o->out_path);
        goto out;
    }
    if ((status = check_outputs(o, mtl_path)) >= 0)
        goto out;
    status = VT_EXIT_BAD_INPUT;
    rc = vt_layout_read(o->layout_path, NULL, &layout, &err);
    if (rc == 0)
        rc = vt_atomic_file_create(&obj.file, o->out_path, "tmp", VT_ATOMIC_FILE_SEQUENTIAL, &err);
    if (rc == 0)
        rc = vt_atomic_file_create(&mtl.file, mtl_path, "tmp", VT_ATOMIC_FILE_SEQUENTIAL, &err);
    struct vt_offset_options opt;
    vt_offset_options_default(&opt);
    opt.layout_name = o->layout_path;
    opt.mtllib = mtllib;
    opt.material = NULL; /* usemtl lines kept: the MTL has every material */
    opt.used = &used;
    opt.digits = o->digits;
    struct vt_offset_stats stats;
    struct vt_offset_sink sink = {sink_write, &obj};
    if (rc == 0)
        rc = vt_offset_rewrite(o->obj_path, &layout, &opt, &sink, &stats, &err);
    if (rc == 0)
        rc = wang_paths(&layout, mtl_path, &err);
    if (rc == 0)
        rc = write_mtl(&mtl, o, &layout, &used, store, &err);
    if (rc == 0)
        rc = vt_atomic_file_commit(&mtl.file, &err);
    if (rc == 0) {
        rc = vt_atomic_file_commit(&obj.file, &err);
        if (rc < 0 && mtl.file.mode == VT_ATOMIC_FILE_RENAME)
            unlink(mtl.file.target_path); /* no half output (a device or FIFO stays) */
    }
    if (rc < 0) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        goto out;
    }
    report(o, mtl_path, &layout, &stats);
    status = VT_EXIT_OK;
out:
    vt_atomic_file_abort(&obj.file); /* no-ops once committed */
    vt_atomic_file_abort(&mtl.file);
    vt_layout_release(&layout);
    vt_offset_used_release(&used);
    free(mtl_path);
    free(store);
    free(mtllib);
    return status;
}

int main(int argc, char **argv)
{
    struct options o;
    vt_tool_init("vt-offset");
    vt_output_path_use_stdio(); /* -o - */
    vt_atomic_file_cleanup_on_signals();
    int rc = parse_options(argc, argv, &o);
    if (rc >= 0)
        return rc;
    if (vt_output_path_is_stdio(o.out_path))
        vt_log_alias(VT_PATH_STDIO, VT_STDOUT_NAME);
    return run(&o);
}
