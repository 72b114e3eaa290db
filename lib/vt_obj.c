/* Streaming OBJ/MTL reader: a line source (file or memory) that joins '\' continuations and strips
 * CRLF, the OBJ statement parser with its vertex arrays, and the MTL parser. */
#include "vt_obj.h"

#include <assert.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "vt_checked.h"

#define READ_CHUNK (64 * 1024)

void vt_obj_limits_default(struct vt_obj_limits *limits)
{
    limits->max_line_bytes = (size_t)1 << 20;
    limits->max_vertices = (uint32_t)1 << 28;
    limits->max_materials = (uint32_t)1 << 20;
}

/* ---- line source ---- */

struct line_src {
    const char *name;
    FILE *file;                /* NULL when reading memory */
    const unsigned char *data; /* the memory, or buf */
    size_t len, pos;
    unsigned char *buf;
    char *line; /* the current logical line, NUL-terminated */
    size_t line_len, line_cap, max_line;
    uint64_t physical;   /* physical lines consumed */
    uint64_t start_line; /* where the current logical line starts */
};

/* Makes input available at s->pos: 1, 0 at the end, or -2 on a read error. */
static int src_fill(struct line_src *s)
{
    if (s->pos < s->len)
        return 1;
    if (!s->file)
        return 0;
    s->len = fread(s->buf, 1, READ_CHUNK, s->file);
    s->pos = 0;
    if (s->len == 0)
        return ferror(s->file) ? -2 : 0;
    return 1;
}

/* Appends n bytes to the line, keeping room for a terminator; the limit counts the raw bytes of the
 * physical lines (continuation '\' and '\r' included). */
static int line_append(struct line_src *s, const unsigned char *bytes, size_t n,
                       struct vt_error *err)
{
    if (n > s->max_line - s->line_len)
        return vt_error_set(err, VT_ERR_LIMIT, "'%s':%llu: line longer than the limit of %zu bytes",
                            s->name, (unsigned long long)s->start_line, s->max_line);
    if (s->line_len + n + 1 > s->line_cap) {
        size_t cap = s->line_cap ? s->line_cap : 256;
        while (cap < s->line_len + n + 1)
            cap *= 2;
        if (cap > s->max_line + 1)
            cap = s->max_line + 1;
        char *p = realloc(s->line, cap);
        if (!p)
            return vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory for a line", s->name);
        s->line = p;
        s->line_cap = cap;
    }
    memcpy(s->line + s->line_len, bytes, n);
    s->line_len += n;
    return 0;
}

/* Ends a physical line: drops a '\r' before the '\n'; returns true when a '\' continues it. */
static bool line_end_physical(struct line_src *s)
{
    s->physical++;
    if (s->line_len && s->line[s->line_len - 1] == '\r')
        s->line_len--;
    if (s->line_len && s->line[s->line_len - 1] == '\\') {
        s->line[s->line_len - 1] = ' ';
        return true;
    }
    return false;
}

/* Reads one logical line into s->line (NUL-terminated). Returns 1, 0 at the end of input, or a
 * negative status. */
static int line_next(struct line_src *s, struct vt_error *err)
{
    s->line_len = 0;
    s->start_line = s->physical + 1;
    bool any = false;
    for (;;) {
        int rc = src_fill(s);
        if (rc == -2)
            return vt_error_set(err, VT_ERR_IO, "cannot read '%s': %s", s->name, strerror(errno));
        if (rc == 0) {
            if (!any)
                return 0;
            line_end_physical(s);
            break;
        }
        any = true;
        const unsigned char *start = s->data + s->pos;
        const unsigned char *nl = memchr(start, '\n', s->len - s->pos);
        size_t n = nl ? (size_t)(nl - start) : s->len - s->pos;
        if (memchr(start, '\0', n))
            return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: NUL byte in a text line",
                                s->name, (unsigned long long)s->physical + 1);
        rc = line_append(s, start, n, err);
        if (rc < 0)
            return rc;
        s->pos += n + (nl != NULL);
        if (nl && !line_end_physical(s))
            break;
    }
    if (!s->line) { /* an empty last line: no buffer yet */
        s->line = malloc(1);
        if (!s->line)
            return vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory for a line", s->name);
        s->line_cap = 1;
    }
    s->line[s->line_len] = '\0';
    return 1;
}

static int src_open(struct line_src *s, const char *path, const struct vt_obj_limits *limits,
                    struct vt_error *err)
{
    memset(s, 0, sizeof *s);
    s->name = path;
    s->max_line = limits->max_line_bytes < SIZE_MAX / 4 ? limits->max_line_bytes : SIZE_MAX / 4;
    s->buf = malloc(READ_CHUNK);
    if (!s->buf)
        return vt_error_set(err, VT_ERR_NOMEM, "cannot read '%s': out of memory", path);
    s->data = s->buf;
    s->file = fopen(path, "rb");
    if (!s->file) {
        int rc = vt_error_set(err, VT_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
        free(s->buf);
        s->buf = NULL;
        return rc;
    }
    return 0;
}

static void src_memory(struct line_src *s, const void *data, size_t size, const char *name,
                       const struct vt_obj_limits *limits)
{
    memset(s, 0, sizeof *s);
    s->name = name;
    s->max_line = limits->max_line_bytes < SIZE_MAX / 4 ? limits->max_line_bytes : SIZE_MAX / 4;
    s->data = data;
    s->len = size;
}

static void src_close(struct line_src *s)
{
    if (s->file)
        fclose(s->file);
    free(s->buf);
    free(s->line);
}

/* ---- tokens and numbers ---- */

static bool is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* Splits the next whitespace-separated token off *cur (NUL-terminating it); NULL at the end or at a
 * token starting with '#' (an inline comment). */
static char *token_next(char **cur)
{
    char *p = *cur;
    while (is_space(*p))
        p++;
    if (*p == '\0' || *p == '#') {
        *cur = p;
        return NULL;
    }
    char *start = p;
    while (*p && !is_space(*p))
        p++;
    if (*p)
        *p++ = '\0';
    *cur = p;
    return start;
}

/* The rest of the line with surrounding whitespace trimmed (in place). */
static char *rest_of_line(char *cur)
{
    while (is_space(*cur))
        cur++;
    size_t n = strlen(cur);
    while (n && is_space(cur[n - 1]))
        cur[--n] = '\0';
    return cur;
}

/* A finite decimal number (digits, sign, point, exponent; no nan/inf/hex), the whole token. */
static bool parse_double(const char *tok, double *out)
{
    if (!*tok || strspn(tok, "0123456789+-.eE") != strlen(tok))
        return false;
    char *end;
    double v = strtod(tok, &end);
    if (end == tok || *end || !isfinite(v))
        return false;
    *out = v;
    return true;
}

/* Parses up to max numbers from *cur into out; returns how many, or -1 on a token that is not one.
 */
static int parse_numbers(char **cur, double *out, int max, const char **bad)
{
    int n = 0;
    char *tok;
    while (n < max && (tok = token_next(cur)) != NULL) {
        if (!parse_double(tok, &out[n])) {
            *bad = tok;
            return -1;
        }
        n++;
    }
    return n;
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

struct vt_obj *vt_obj_create(const struct vt_obj_limits *limits, struct vt_error *err)
{
    struct vt_obj *obj = calloc(1, sizeof *obj);
    if (!obj) {
        vt_error_set(err, VT_ERR_NOMEM, "cannot create an OBJ reader: out of memory");
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
    struct line_src *src;
    const struct vt_obj_callbacks *cb;
};

static uint64_t cur_line(const struct obj_parse *p)
{
    return p->src->start_line;
}

/* Appends one entry to a, growing it (and vt_components when comps is not NULL). */
static int vec_push(struct obj_parse *p, struct vec_array *a, unsigned char **comps,
                    const double xyz[3], const char *what, struct vt_error *err)
{
    if (a->count >= p->obj->limits.max_vertices)
        return vt_error_set(err, VT_ERR_LIMIT, "'%s':%llu: more than %lu %s (the limit)",
                            p->src->name, (unsigned long long)cur_line(p),
                            (unsigned long)p->obj->limits.max_vertices, what);
    if (a->count == a->cap) {
        uint64_t cap = a->cap ? (uint64_t)a->cap * 2 : 1024;
        if (cap > p->obj->limits.max_vertices)
            cap = p->obj->limits.max_vertices;
        size_t bytes;
        if (!vt_size_mul((size_t)cap, 3 * sizeof(double), &bytes))
            return vt_error_set(err, VT_ERR_LIMIT, "'%s': too many %s", p->src->name, what);
        double *grown = realloc(a->xyz, bytes);
        if (!grown)
            return vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory for %s", p->src->name,
                                what);
        a->xyz = grown;
        if (comps) {
            unsigned char *c = realloc(*comps, (size_t)cap);
            if (!c)
                return vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory for %s", p->src->name,
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
static int obj_vertex(struct obj_parse *p, const char *kw, char *cur, struct vt_error *err)
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
    int n = parse_numbers(&cur, vals, max, &bad);
    if (n < 0)
        return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: bad number '%s' in '%s'",
                            p->src->name, (unsigned long long)cur_line(p), bad, kw);
    if (n < min || token_next(&cur))
        return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: '%s' needs %d to %d numbers",
                            p->src->name, (unsigned long long)cur_line(p), kw, min, max);
    int rc = vec_push(p, a, comps, vals, what, err);
    if (rc == 0 && comps)
        p->obj->vt_components[a->count - 1] = (unsigned char)n;
    return rc;
}

/* A signed decimal index occupying [s, e); false on junk or overflow. */
static bool parse_index(const char *s, const char *e, int64_t *out)
{
    bool neg = false;
    if (s < e && (*s == '-' || *s == '+'))
        neg = *s++ == '-';
    if (s == e)
        return false;
    int64_t v = 0;
    for (; s < e; s++) {
        if (*s < '0' || *s > '9' || v > (INT64_C(1) << 40))
            return false;
        v = v * 10 + (*s - '0');
    }
    *out = neg ? -v : v;
    return true;
}

static const char *const index_names[3] = {"vertex", "texture", "normal"};

/* Resolves one OBJ index (1-based, or negative counting back from the latest) into 0-based. */
static int resolve_index(struct obj_parse *p, int kind, int64_t idx, uint32_t count,
                         const char *tok, uint32_t *out, struct vt_error *err)
{
    static const char *const plural[3] = {"vertices", "texcoords", "normals"};
    if (idx == 0)
        return vt_error_set(err, VT_ERR_BAD_INPUT,
                            "'%s':%llu: %s index 0 in '%s' (OBJ indices start at 1)", p->src->name,
                            (unsigned long long)cur_line(p), index_names[kind], tok);
    int64_t abs_idx = idx > 0 ? idx - 1 : (int64_t)count + idx;
    if (abs_idx < 0 || abs_idx >= (int64_t)count)
        return vt_error_set(err, VT_ERR_BAD_INPUT,
                            "'%s':%llu: %s index %lld in '%s' out of range (%lu %s defined)",
                            p->src->name, (unsigned long long)cur_line(p), index_names[kind],
                            (long long)idx, tok, (unsigned long)count, plural[kind]);
    *out = (uint32_t)abs_idx;
    return 0;
}

/* One corner token: v, v/vt, v//vn or v/vt/vn. */
static int obj_corner(struct obj_parse *p, const char *tok, struct vt_obj_corner *c,
                      struct vt_error *err)
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
            if (!parse_index(s, e, &idx))
                return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: bad %s index '%s'",
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
    return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: bad face corner '%s'", p->src->name,
                        (unsigned long long)cur_line(p), tok);
}

/* Turns a callback's non-zero return into the read's status, with a message if it left none. */
static int callback_status(struct obj_parse *p, int rc, const char *what, struct vt_error *cb_err,
                           struct vt_error *err)
{
    if (rc == 0)
        return 0;
    int status = rc < 0 ? rc : VT_ERR_CANCELLED;
    if (cb_err->status != VT_OK) {
        if (err)
            *err = *cb_err;
        return status;
    }
    return vt_error_set(err, status, "'%s':%llu: stopped by the %s callback", p->src->name,
                        (unsigned long long)cur_line(p), what);
}

static int obj_face(struct obj_parse *p, char *cur, struct vt_error *err)
{
    struct vt_obj *obj = p->obj;
    uint32_t n = 0;
    char *tok;
    while ((tok = token_next(&cur)) != NULL) {
        if (n == obj->corner_cap) {
            /* a corner takes >= 2 bytes of the line, so the line limit bounds this */
            size_t cap = obj->corner_cap ? obj->corner_cap * 2 : 16;
            struct vt_obj_corner *c = realloc(obj->corners, cap * sizeof *c);
            if (!c)
                return vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory for a face",
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
        return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: face with %lu corners (needs 3)",
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
    struct vt_error cb_err = {0};
    return callback_status(p, p->cb->face(p->cb->user, obj, &f, &cb_err), "face", &cb_err, err);
}

static int set_name(struct obj_parse *p, char **slot, const char *value, struct vt_error *err)
{
    char *copy = strdup(value);
    if (!copy)
        return vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory", p->src->name);
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

static int obj_mtllib_one(struct obj_parse *p, const char *file, struct vt_error *err)
{
    if (!p->cb || !p->cb->mtllib)
        return 0;
    char *path = vt_obj_resolve_path(p->src->name, file);
    if (!path)
        return vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory", p->src->name);
    struct vt_error cb_err = {0};
    int rc = p->cb->mtllib(p->cb->user, p->obj, path, cur_line(p), &cb_err);
    free(path);
    return callback_status(p, rc, "mtllib", &cb_err, err);
}

static int obj_mtllib(struct obj_parse *p, char *cur, struct vt_error *err)
{
    char *rest = rest_of_line(cur);
    if (!*rest)
        return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: mtllib without a file name",
                            p->src->name, (unsigned long long)cur_line(p));
    if (names_one_file(rest))
        return obj_mtllib_one(p, rest, err);
    char *tok;
    while ((tok = token_next(&rest)) != NULL) {
        int rc = obj_mtllib_one(p, tok, err);
        if (rc < 0)
            return rc;
    }
    return 0;
}

static int obj_usemtl(struct obj_parse *p, char *cur, struct vt_error *err)
{
    int rc = set_name(p, &p->obj->material, rest_of_line(cur), err);
    if (rc < 0 || !p->cb || !p->cb->usemtl)
        return rc;
    struct vt_error cb_err = {0};
    rc = p->cb->usemtl(p->cb->user, p->obj, p->obj->material, cur_line(p), &cb_err);
    return callback_status(p, rc, "usemtl", &cb_err, err);
}

static int obj_statement(struct obj_parse *p, struct vt_error *err)
{
    char *cur = p->src->line;
    char *kw = token_next(&cur);
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
        return set_name(p, &p->obj->group, rest_of_line(cur), err);
    if (strcmp(kw, "o") == 0)
        return set_name(p, &p->obj->object, rest_of_line(cur), err);
    if (strcmp(kw, "l") == 0 || strcmp(kw, "p") == 0 || strcmp(kw, "s") == 0 ||
        strcmp(kw, "vp") == 0)
        p->obj->stats.ignored_statements++;
    else
        p->obj->stats.unknown_statements++;
    return 0;
}

static int obj_parse(struct vt_obj *obj, struct line_src *src, const struct vt_obj_callbacks *cb,
                     struct vt_error *err)
{
    struct obj_parse p = {obj, src, cb};
    int rc;
    while ((rc = line_next(src, err)) == 1) {
        rc = obj_statement(&p, err);
        if (rc < 0)
            break;
    }
    obj->stats.lines = src->physical;
    return rc < 0 ? rc : 0;
}

int vt_obj_read(struct vt_obj *obj, const char *path, const struct vt_obj_callbacks *cb,
                struct vt_error *err)
{
    struct line_src src;
    obj_clear(obj);
    int rc = src_open(&src, path, &obj->limits, err);
    if (rc < 0)
        return rc;
    rc = obj_parse(obj, &src, cb, err);
    src_close(&src);
    return rc;
}

int vt_obj_parse_memory(struct vt_obj *obj, const void *data, size_t size, const char *name,
                        const struct vt_obj_callbacks *cb, struct vt_error *err)
{
    struct line_src src;
    obj_clear(obj);
    src_memory(&src, data, size, name, &obj->limits);
    int rc = obj_parse(obj, &src, cb, err);
    src_close(&src);
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

/* ---- MTL ---- */

struct mtl_parse {
    struct vt_mtl *mtl;
    struct line_src *src;
    const struct vt_obj_limits *limits;
    size_t cap;
};

static int mtl_bad(struct mtl_parse *p, const char *what, const char *tok, struct vt_error *err)
{
    return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: %s '%s'", p->src->name,
                        (unsigned long long)p->src->start_line, what, tok);
}

static void map_defaults(struct vt_mtl_map *m)
{
    memset(m, 0, sizeof *m);
    m->s[0] = m->s[1] = m->s[2] = 1;
    m->bm = 1;
    m->mm[1] = 1;
    m->blendu = m->blendv = true;
}

static void map_release(struct vt_mtl_map *m)
{
    free(m->file);
    free(m->path);
    map_defaults(m);
}

static int mtl_newmtl(struct mtl_parse *p, char *cur, struct vt_error *err)
{
    struct vt_mtl *mtl = p->mtl;
    if (mtl->material_count >= p->limits->max_materials)
        return vt_error_set(err, VT_ERR_LIMIT, "'%s':%llu: more than %lu materials (the limit)",
                            p->src->name, (unsigned long long)p->src->start_line,
                            (unsigned long)p->limits->max_materials);
    if (mtl->material_count == p->cap) {
        size_t cap = p->cap ? p->cap * 2 : 16, bytes;
        struct vt_mtl_material *m;
        if (!vt_size_mul(cap, sizeof *m, &bytes) || !(m = realloc(mtl->materials, bytes)))
            return vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory for materials",
                                p->src->name);
        mtl->materials = m;
        p->cap = cap;
    }
    struct vt_mtl_material *m = &mtl->materials[mtl->material_count];
    memset(m, 0, sizeof *m);
    for (int i = 0; i < VT_MTL_MAP_COUNT; i++)
        map_defaults(&m->maps[i]);
    m->d = 1;
    m->line = p->src->start_line;
    m->name = strdup(rest_of_line(cur));
    if (!m->name)
        return vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory", p->src->name);
    mtl->material_count++;
    return 0;
}

/* Kd/Ka/Ks r [g b] (one value means grey); "spectral" and "xyz" forms are counted as unknown. */
static int mtl_colour(struct mtl_parse *p, struct vt_mtl_material *m, const char *kw, char *cur,
                      struct vt_error *err)
{
    double rgb[3];
    const char *bad = NULL;
    const char *rest = rest_of_line(cur);
    if (strncmp(rest, "spectral", 8) == 0 || strncmp(rest, "xyz", 3) == 0) {
        p->mtl->unknown_statements++;
        return 0;
    }
    int n = parse_numbers(&cur, rgb, 3, &bad);
    if (n < 0)
        return mtl_bad(p, "bad number", bad, err);
    if ((n != 1 && n != 3) || token_next(&cur))
        return mtl_bad(p, "needs 1 or 3 numbers:", kw, err);
    if (n == 1)
        rgb[1] = rgb[2] = rgb[0];
    double *dst = kw[1] == 'd' ? m->kd : kw[1] == 'a' ? m->ka : m->ks;
    memcpy(dst, rgb, sizeof rgb);
    m->flags |= kw[1] == 'd' ? VT_MTL_HAS_KD : kw[1] == 'a' ? VT_MTL_HAS_KA : VT_MTL_HAS_KS;
    return 0;
}

/* d [-halo] f, Tr f, illum n. */
static int mtl_scalar(struct mtl_parse *p, struct vt_mtl_material *m, const char *kw, char *cur,
                      struct vt_error *err)
{
    char *tok = token_next(&cur);
    if (tok && strcmp(kw, "d") == 0 && strcmp(tok, "-halo") == 0)
        tok = token_next(&cur);
    double v;
    if (!tok)
        return mtl_bad(p, "missing value after", kw, err);
    if (!parse_double(tok, &v) || token_next(&cur))
        return mtl_bad(p, "bad number", tok, err);
    if (kw[0] == 'd') {
        m->d = v, m->flags |= VT_MTL_HAS_D;
    } else if (kw[0] == 'T') {
        m->tr = v, m->flags |= VT_MTL_HAS_TR;
    } else {
        if (v != floor(v) || v < 0 || v > 100)
            return mtl_bad(p, "bad illum", tok, err);
        m->illum = (int)v, m->flags |= VT_MTL_HAS_ILLUM;
    }
    return 0;
}

static int map_kind(const char *kw)
{
    static const char *const names[] = {"map_Kd", "map_Ka",   "map_Ks", "map_d", "map_Bump",
                                        "bump",   "map_bump", "norm",   "disp"};
    static const int kinds[] = {VT_MTL_MAP_KD,   VT_MTL_MAP_KA,   VT_MTL_MAP_KS,
                                VT_MTL_MAP_D,    VT_MTL_MAP_BUMP, VT_MTL_MAP_BUMP,
                                VT_MTL_MAP_BUMP, VT_MTL_MAP_NORM, VT_MTL_MAP_DISP};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (strcasecmp(kw, names[i]) == 0)
            return kinds[i];
    return -1;
}

/* Reads 1..max numbers of an option into out (unread ones keep their value). A token that is not a
 * number ends the list (it may be the file name). */
static int map_numbers(struct mtl_parse *p, char **cur, const char *opt, double *out, int max,
                       struct vt_error *err)
{
    int n = 0;
    while (n < max) {
        char *save = *cur;
        char *tok = token_next(cur);
        if (!tok || !parse_double(tok, &out[n])) {
            if (tok && tok + strlen(tok) < *cur)
                tok[strlen(tok)] = ' '; /* undo the split: the token belongs to the file name */
            *cur = save;
            break;
        }
        n++;
    }
    return n ? 0 : mtl_bad(p, "missing number after", opt, err);
}

static int map_onoff(struct mtl_parse *p, char **cur, const char *opt, bool *out,
                     struct vt_error *err)
{
    char *tok = token_next(cur);
    if (tok && strcmp(tok, "on") == 0)
        *out = true;
    else if (tok && strcmp(tok, "off") == 0)
        *out = false;
    else
        return mtl_bad(p, "expected on or off after", opt, err);
    return 0;
}

/* One option starting at tok; fills m and sets its bit. */
static int map_option(struct mtl_parse *p, struct vt_mtl_map *m, const char *opt, char **cur,
                      struct vt_error *err)
{
    static const struct {
        const char *name;
        unsigned bit;
    } table[] = {{"-s", VT_MTL_OPT_S},           {"-o", VT_MTL_OPT_O},
                 {"-t", VT_MTL_OPT_T},           {"-clamp", VT_MTL_OPT_CLAMP},
                 {"-bm", VT_MTL_OPT_BM},         {"-imfchan", VT_MTL_OPT_IMFCHAN},
                 {"-blendu", VT_MTL_OPT_BLENDU}, {"-blendv", VT_MTL_OPT_BLENDV},
                 {"-mm", VT_MTL_OPT_MM},         {"-texres", VT_MTL_OPT_TEXRES},
                 {"-cc", VT_MTL_OPT_CC},         {"-boost", VT_MTL_OPT_BOOST}};
    unsigned bit = 0;
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)
        if (strcmp(opt, table[i].name) == 0)
            bit = table[i].bit;
    m->options |= bit;
    switch (bit) {
    case VT_MTL_OPT_S:
        return map_numbers(p, cur, opt, m->s, 3, err);
    case VT_MTL_OPT_O:
        return map_numbers(p, cur, opt, m->o, 3, err);
    case VT_MTL_OPT_T:
        return map_numbers(p, cur, opt, m->t, 3, err);
    case VT_MTL_OPT_BM:
        return map_numbers(p, cur, opt, &m->bm, 1, err);
    case VT_MTL_OPT_BOOST:
        return map_numbers(p, cur, opt, &m->boost, 1, err);
    case VT_MTL_OPT_TEXRES:
        return map_numbers(p, cur, opt, &m->texres, 1, err);
    case VT_MTL_OPT_MM:
        return map_numbers(p, cur, opt, m->mm, 2, err);
    case VT_MTL_OPT_CLAMP:
        return map_onoff(p, cur, opt, &m->clamp, err);
    case VT_MTL_OPT_BLENDU:
        return map_onoff(p, cur, opt, &m->blendu, err);
    case VT_MTL_OPT_BLENDV:
        return map_onoff(p, cur, opt, &m->blendv, err);
    case VT_MTL_OPT_CC:
        return map_onoff(p, cur, opt, &m->cc, err);
    case VT_MTL_OPT_IMFCHAN: {
        char *tok = token_next(cur);
        if (!tok || strlen(tok) != 1 || !strchr("rgbmlz", tok[0]))
            return mtl_bad(p, "expected r, g, b, m, l or z after", opt, err);
        m->imfchan = tok[0];
        return 0;
    }
    default:
        return mtl_bad(p, "unknown map option", opt, err);
    }
}

/* map_* [options] file name (the rest of the line, spaces allowed). */
static int mtl_map(struct mtl_parse *p, struct vt_mtl_material *m, int kind, char *cur,
                   struct vt_error *err)
{
    struct vt_mtl_map map;
    map_defaults(&map);
    for (;;) {
        while (is_space(*cur))
            cur++;
        if (cur[0] != '-' || (cur[1] >= '0' && cur[1] <= '9'))
            break;
        char *opt = token_next(&cur);
        int rc = map_option(p, &map, opt, &cur, err);
        if (rc < 0)
            return rc;
    }
    char *rest = rest_of_line(cur);
    if (!*rest)
        return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: map statement without a file name",
                            p->src->name, (unsigned long long)p->src->start_line);
    map.file = vt_obj_resolve_path("", rest);
    map.path = vt_obj_resolve_path(p->src->name, rest);
    if (!map.file || !map.path) {
        map_release(&map);
        return vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory", p->src->name);
    }
    map_release(&m->maps[kind]); /* a repeated statement replaces the earlier one */
    m->maps[kind] = map;
    return 0;
}

static int mtl_statement(struct mtl_parse *p, struct vt_error *err)
{
    char *cur = p->src->line;
    char *kw = token_next(&cur);
    if (!kw)
        return 0;
    if (strcmp(kw, "newmtl") == 0)
        return mtl_newmtl(p, cur, err);
    struct vt_mtl_material *m =
        p->mtl->material_count ? &p->mtl->materials[p->mtl->material_count - 1] : NULL;
    int kind = map_kind(kw);
    if (!m) {
        p->mtl->unknown_statements++; /* before any newmtl: nothing to attach it to */
        return 0;
    }
    if (kind >= 0)
        return mtl_map(p, m, kind, cur, err);
    if (strcmp(kw, "Kd") == 0 || strcmp(kw, "Ka") == 0 || strcmp(kw, "Ks") == 0)
        return mtl_colour(p, m, kw, cur, err);
    if (strcmp(kw, "d") == 0 || strcmp(kw, "Tr") == 0 || strcmp(kw, "illum") == 0)
        return mtl_scalar(p, m, kw, cur, err);
    p->mtl->unknown_statements++;
    return 0;
}

static int mtl_parse(struct line_src *src, const struct vt_obj_limits *limits, struct vt_mtl *mtl,
                     struct vt_error *err)
{
    struct mtl_parse p = {mtl, src, limits, 0};
    int rc;
    while ((rc = line_next(src, err)) == 1) {
        rc = mtl_statement(&p, err);
        if (rc < 0)
            break;
    }
    return rc < 0 ? rc : 0;
}

int vt_mtl_read(const char *path, const struct vt_obj_limits *limits, struct vt_mtl *mtl,
                struct vt_error *err)
{
    struct vt_obj_limits defaults;
    if (!limits) {
        vt_obj_limits_default(&defaults);
        limits = &defaults;
    }
    memset(mtl, 0, sizeof *mtl);
    struct line_src src;
    int rc = src_open(&src, path, limits, err);
    if (rc < 0)
        return rc;
    rc = mtl_parse(&src, limits, mtl, err);
    src_close(&src);
    return rc;
}

int vt_mtl_parse_memory(const void *data, size_t size, const char *name,
                        const struct vt_obj_limits *limits, struct vt_mtl *mtl,
                        struct vt_error *err)
{
    struct vt_obj_limits defaults;
    if (!limits) {
        vt_obj_limits_default(&defaults);
        limits = &defaults;
    }
    memset(mtl, 0, sizeof *mtl);
    struct line_src src;
    src_memory(&src, data, size, name, limits);
    int rc = mtl_parse(&src, limits, mtl, err);
    src_close(&src);
    return rc;
}

void vt_mtl_release(struct vt_mtl *mtl)
{
    if (!mtl)
        return;
    for (size_t i = 0; i < mtl->material_count; i++) {
        free(mtl->materials[i].name);
        for (int k = 0; k < VT_MTL_MAP_COUNT; k++)
            map_release(&mtl->materials[i].maps[k]);
    }
    free(mtl->materials);
    memset(mtl, 0, sizeof *mtl);
}

const struct vt_mtl_material *vt_mtl_find(const struct vt_mtl *mtl, const char *name)
{
    for (size_t i = mtl->material_count; i-- > 0;)
        if (strcmp(mtl->materials[i].name, name) == 0)
            return &mtl->materials[i];
    return NULL;
}
