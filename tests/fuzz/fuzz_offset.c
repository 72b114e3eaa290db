/* libFuzzer target for the vt-offset rewriter (lib/offset, vt_offset_rewrite_memory()): the input
 * is OBJ text, rewritten onto a small fixed layout built in memory (below) into a memory sink.
 * Invariants are checked, not only crashes (a violation aborts):
 *   - a failure has a documented status (BAD_INPUT, LIMIT, NOMEM), err.status equal to it, a
 *     one-line message naming 's.obj', and nothing written (all input errors come before the first
 *     byte). When lib/obj's reader accepts the input, the failure must be one the reader does not
 *     check (a material, the UV range, the cut's limits);
 *   - on success, when lib/obj's reader accepts the input (the rewriter does not parse v and vn,
 *     so it copies what the reader would refuse), the output must parse with vt_obj_parse_memory()
 *     (every index in range) with exactly one mtllib (out.mtl), as many usemtl as the input, and
 *     the counts of the stats: f = faces - faces_cut + pieces, faces_written = pieces +
 *     faces_split, v = input v + positions_added, vt = input vt + vt_duplicated + vt_added, vn =
 *     input vn + vn_added;
 *   - every texture coordinate of an output face lies in [0,1] and inside its material's entry
 *     (its crop, in atlas texels, within the rounding of the written decimals); on a constant
 *     entry it is the centre of the cell. The face's material is the input's usemtl of the same
 *     rank (the rewriter renames every usemtl to vt_atlas, one for one);
 *   - when no face was cut or split, output face i is input face i: the same v and vn indices and
 *     texcoords where the input has them, each mapping back to the input's (u, v) plus a whole
 *     repeat, one move per face.
 * Inputs whose faces' texture coordinates span more than VT_FUZZ_MAX_CELLS unit cells in all are
 * skipped: a face of a wrap entry is cut into a piece per cell it covers (lib/chart allows 2^20
 * cells per face), so that a few bytes can ask for millions of pieces and hundreds of MB, by
 * design. Faces over lib/chart's limit are not counted: it refuses them before any work, and that
 * path is fuzzed. */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vt_layout.h"
#include "vt_obj.h"
#include "vt_offset.h"
#include "vt_text.h"
#include "vts.h"

int fuzz_offset_one(const uint8_t *data, size_t size);
#ifndef VT_FUZZ_NO_ENTRY
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
#endif

#define NAME              "s.obj"
#define VT_FUZZ_MAX_CELLS 4096.0
#define VT_FUZZ_MAX_VERTS (1u << 12)

/* ---- the layout: a 256x128 atlas (not square, so that u/v or width/height mix-ups show) ---- */

struct fspec {
    const char *name, *alias;
    uint32_t x, y, w, h, ru, rv;
    int32_t ou, ov;
    uint32_t crop_x, crop_y, crop_w, crop_h; /* 0: the whole block */
    bool wrap, constant;
};

static const struct fspec specs[] = {
    /* plain, with an alias (charts are grouped by name, the entry is shared) */
    {"plain", "plain2", 0, 0, 64, 64, 1, 1, 0, 0, 0, 0, 0, 0, false, false},
    /* 2x2 copies from u -1 (v 0), cropped: u -0.75..0.75, v 0.125..1.875 */
    {"rep", NULL, 64, 0, 32, 32, 2, 2, -1, 0, 8, 4, 48, 56, false, false},
    {"const_grey", NULL, 128, 0, 8, 8, 1, 1, 0, 0, 0, 0, 0, 0, false, true},
    /* one copy of a repeating texture: faces crossing integer lines are cut (lib/chart) */
    {"wrap", NULL, 160, 32, 64, 64, 1, 1, 0, 0, 0, 0, 0, 0, true, false},
};
#define ENTRY_COUNT (sizeof specs / sizeof specs[0])

static struct vt_layout layout;
static bool layout_ready;

static char *dup_or_die(const char *s)
{
    char *p = strdup(s);
    if (!p)
        abort();
    return p;
}

static void build_layout(void)
{
    struct vts_error err = {0};
    if (vt_layout_alloc(&layout, 1, ENTRY_COUNT, &err) < 0)
        abort();
    layout.width = 256;
    layout.height = 128;
    layout.tile_content = 64;
    layout.border = 4;
    layout.layers[0].name = dup_or_die("diffuse");
    layout.layers[0].map = dup_or_die("map_Kd");
    layout.layers[0].colour = VTS_COLOUR_SRGB;
    for (uint32_t i = 0; i < ENTRY_COUNT; i++) {
        const struct fspec *s = &specs[i];
        struct vt_layout_entry *e = &layout.entries[i];
        e->name = dup_or_die(s->name);
        if (s->alias) {
            e->aliases = malloc(sizeof *e->aliases);
            if (!e->aliases)
                abort();
            e->aliases[0] = dup_or_die(s->alias);
            e->alias_count = 1;
        }
        e->x = s->x, e->y = s->y, e->width = s->w, e->height = s->h;
        e->repeat_u = s->ru, e->repeat_v = s->rv, e->origin_u = s->ou, e->origin_v = s->ov;
        e->crop_x = s->crop_x, e->crop_y = s->crop_y;
        e->crop_width = s->crop_w, e->crop_height = s->crop_h;
        e->cell_width = s->crop_w ? s->crop_w : s->w * s->ru;
        e->cell_height = s->crop_h ? s->crop_h : s->h * s->rv;
        e->wrap = s->wrap;
        e->scale = 1;
        if (s->constant) {
            e->textures[0].fill[0] = e->textures[0].fill[1] = e->textures[0].fill[2] = 0.5;
            e->textures[0].fill[3] = 1;
        } else {
            e->textures[0].path = dup_or_die("t.png");
            e->textures[0].resolved = dup_or_die("t.png");
            e->textures[0].width = s->w, e->textures[0].height = s->h;
        }
    }
    if (vt_layout_index(&layout, &err) < 0)
        abort(); /* the fixture itself is wrong */
    layout_ready = true;
}

/* ---- the screen: how many unit cells the faces' texcoords cover in all ---- */

static double screen_uv[2 * VT_FUZZ_MAX_VERTS];

/* The cells of the faces (an upper bound of the pieces a cut makes); read with vt_obj's line
 * rules. Stops at a line the reader refuses (the rewriter refuses it too). */
static double screen_cells(const uint8_t *data, size_t size, size_t max_line)
{
    struct vt_text_src src;
    struct vts_error err = {0};
    vt_text_memory(&src, data, size, NAME, max_line);
    uint32_t nvt = 0;
    double cells = 0;
    while (cells <= VT_FUZZ_MAX_CELLS && vt_text_next_line(&src, &err) == 1) {
        char *cur = src.line, *kw = vt_text_token(&cur), *tok;
        if (!kw)
            continue;
        if (strcmp(kw, "vt") == 0) {
            double x[2] = {0, 0};
            for (int k = 0; k < 2 && (tok = vt_text_token(&cur)) != NULL; k++)
                if (!vt_text_double(tok, &x[k]))
                    x[k] = 0;
            if (nvt < VT_FUZZ_MAX_VERTS) {
                screen_uv[2 * nvt] = x[0];
                screen_uv[2 * nvt + 1] = x[1];
            }
            nvt++;
        } else if (strcmp(kw, "f") == 0) {
            double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
            while ((tok = vt_text_token(&cur)) != NULL) {
                char *s = strchr(tok, '/'), *e;
                int64_t idx;
                if (!s)
                    continue;
                e = strchr(++s, '/');
                if (!vt_text_index(s, e ? e : s + strlen(s), &idx) || idx == 0)
                    continue;
                int64_t i = idx > 0 ? idx - 1 : (int64_t)nvt + idx;
                if (i < 0 || i >= (int64_t)nvt || i >= (int64_t)VT_FUZZ_MAX_VERTS)
                    continue;
                for (int a = 0; a < 2; a++) {
                    lo[a] = fmin(lo[a], screen_uv[2 * i + a]);
                    hi[a] = fmax(hi[a], screen_uv[2 * i + a]);
                }
            }
            if (lo[0] > hi[0])
                continue;
            /* cells as lib/chart counts them (vt_cut.c, cell_range), one more per axis for the
             * rounding of a move; a face lib/chart refuses as too large costs nothing */
            double n[2];
            for (int a = 0; a < 2; a++)
                n[a] = (hi[a] > lo[a] ? ceil(hi[a]) - floor(lo[a]) : 1) + 1;
            const double max = 1 << 20; /* VT_CUT_MAX_CELLS */
            if (!(n[0] - 2 > max || n[1] - 2 > max || (n[0] - 2) * (n[1] - 2) > max))
                cells += n[0] * n[1];
        }
    }
    vt_text_close(&src);
    return cells;
}

/* ---- what vt_obj reads ---- */

struct fface {
    uint32_t first, count; /* corners */
    uint32_t mat;          /* usemtl rank (0: none yet, k: the k-th usemtl) */
};

struct fmesh {
    struct vt_obj_corner *corners;
    struct fface *faces;
    uint32_t ncorner, nface, cap_corner, cap_face;
    char **usemtl;
    uint32_t nusemtl, cap_usemtl;
    uint32_t nmtllib;
    bool mtllib_ok;
    uint32_t nv, nvt, nvn;
    double *uv; /* 3 per vt */
};

static void *grow_or_die(void *p, uint32_t *cap, uint32_t need, size_t elem)
{
    if (need <= *cap)
        return p;
    uint32_t n = *cap ? *cap : 64;
    while (n < need)
        n *= 2;
    void *q = realloc(p, (size_t)n * elem);
    if (!q)
        abort();
    *cap = n;
    return q;
}

static int on_face(void *user, const struct vt_obj *obj, const struct vt_obj_face *f,
                   struct vts_error *err)
{
    (void)obj, (void)err;
    struct fmesh *m = user;
    m->faces = grow_or_die(m->faces, &m->cap_face, m->nface + 1, sizeof *m->faces);
    m->corners =
        grow_or_die(m->corners, &m->cap_corner, m->ncorner + f->corner_count, sizeof *m->corners);
    m->faces[m->nface++] = (struct fface){m->ncorner, f->corner_count, m->nusemtl};
    memcpy(m->corners + m->ncorner, f->corners, f->corner_count * sizeof *f->corners);
    m->ncorner += f->corner_count;
    return 0;
}

static int on_usemtl(void *user, const struct vt_obj *obj, const char *name, uint64_t line,
                     struct vts_error *err)
{
    (void)obj, (void)line, (void)err;
    struct fmesh *m = user;
    m->usemtl = grow_or_die(m->usemtl, &m->cap_usemtl, m->nusemtl + 1, sizeof *m->usemtl);
    m->usemtl[m->nusemtl++] = dup_or_die(name);
    return 0;
}

static int on_mtllib(void *user, const struct vt_obj *obj, const char *path, uint64_t line,
                     struct vts_error *err)
{
    (void)obj, (void)line, (void)err;
    struct fmesh *m = user;
    m->nmtllib++;
    m->mtllib_ok = strcmp(path, "out.mtl") == 0;
    return 0;
}

static void fmesh_release(struct fmesh *m)
{
    for (uint32_t i = 0; i < m->nusemtl; i++)
        free(m->usemtl[i]);
    free(m->usemtl);
    free(m->corners);
    free(m->faces);
    free(m->uv);
    memset(m, 0, sizeof *m);
}

/* Reads text with vt_obj into m (m zeroed first); returns its status. */
static int read_mesh(const void *text, size_t size, const char *name,
                     const struct vt_obj_limits *limits, struct fmesh *m)
{
    memset(m, 0, sizeof *m);
    struct vts_error err = {0};
    struct vt_obj *obj = vt_obj_create(limits, &err);
    if (!obj)
        abort();
    struct vt_obj_callbacks cb = {on_mtllib, on_usemtl, on_face, m};
    int rc = vt_obj_parse_memory(obj, text, size, name, &cb, &err);
    m->nv = vt_obj_position_count(obj);
    m->nvt = vt_obj_texcoord_count(obj);
    m->nvn = vt_obj_normal_count(obj);
    m->uv = malloc(((size_t)m->nvt + 1) * 3 * sizeof *m->uv);
    if (!m->uv)
        abort();
    if (m->nvt)
        memcpy(m->uv, vt_obj_texcoords(obj), (size_t)m->nvt * 3 * sizeof *m->uv);
    vt_obj_destroy(obj);
    return rc;
}

/* ---- the checks ---- */

struct membuf {
    char *data;
    size_t len, cap;
};

static int sink_write(void *user, const void *data, size_t size, struct vts_error *err)
{
    (void)err;
    struct membuf *m = user;
    if (m->len + size + 1 > m->cap) {
        size_t cap = (m->len + size + 1) * 2;
        char *p = realloc(m->data, cap);
        if (!p)
            abort();
        m->data = p;
        m->cap = cap;
    }
    memcpy(m->data + m->len, data, size);
    m->len += size;
    m->data[m->len] = '\0';
    return 0;
}

/* The entry of a face of usemtl rank mat in the input's names, or NULL. */
static const struct vt_layout_entry *entry_of(const struct fmesh *in, uint32_t mat)
{
    return mat == 0 || mat > in->nusemtl ? NULL : vt_layout_find(&layout, in->usemtl[mat - 1]);
}

static bool is_constant(const struct vt_layout_entry *e)
{
    return e->textures[0].path == NULL;
}

/* Distance of x from the nearest integer. */
static double off_integer(double x)
{
    return fabs(x - round(x));
}

static double ulp(double x)
{
    x = fabs(x);
    return nextafter(x, INFINITY) - x;
}

/* Every output face's texcoords: in [0,1], inside the entry (tol: the written decimals). */
static void check_ranges(const struct fmesh *in, const struct fmesh *out, double tol)
{
    for (uint32_t f = 0; f < out->nface; f++) {
        const struct fface *ff = &out->faces[f];
        const struct vt_layout_entry *e = entry_of(in, ff->mat);
        for (uint32_t k = 0; k < ff->count; k++) {
            uint32_t t = out->corners[ff->first + k].vt;
            if (t == VT_OBJ_NONE)
                continue;
            if (!e)
                abort(); /* texcoords without a material of the layout: must have been refused */
            double au = out->uv[3 * (size_t)t], av = out->uv[3 * (size_t)t + 1];
            if (!(au >= 0 && au <= 1 && av >= 0 && av <= 1))
                abort();
            double x = au * layout.width, y = (1 - av) * layout.height; /* atlas texels, y down */
            double tx = tol * layout.width, ty = tol * layout.height;
            if (is_constant(e)) {
                if (fabs(x - (e->x + e->width / 2.0)) > tx ||
                    fabs(y - (e->y + e->height / 2.0)) > ty)
                    abort();
            } else if (x < e->x - tx || x > e->x + e->crop_width + tx || y < e->y - ty ||
                       y > e->y + e->crop_height + ty) {
                abort();
            }
        }
    }
}

/* Nothing cut or split: output face i is input face i, its texcoords the input's moved by a whole
 * repeat (one move per face). */
static void check_faces_kept(const struct fmesh *in, const struct fmesh *out, double tol)
{
    if (in->nface != out->nface)
        abort();
    for (uint32_t f = 0; f < in->nface; f++) {
        const struct fface *fi = &in->faces[f], *fo = &out->faces[f];
        if (fi->count != fo->count || fi->mat != fo->mat)
            abort();
        const struct vt_layout_entry *e = entry_of(in, fi->mat);
        double move[2] = {NAN, NAN};
        for (uint32_t k = 0; k < fi->count; k++) {
            const struct vt_obj_corner *ci = &in->corners[fi->first + k];
            const struct vt_obj_corner *co = &out->corners[fo->first + k];
            if (ci->v != co->v || ci->vn != co->vn ||
                (ci->vt == VT_OBJ_NONE) != (co->vt == VT_OBJ_NONE))
                abort();
            if (ci->vt == VT_OBJ_NONE || !e || is_constant(e))
                continue;
            /* the output's atlas coordinate back to the material's (u, v) */
            double au = out->uv[3 * (size_t)co->vt], av = out->uv[3 * (size_t)co->vt + 1];
            double mu = (au * layout.width - e->x + e->crop_x) / e->width + e->origin_u;
            double mv = e->origin_v + e->repeat_v -
                        ((1 - av) * layout.height - e->y + e->crop_y) / e->height;
            double u = in->uv[3 * (size_t)ci->vt], v = in->uv[3 * (size_t)ci->vt + 1];
            double d[2] = {mu - u, mv - v};
            double t[2] = {tol * layout.width / e->width + 4 * ulp(u) + 4 * ulp(mu),
                           tol * layout.height / e->height + 4 * ulp(v) + 4 * ulp(mv)};
            for (int a = 0; a < 2; a++) {
                if (off_integer(d[a]) > t[a])
                    abort();
                if (isnan(move[a]))
                    move[a] = round(d[a]);
                else if (round(d[a]) != move[a])
                    abort();
            }
        }
    }
}

/* Failures the rewriter may give on an input vt_obj accepts: what vt_obj does not check. A message
 * cut at the size of struct vts_error (a long material name) cannot be told. */
static bool beyond_the_reader(const char *message)
{
    if (strlen(message) + 1 == sizeof((struct vts_error *)0)->message)
        return true;
    static const char *const allowed[] = {
        "face with texture coordinates before any usemtl",
        "is not in 'atlas.json'",
        "is outside the UV range",
        "cannot cut face",
        "too many",
        "cannot label charts",
    };
    for (size_t i = 0; i < sizeof allowed / sizeof allowed[0]; i++)
        if (strstr(message, allowed[i]))
            return true;
    return false;
}

int fuzz_offset_one(const uint8_t *data, size_t size)
{
    if (!layout_ready)
        build_layout();
    struct vt_offset_options opt;
    vt_offset_options_default(&opt);
    opt.mtllib = "out.mtl";
    opt.limits.max_line_bytes = 4096; /* small limits keep the fuzzer fast and reach the limits */
    opt.limits.max_vertices = VT_FUZZ_MAX_VERTS;
    opt.limits.max_materials = 64;
    if (screen_cells(data, size, opt.limits.max_line_bytes) > VT_FUZZ_MAX_CELLS)
        return 0;

    struct membuf out = {0};
    struct vt_offset_sink sink = {sink_write, &out};
    struct vt_offset_stats st;
    memset(&st, 0, sizeof st);
    struct vts_error err = {0};
    int rc = vt_offset_rewrite_memory(data, size, NAME, &layout, &opt, &sink, &st, &err);

    struct fmesh in;
    int in_rc = read_mesh(data, size, NAME, &opt.limits, &in);
    if (rc != 0) {
        if ((rc != VTS_ERR_BAD_INPUT && rc != VTS_ERR_LIMIT && rc != VTS_ERR_NOMEM) ||
            err.status != rc || !strstr(err.message, "'" NAME "'") || strchr(err.message, '\n') ||
            out.len != 0)
            abort();
        if (in_rc == 0 && !beyond_the_reader(err.message))
            abort();
    } else if (in_rc == 0) {
        struct fmesh o;
        /* the reader's default limits: the output may hold more vertices and longer lines */
        if (read_mesh(out.data, out.len, "out.obj", NULL, &o) != 0)
            abort();
        if (st.faces != in.nface || st.vt_lines != in.nvt ||
            st.vt_rewritten + st.vt_unused != st.vt_lines ||
            o.nface != st.faces - st.faces_cut + st.pieces ||
            st.faces_written != st.pieces + st.faces_split || o.nv != in.nv + st.positions_added ||
            o.nvt != in.nvt + st.vt_duplicated + st.vt_added || o.nvn != in.nvn + st.vn_added ||
            o.nmtllib != 1 || !o.mtllib_ok || o.nusemtl != in.nusemtl)
            abort();
        for (uint32_t i = 0; i < o.nusemtl; i++)
            if (strcmp(o.usemtl[i], VT_OFFSET_MATERIAL) != 0)
                abort();
        /* half a unit of the last written decimal, and the double rounding of the mapping */
        double tol = 0.5 * pow(10.0, -(double)st.digits) + 1e-12;
        check_ranges(&in, &o, tol);
        if (st.faces_cut + st.faces_split == 0)
            check_faces_kept(&in, &o, tol);
        fmesh_release(&o);
    }
    fmesh_release(&in);
    free(out.data);
    return 0;
}

#ifndef VT_FUZZ_NO_ENTRY
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz_offset_one(data, size);
}
#endif
