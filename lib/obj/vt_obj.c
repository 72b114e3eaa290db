/* Streaming OBJ reader: the statement parser with its vertex arrays, and path resolution. The line
 * source is vt_text.c; the MTL parser is vt_mtl.c. */
#include "vt_obj.h"

#include <assert.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "vt_checked.h"
#include "vt_error.h"
#include "vt_text.h"

void vt_obj_limits_default(struct vt_obj_limits *limits)
{
    limits->max_line_bytes = (size_t)1 << 20;
    limits->max_vertices = (uint32_t)1 << 28;
    limits->max_materials = (uint32_t)1 << 20;
}

/* ---- OBJ ---- */

struct vec_array {
    double *xyz; /* 3 per entry */
    uint32_t count, cap;
};

struct vt_obj {
    struct vt_obj_limits limits;
    struct vec_array v, vt, vn;
    unsigned char *vt_components; /* parallel to vt, cap vt.cap */
    struct vt_obj_corner *corners;
    size_t corner_cap;
    char *material, *group, *object;
    struct vt_obj_stats stats;
};

struct vt_obj *vt_obj_create(const struct vt_obj_limits *limits, struct vts_error *err)
{
    struct vt_obj *obj = calloc(1, sizeof *obj);
    if (!obj) {
        vt_error_set(err, VTS_ERR_NOMEM, "cannot create an OBJ reader: out of memory");
        return NULL;
    }
    if (limits)
        obj->limits = *limits;
    else
        vt_obj_limits_default(&obj->limits);
    if (obj->limits.max_vertices > UINT32_MAX - 1)
        obj->limits.max_vertices = UINT32_MAX - 1;
    return obj;
}

static void obj_clear(struct vt_obj *obj)
{
    free(obj->v.xyz);
    free(obj->vt.xyz);
    free(obj->vn.xyz);
    free(obj->vt_components);
    free(obj->corners);
    free(obj->material);
    free(obj->group);
    free(obj->object);
    struct vt_obj_limits limits = obj->limits;
    memset(obj, 0, sizeof *obj);
    obj->limits = limits;
}

void vt_obj_destroy(struct vt_obj *obj)
{
    if (!obj)
        return;
    obj_clear(obj);
    free(obj);
}

uint32_t vt_obj_position_count(const struct vt_obj *obj)
{
    return obj->v.count;
}

const double *vt_obj_positions(const struct vt_obj *obj)
{
    return obj->v.xyz;
}

uint32_t vt_obj_texcoord_count(const struct vt_obj *obj)
{
    return obj->vt.count;
}

const double *vt_obj_texcoords(const struct vt_obj *obj)
{
    return obj->vt.xyz;
}

uint32_t vt_obj_normal_count(const struct vt_obj *obj)
{
    return obj->vn.count;
}

const double *vt_obj_normals(const struct vt_obj *obj)
{
    return obj->vn.xyz;
}

unsigned vt_obj_texcoord_components(const struct vt_obj *obj, uint32_t index)
{
    return index < obj->vt.count ? obj->vt_components[index] : 0;
}

void vt_obj_stats(const struct vt_obj *obj, struct vt_obj_stats *stats)
{
    *stats = obj->stats;
}

/* Parser state of one read. */
struct obj_parse {
    struct vt_obj *obj;
    struct vt_text_src *src;
    const struct vt_obj_callbacks *cb;
};

static uint64_t cur_line(const struct obj_parse *p)
{
    return p->src->start_line;
}

/* Appends one entry to a, growing it (and vt_components when comps is not NULL). */
static int vec_push(struct obj_parse *p, struct vec_array *a, unsigned char **comps,
                    const double xyz[3], const char *what, struct vts_error *err)
{
    if (a->count >= p->obj->limits.max_vertices)
        return vt_error_set(err, VTS_ERR_LIMIT, "'%s':%llu: more than %lu %s (the limit)",
                            p->src->name, (unsigned long long)cur_line(p),
                            (unsigned long)p->obj->limits.max_vertices, what);
    if (a->count == a->cap) {
        uint64_t cap = a->cap ? (uint64_t)a->cap * 2 : 1024;
        if (cap > p->obj->limits.max_vertices)
            cap = p->obj->limits.max_vertices;
        size_t bytes;
        if (!vt_size_mul((size_t)cap, 3 * sizeof(double), &bytes))
            return vt_error_set(err, VTS_ERR_LIMIT, "'%s': too many %s", p->src->name, what);
        double *grown = realloc(a->xyz, bytes);
        if (!grown)
            return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory for %s", p->src->name,
                                what);
        a->xyz = grown;
        if (comps) {
            unsigned char *c = realloc(*comps, (size_t)cap);
            if (!c)
                return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory for %s", p->src->name,
                                    what);
            *comps = c;
        }
        a->cap = (uint32_t)cap;
    }
    memcpy(a->xyz + (size_t)a->count * 3, xyz, 3 * sizeof(double));
    a->count++;
    return 0;
}

/* v x y z [w] [r g b]: keeps x y z. vt u [v [w]]. vn x y z. */
static int obj_vertex(struct obj_parse *p, const char *kw, char *cur, struct vts_error *err)
{
    double vals[7] = {0};
    const char *bad = NULL;
    int min = 3, max = 7;
    const char *what = "vertices";
    struct vec_array *a = &p->obj->v;
    unsigned char **comps = NULL;
    if (kw[1] == 't') {
        min = 1, max = 3, what = "texcoords", a = &p->obj->vt, comps = &p->obj->vt_components;
    } else if (kw[1] == 'n') {
        max = 3, what = "normals", a = &p->obj->vn;
    }
    int n = vt_text_numbers(&cur, vals, max, &bad);
    if (n < 0)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: bad number '%s' in '%s'",
                            p->src->name, (unsigned long long)cur_line(p), bad, kw);
    if (n < min || vt_text_token(&cur))
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: '%s' needs %d to %d numbers",
                            p->src->name, (unsigned long long)cur_line(p), kw, min, max);
    int rc = vec_push(p, a, comps, vals, what, err);
    if (rc == 0 && comps)
        p->obj->vt_components[a->count - 1] = (unsigned char)n;
    return rc;
}

static const char *const index_names[3] = {"vertex", "texture", "normal"};

/* Resolves one OBJ index (1-based, or negative counting back from the latest) into 0-based. */
static int resolve_index(struct obj_parse *p, int kind, int64_t idx, uint32_t count,
                         const char *tok, uint32_t *out, struct vts_error *err)
{
    static const char *const plural[3] = {"vertices", "texcoords", "normals"};
    if (idx == 0)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "'%s':%llu: %s index 0 in '%s' (OBJ indices start at 1)", p->src->name,
                            (unsigned long long)cur_line(p), index_names[kind], tok);
    int64_t abs_idx = idx > 0 ? idx - 1 : (int64_t)count + idx;
    if (abs_idx < 0 || abs_idx >= (int64_t)count)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "'%s':%llu: %s index %lld in '%s' out of range (%lu %s defined)",
                            p->src->name, (unsigned long long)cur_line(p), index_names[kind],
                            (long long)idx, tok, (unsigned long)count, plural[kind]);
    *out = (uint32_t)abs_idx;
    return 0;
}

/* One corner token: v, v/vt, v//vn or v/vt/vn. */
static int obj_corner(struct obj_parse *p, const char *tok, struct vt_obj_corner *c,
                      struct vts_error *err)
{
    const struct vec_array *arrays[3] = {&p->obj->v, &p->obj->vt, &p->obj->vn};
    uint32_t *outs[3] = {&c->v, &c->vt, &c->vn};
    c->vt = c->vn = VT_OBJ_NONE;
    const char *s = tok;
    for (int kind = 0; kind < 3; kind++) {
        const char *e = strchr(s, '/');
        if (!e)
            e = s + strlen(s);
        if (e > s || kind == 0) {
            int64_t idx;
            if (!vt_text_index(s, e, &idx))
                return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: bad %s index '%s'",
                                    p->src->name, (unsigned long long)cur_line(p),
                                    index_names[kind], tok);
            int rc = resolve_index(p, kind, idx, arrays[kind]->count, tok, outs[kind], err);
            if (rc < 0)
                return rc;
        }
        if (*e == '\0')
            return 0;
        s = e + 1;
    }
    return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: bad face corner '%s'", p->src->name,
                        (unsigned long long)cur_line(p), tok);
}

/* Turns a callback's non-zero return into the read's status, with a message if it left none. */
static int callback_status(struct obj_parse *p, int rc, const char *what, struct vts_error *cb_err,
                           struct vts_error *err)
{
    if (rc == 0)
        return 0;
    int status = rc < 0 ? rc : VTS_ERR_CANCELLED;
    if (cb_err->status != VTS_OK) {
        if (err)
            *err = *cb_err;
        return status;
    }
    return vt_error_set(err, status, "'%s':%llu: stopped by the %s callback", p->src->name,
                        (unsigned long long)cur_line(p), what);
}

static int obj_face(struct obj_parse *p, char *cur, struct vts_error *err)
{
    struct vt_obj *obj = p->obj;
    uint32_t n = 0;
    char *tok;
    while ((tok = vt_text_token(&cur)) != NULL) {
        if (n == obj->corner_cap) {
            /* a corner takes >= 2 bytes of the line, so the line limit bounds this */
            size_t cap = obj->corner_cap ? obj->corner_cap * 2 : 16;
            struct vt_obj_corner *c = realloc(obj->corners, cap * sizeof *c);
            if (!c)
                return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory for a face",
                                    p->src->name);
            obj->corners = c;
            obj->corner_cap = cap;
        }
        int rc = obj_corner(p, tok, &obj->corners[n], err);
        if (rc < 0)
            return rc;
        n++;
    }
    if (n < 3)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: face with %lu corners (needs 3)",
                            p->src->name, (unsigned long long)cur_line(p), (unsigned long)n);
    obj->stats.faces++;
    if (!p->cb || !p->cb->face)
        return 0;
    struct vt_obj_face f = {obj->corners,
                            n,
                            obj->material ? obj->material : "",
                            obj->group ? obj->group : "",
                            obj->object ? obj->object : "",
                            cur_line(p)};
    struct vts_error cb_err = {0};
    return callback_status(p, p->cb->face(p->cb->user, obj, &f, &cb_err), "face", &cb_err, err);
}

static int set_name(struct obj_parse *p, char **slot, const char *value, struct vts_error *err)
{
    char *copy = strdup(value);
    if (!copy)
        return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory", p->src->name);
    free(*slot);
    *slot = copy;
    return 0;
}

/* Most exporters separate several libraries with spaces; a name with spaces is recognised when the
 * line ends in ".mtl" but some space-separated piece does not. */
static bool names_one_file(const char *rest)
{
    size_t n = strlen(rest);
    if (n < 4 || strcmp(rest + n - 4, ".mtl") != 0)
        return false;
    const char *s = rest;
    while (*s) {
        size_t len = strcspn(s, " \t");
        if (len && (len < 4 || strncmp(s + len - 4, ".mtl", 4) != 0))
            return true;
        s += len;
        s += strspn(s, " \t");
    }
    return false;
}

static int obj_mtllib_one(struct obj_parse *p, const char *file, struct vts_error *err)
{
    if (!p->cb || !p->cb->mtllib)
        return 0;
    char *path = vt_obj_resolve_path(p->src->name, file);
    if (!path)
        return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory", p->src->name);
    struct vts_error cb_err = {0};
    int rc = p->cb->mtllib(p->cb->user, p->obj, path, cur_line(p), &cb_err);
    free(path);
    return callback_status(p, rc, "mtllib", &cb_err, err);
}

static int obj_mtllib(struct obj_parse *p, char *cur, struct vts_error *err)
{
    char *rest = vt_text_rest(cur);
    if (!*rest)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: mtllib without a file name",
                            p->src->name, (unsigned long long)cur_line(p));
    if (names_one_file(rest))
        return obj_mtllib_one(p, rest, err);
    char *tok;
    while ((tok = vt_text_token(&rest)) != NULL) {
        int rc = obj_mtllib_one(p, tok, err);
        if (rc < 0)
            return rc;
    }
    return 0;
}

static int obj_usemtl(struct obj_parse *p, char *cur, struct vts_error *err)
{
    int rc = set_name(p, &p->obj->material, vt_text_rest(cur), err);
    if (rc < 0 || !p->cb || !p->cb->usemtl)
        return rc;
    struct vts_error cb_err = {0};
    rc = p->cb->usemtl(p->cb->user, p->obj, p->obj->material, cur_line(p), &cb_err);
    return callback_status(p, rc, "usemtl", &cb_err, err);
}

static int obj_statement(struct obj_parse *p, struct vts_error *err)
{
    char *cur = p->src->line;
    char *kw = vt_text_token(&cur);
    if (!kw)
        return 0; /* blank or comment */
    if (strcmp(kw, "v") == 0 || strcmp(kw, "vt") == 0 || strcmp(kw, "vn") == 0)
        return obj_vertex(p, kw, cur, err);
    if (strcmp(kw, "f") == 0)
        return obj_face(p, cur, err);
    if (strcmp(kw, "usemtl") == 0)
        return obj_usemtl(p, cur, err);
    if (strcmp(kw, "mtllib") == 0)
        return obj_mtllib(p, cur, err);
    if (strcmp(kw, "g") == 0)
        return set_name(p, &p->obj->group, vt_text_rest(cur), err);
    if (strcmp(kw, "o") == 0)
        return set_name(p, &p->obj->object, vt_text_rest(cur), err);
    if (strcmp(kw, "l") == 0 || strcmp(kw, "p") == 0 || strcmp(kw, "s") == 0 ||
        strcmp(kw, "vp") == 0)
        p->obj->stats.ignored_statements++;
    else
        p->obj->stats.unknown_statements++;
    return 0;
}

static int obj_parse(struct vt_obj *obj, struct vt_text_src *src, const struct vt_obj_callbacks *cb,
                     struct vts_error *err)
{
    struct obj_parse p = {obj, src, cb};
    int rc;
    while ((rc = vt_text_next_line(src, err)) == 1) {
        rc = obj_statement(&p, err);
        if (rc < 0)
            break;
    }
    obj->stats.lines = src->physical;
    return rc < 0 ? rc : 0;
}

int vt_obj_read(struct vt_obj *obj, const char *path, const struct vt_obj_callbacks *cb,
                struct vts_error *err)
{
    struct vt_text_src src;
    obj_clear(obj);
    int rc = vt_text_open(&src, path, obj->limits.max_line_bytes, err);
    if (rc < 0)
        return rc;
    rc = obj_parse(obj, &src, cb, err);
    vt_text_close(&src);
    return rc;
}

int vt_obj_parse_memory(struct vt_obj *obj, const void *data, size_t size, const char *name,
                        const struct vt_obj_callbacks *cb, struct vts_error *err)
{
    struct vt_text_src src;
    obj_clear(obj);
    vt_text_memory(&src, data, size, name, obj->limits.max_line_bytes);
    int rc = obj_parse(obj, &src, cb, err);
    vt_text_close(&src);
    return rc;
}

/* ---- paths ---- */

static bool path_is_absolute(const char *p)
{
    return p[0] == '/' || p[0] == '\\' ||
           (((p[0] | 0x20) >= 'a' && (p[0] | 0x20) <= 'z') && p[1] == ':');
}

char *vt_obj_resolve_path(const char *base_file, const char *file)
{
    size_t dir_len = 0;
    if (!path_is_absolute(file)) {
        const char *slash = strrchr(base_file, '/');
        dir_len = slash ? (size_t)(slash - base_file) + 1 : 0;
    }
    size_t file_len = strlen(file);
    char *out = malloc(dir_len + file_len + 1);
    if (!out)
        return NULL;
    memcpy(out, base_file, dir_len);
    for (size_t i = 0; i <= file_len; i++)
        out[dir_len + i] = file[i] == '\\' ? '/' : file[i];
    return out;
}
