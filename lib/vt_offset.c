/* vt-offset's rewriting engine (see vt_offset.h and docs/cli/vt-offset.md).
 *
 * The OBJ is read twice through the same raw line source. It keeps each logical line as raw bytes
 * (terminators, '\r' and '\' continuations included) so that lines can be copied unchanged, and
 * tokenises the raw bytes with vt_obj's rules: whitespace is space, tab, '\r', '\v', '\f', a
 * '\n' inside a continued line and a '\' that continues the line; a token starting with '#' ends
 * the statement. We do not use vt_obj_read() for pass 1: it keeps every v and vn (the rewrite
 * must grow with the vt count only) and parses their numbers with strtod (too slow here); the
 * statements that matter (vt, f, usemtl, mtllib) are checked with its rules and messages. */
#include "vt_offset.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_checked.h"
#include "vt_text.h"
#include "vt_uv_text.h"

#define READ_CHUNK  ((size_t)1 << 20)
#define OUT_CHUNK   ((size_t)1 << 20)
#define NONE        UINT32_MAX       /* no material / no extra */
#define MAT_NONE    UINT32_MAX       /* before any usemtl */
#define MAT_MISSING (UINT32_MAX - 1) /* usemtl of a material the layout lacks */

void vt_offset_options_default(struct vt_offset_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->layout_name = "atlas.json";
    opt->mtllib = "out.mtl";
    opt->material = VT_OFFSET_MATERIAL;
    vt_obj_limits_default(&opt->limits);
}

unsigned vt_offset_default_digits(const struct vt_layout *layout)
{
    double edge = layout->width > layout->height ? layout->width : layout->height;
    unsigned digits = 6;
    /* half a unit of the last place, in texels, at most 1e-4 */
    while (digits < VT_UV_MAX_DIGITS && 0.5 * pow(10.0, -(double)digits) * edge > 1e-4)
        digits++;
    return digits;
}

bool vt_offset_f32_warning(const struct vt_offset_stats *stats)
{
    return stats->max_error_f32 > VT_OFFSET_F32_WARN_TEXELS;
}

/* ---- raw logical lines ---- */

struct src {
    const char *name;
    FILE *file;                /* NULL for memory */
    const unsigned char *data; /* buf, or the caller's memory */
    unsigned char *buf;
    size_t cap, len, pos;
    bool eof;
    bool nul; /* a NUL byte was read: lines are checked for it */
    size_t max_line;
    uint64_t physical; /* physical lines consumed */
    uint64_t line;     /* first physical line of the current logical line */
};

static int src_open(struct src *s, const char *path, const void *mem, size_t mem_size,
                    size_t max_line, struct vt_error *err)
{
    memset(s, 0, sizeof *s);
    s->name = path;
    s->max_line = max_line < SIZE_MAX / 4 ? max_line : SIZE_MAX / 4;
    if (mem) {
        s->data = mem;
        s->len = mem_size;
        s->eof = true;
        s->nul = memchr(mem, '\0', mem_size) != NULL;
        return 0;
    }
    s->file = fopen(path, "rb");
    if (!s->file)
        return vt_error_set(err, VT_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
    s->cap = READ_CHUNK;
    s->buf = malloc(s->cap);
    if (!s->buf) {
        fclose(s->file);
        s->file = NULL;
        return vt_error_set(err, VT_ERR_NOMEM, "cannot read '%s': out of memory", path);
    }
    s->data = s->buf;
    return 0;
}

static void src_close(struct src *s)
{
    if (s->file)
        fclose(s->file);
    free(s->buf);
    memset(s, 0, sizeof *s);
}

/* Keeps the unread bytes, growing the buffer when the line being read fills it, and reads more. */
static int src_fill(struct src *s, size_t *scan, struct vt_error *err)
{
    if (s->pos > 0) {
        memmove(s->buf, s->buf + s->pos, s->len - s->pos);
        s->len -= s->pos;
        *scan -= s->pos;
        s->pos = 0;
    }
    if (s->len == s->cap) {
        /* a line of max_line counted bytes takes at most 2 * max_line + 2 raw ones */
        if (s->len > 2 * s->max_line + 2)
            return vt_error_set(err, VT_ERR_LIMIT,
                                "'%s':%llu: line longer than the limit of %zu bytes", s->name,
                                (unsigned long long)s->physical + 1, s->max_line);
        unsigned char *grown = realloc(s->buf, s->cap * 2);
        if (!grown)
            return vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory for a line", s->name);
        s->buf = grown;
        s->data = grown;
        s->cap *= 2;
    }
    size_t got = fread(s->buf + s->len, 1, s->cap - s->len, s->file);
    if (got == 0) {
        if (ferror(s->file))
            return vt_error_set(err, VT_ERR_IO, "cannot read '%s': %s", s->name, strerror(errno));
        s->eof = true;
    }
    if (memchr(s->buf + s->len, '\0', got))
        s->nul = true;
    s->len += got;
    return 0;
}

/* The next logical line as raw bytes (with its '\n'): 1, 0 at the end, or a negative status. */
static int src_next(struct src *s, const unsigned char **line, size_t *line_len,
                    struct vt_error *err)
{
    size_t scan = s->pos, end;
    uint64_t newlines = 0;
    s->line = s->physical + 1;
    for (;;) {
        const unsigned char *nl =
            scan < s->len ? memchr(s->data + scan, '\n', s->len - scan) : NULL;
        if (nl) {
            size_t at = (size_t)(nl - s->data), b = at;
            newlines++;
            if (b > s->pos && s->data[b - 1] == '\r')
                b--;
            if (b > s->pos && s->data[b - 1] == '\\') {
                scan = at + 1;
                continue;
            }
            end = at + 1;
            break;
        }
        if (s->eof) {
            if (s->pos == s->len)
                return 0;
            end = s->len;
            break;
        }
        int rc = src_fill(s, &scan, err);
        if (rc < 0)
            return rc;
    }
    const unsigned char *p = s->data + s->pos;
    size_t n = end - s->pos;
    if (n - newlines > s->max_line)
        return vt_error_set(err, VT_ERR_LIMIT, "'%s':%llu: line longer than the limit of %zu bytes",
                            s->name, (unsigned long long)s->line, s->max_line);
    const unsigned char *nul = s->nul ? memchr(p, '\0', n) : NULL;
    if (nul) {
        uint64_t at_line = s->line;
        for (const unsigned char *q = p; q < nul; q++)
            at_line += *q == '\n';
        return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: NUL byte in a text line", s->name,
                            (unsigned long long)at_line);
    }
    s->physical += newlines + (p[n - 1] != '\n');
    s->pos = end;
    *line = p;
    *line_len = n;
    return 1;
}

/* ---- tokens of a raw line ---- */

static inline bool raw_space(const unsigned char *p, const unsigned char *end)
{
    switch (*p) {
    case ' ':
    case '\t':
    case '\r':
    case '\n':
    case '\v':
    case '\f':
        return true;
    case '\\': {
        const unsigned char *q = p + 1;
        if (q < end && *q == '\r')
            q++;
        return q == end || *q == '\n';
    }
    default:
        return false;
    }
}

struct tok {
    const unsigned char *s, *e;
};

/* The next token of [*cur, end); false at the end or at a '#' comment. */
static inline bool next_tok(const unsigned char **cur, const unsigned char *end, struct tok *t)
{
    const unsigned char *p = *cur;
    while (p < end && raw_space(p, end))
        p++;
    if (p == end || *p == '#') {
        *cur = p;
        return false;
    }
    t->s = p;
    while (p < end && !raw_space(p, end))
        p++;
    t->e = p;
    *cur = p;
    return true;
}

static inline bool tok_is(const struct tok *t, const char *word, size_t n)
{
    return (size_t)(t->e - t->s) == n && memcmp(t->s, word, n) == 0;
}

enum keyword { KW_OTHER, KW_V, KW_VT, KW_VN, KW_F, KW_L, KW_USEMTL, KW_MTLLIB };

static enum keyword keyword_of(const struct tok *t)
{
    switch (t->e - t->s) {
    case 1:
        return t->s[0] == 'v' ? KW_V : t->s[0] == 'f' ? KW_F : t->s[0] == 'l' ? KW_L : KW_OTHER;
    case 2:
        return tok_is(t, "vt", 2) ? KW_VT : tok_is(t, "vn", 2) ? KW_VN : KW_OTHER;
    case 6:
        return tok_is(t, "usemtl", 6) ? KW_USEMTL : tok_is(t, "mtllib", 6) ? KW_MTLLIB : KW_OTHER;
    default:
        return KW_OTHER;
    }
}

/* A signed decimal index in [s, e) (vt_obj's rules); false on junk or overflow. */
static bool parse_index(const unsigned char *s, const unsigned char *e, int64_t *out)
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

/* ---- the run ---- */

struct extra {
    uint32_t mat;  /* entry index */
    uint32_t next; /* next extra of the same vt, or NONE */
};

struct repl {
    size_t s, e; /* bytes of the line to replace */
    int64_t value;
};

struct run {
    const struct vt_layout *layout;
    const struct vt_offset_options *opt;
    const struct vt_offset_sink *out;
    struct src src;
    unsigned digits;
    /* pass 1 */
    uint64_t nv, nvn;
    uint32_t nvt, cap;
    double *uv;          /* u v per vt */
    uint32_t *first;     /* entry index of the first material using the vt, or NONE */
    uint32_t *head;      /* its first extra material, or NONE */
    uint32_t *new_index; /* 0-based index of its first copy in the output */
    struct extra *extra;
    uint32_t extra_count, extra_cap;
    uint32_t mat;      /* current material (entry index, MAT_NONE or MAT_MISSING) */
    char *mat_name;    /* name on the current usemtl line */
    uint64_t mat_line; /* its line */
    bool any_mtllib;
    char *clean; /* a line as vt_obj sees it (usemtl, mtllib) */
    size_t clean_cap;
    /* pass 2 */
    uint32_t in_vt;  /* vt statements copied so far */
    uint64_t out_vt; /* vt lines written so far */
    bool mtllib_written;
    struct repl *repl;
    size_t repl_cap;
    unsigned char *obuf;
    size_t olen;
    struct vt_offset_stats stats;
};

static int out_flush(struct run *r, struct vt_error *err)
{
    if (r->olen == 0)
        return 0;
    int rc = r->out->write(r->out->user, r->obuf, r->olen, err);
    r->olen = 0;
    return rc < 0 ? rc : 0;
}

static int out_put(struct run *r, const void *data, size_t n, struct vt_error *err)
{
    if (n > OUT_CHUNK - r->olen) {
        int rc = out_flush(r, err);
        if (rc < 0)
            return rc;
        if (n > OUT_CHUNK) {
            rc = r->out->write(r->out->user, data, n, err);
            return rc < 0 ? rc : 0;
        }
    }
    memcpy(r->obuf + r->olen, data, n);
    r->olen += n;
    return 0;
}

static int out_str(struct run *r, const char *s, struct vt_error *err)
{
    return out_put(r, s, strlen(s), err);
}

/* Copies the line as vt_obj sees it into r->clean: '\r' before '\n' dropped, a continuing '\'
 * turned into a space, the '\n's removed. */
static int clean_line(struct run *r, const unsigned char *p, size_t n, struct vt_error *err)
{
    if (n + 1 > r->clean_cap) {
        char *grown = realloc(r->clean, n + 1);
        if (!grown)
            return vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory for a line", r->src.name);
        r->clean = grown;
        r->clean_cap = n + 1;
    }
    size_t len = 0;
    const unsigned char *end = p + n;
    while (p < end) {
        const unsigned char *nl = memchr(p, '\n', (size_t)(end - p));
        const unsigned char *pe = nl ? nl : end;
        size_t start = len;
        memcpy(r->clean + len, p, (size_t)(pe - p));
        len += (size_t)(pe - p);
        if (len > start && r->clean[len - 1] == '\r')
            len--;
        if (len > start && r->clean[len - 1] == '\\')
            r->clean[len - 1] = ' ';
        p = nl ? nl + 1 : end;
    }
    r->clean[len] = '\0';
    return 0;
}

/* The name on a usemtl line (vt_obj: the rest of the line, trimmed). */
static int usemtl_name(struct run *r, const unsigned char *line, size_t n, char **name,
                       struct vt_error *err)
{
    int rc = clean_line(r, line, n, err);
    if (rc < 0)
        return rc;
    char *cur = r->clean;
    vt_text_token(&cur); /* the keyword */
    *name = vt_text_rest(cur);
    return 0;
}

static uint32_t material_index(const struct run *r, const char *name)
{
    const struct vt_layout_entry *e = vt_layout_find(r->layout, name);
    return e ? (uint32_t)(e - r->layout->entries) : MAT_MISSING;
}

/* ---- pass 1 ---- */

static int grow_vt(struct run *r, struct vt_error *err)
{
    if (r->nvt >= r->opt->limits.max_vertices || r->nvt >= UINT32_MAX - 1)
        return vt_error_set(err, VT_ERR_LIMIT, "'%s':%llu: more than %lu texcoords (the limit)",
                            r->src.name, (unsigned long long)r->src.line,
                            (unsigned long)r->opt->limits.max_vertices);
    if (r->nvt < r->cap)
        return 0;
    uint64_t cap = r->cap ? (uint64_t)r->cap * 2 : 4096;
    if (cap > UINT32_MAX - 1)
        cap = UINT32_MAX - 1;
    size_t uv_bytes, idx_bytes;
    if (!vt_size_mul((size_t)cap, 2 * sizeof(double), &uv_bytes) ||
        !vt_size_mul((size_t)cap, sizeof(uint32_t), &idx_bytes))
        return vt_error_set(err, VT_ERR_LIMIT, "'%s': too many texcoords", r->src.name);
    double *uv = realloc(r->uv, uv_bytes);
    if (uv)
        r->uv = uv;
    uint32_t *first = uv ? realloc(r->first, idx_bytes) : NULL;
    if (first)
        r->first = first;
    uint32_t *head = first ? realloc(r->head, idx_bytes) : NULL;
    if (!head)
        return vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory for texcoords", r->src.name);
    r->head = head;
    r->cap = (uint32_t)cap;
    return 0;
}

static int count_vertex(struct run *r, uint64_t *count, const char *what, struct vt_error *err)
{
    if (*count >= r->opt->limits.max_vertices)
        return vt_error_set(err, VT_ERR_LIMIT, "'%s':%llu: more than %lu %s (the limit)",
                            r->src.name, (unsigned long long)r->src.line,
                            (unsigned long)r->opt->limits.max_vertices, what);
    (*count)++;
    return 0;
}

/* Copies a token into buf for a message (cut at 63 bytes). */
static const char *tok_text(const struct tok *t, char buf[64])
{
    size_t n = (size_t)(t->e - t->s);
    if (n > 63)
        n = 63;
    memcpy(buf, t->s, n);
    buf[n] = '\0';
    return buf;
}

static int pass1_vt(struct run *r, const unsigned char *cur, const unsigned char *end,
                    struct vt_error *err)
{
    double vals[3] = {0, 0, 0};
    int n = 0;
    struct tok t;
    char text[64];
    while (next_tok(&cur, end, &t)) {
        if (n == 3)
            return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: 'vt' needs 1 to 3 numbers",
                                r->src.name, (unsigned long long)r->src.line);
        if (!vt_uv_parse((const char *)t.s, (size_t)(t.e - t.s), &vals[n]))
            return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: bad number '%s' in 'vt'",
                                r->src.name, (unsigned long long)r->src.line, tok_text(&t, text));
        n++;
    }
    if (n == 0)
        return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: 'vt' needs 1 to 3 numbers",
                            r->src.name, (unsigned long long)r->src.line);
    int rc = grow_vt(r, err);
    if (rc < 0)
        return rc;
    r->uv[2 * (size_t)r->nvt] = vals[0];
    r->uv[2 * (size_t)r->nvt + 1] = vals[1];
    r->first[r->nvt] = NONE;
    r->head[r->nvt] = NONE;
    r->nvt++;
    return 0;
}

/* True when every layer of e is a constant fill (a material without textures): its texture
 * coordinates do not matter, and every one is mapped to the centre of its cell so that bilinear
 * filtering never reaches the neighbouring cells. */
static bool constant_entry(const struct vt_layout *l, const struct vt_layout_entry *e)
{
    for (uint32_t k = 0; k < l->layer_count; k++)
        if (e->textures[k].path)
            return false;
    return true;
}

/* Checks that vt i lies in what material m covers. */
static int check_covered(struct run *r, uint32_t i, uint32_t m, struct vt_error *err)
{
    const struct vt_layout_entry *e = &r->layout->entries[m];
    if (constant_entry(r->layout, e))
        return 0;
    double u = r->uv[2 * (size_t)i], v = r->uv[2 * (size_t)i + 1];
    if (vt_layout_uv_covered(e, u, v))
        return 0;
    return vt_error_set(err, VT_ERR_BAD_INPUT,
                        "'%s':%llu: vt %lu (%.9g %.9g) is outside the UV range of material '%s' "
                        "in '%s' (u %ld..%ld, v %ld..%ld)",
                        r->src.name, (unsigned long long)r->src.line, (unsigned long)i + 1, u, v,
                        e->name, r->opt->layout_name, (long)e->origin_u,
                        (long)e->origin_u + (long)e->repeat_u, (long)e->origin_v,
                        (long)e->origin_v + (long)e->repeat_v);
}

/* Records that the current material uses vt i. */
static int use_vt(struct run *r, uint32_t i, struct vt_error *err)
{
    uint32_t m = r->mat;
    if (m == MAT_NONE)
        return vt_error_set(err, VT_ERR_BAD_INPUT,
                            "'%s':%llu: face with texture coordinates before any usemtl",
                            r->src.name, (unsigned long long)r->src.line);
    if (m == MAT_MISSING)
        return vt_error_set(err, VT_ERR_BAD_INPUT,
                            "'%s':%llu: material '%s' (usemtl on line %llu) is not in '%s'",
                            r->src.name, (unsigned long long)r->src.line, r->mat_name,
                            (unsigned long long)r->mat_line, r->opt->layout_name);
    if (r->first[i] == m)
        return 0;
    if (r->first[i] == NONE) {
        int rc = check_covered(r, i, m, err);
        if (rc == 0)
            r->first[i] = m;
        return rc;
    }
    uint32_t prev = NONE;
    for (uint32_t k = r->head[i]; k != NONE; prev = k, k = r->extra[k].next)
        if (r->extra[k].mat == m)
            return 0;
    int rc = check_covered(r, i, m, err);
    if (rc < 0)
        return rc;
    if (r->extra_count == r->extra_cap) {
        if (r->extra_cap >= UINT32_MAX / 2)
            return vt_error_set(err, VT_ERR_LIMIT, "'%s': too many shared texcoords", r->src.name);
        uint32_t cap = r->extra_cap ? r->extra_cap * 2 : 256;
        struct extra *grown = realloc(r->extra, (size_t)cap * sizeof *grown);
        if (!grown)
            return vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory for shared texcoords",
                                r->src.name);
        r->extra = grown;
        r->extra_cap = cap;
    }
    uint32_t at = r->extra_count++;
    r->extra[at] = (struct extra){m, NONE};
    if (prev == NONE)
        r->head[i] = at;
    else
        r->extra[prev].next = at;
    return 0;
}

/* One face corner: v, v/vt, v//vn or v/vt/vn, checked like vt_obj; *vt gets the 0-based texture
 * index or NONE. */
static int pass1_corner(struct run *r, const struct tok *t, uint32_t *vt, struct vt_error *err)
{
    static const char *const names[3] = {"vertex", "texture", "normal"};
    static const char *const plural[3] = {"vertices", "texcoords", "normals"};
    const uint64_t counts[3] = {r->nv, r->nvt, r->nvn};
    char text[64];
    const unsigned char *s = t->s;
    *vt = NONE;
    for (int kind = 0; kind < 3; kind++) {
        const unsigned char *e = memchr(s, '/', (size_t)(t->e - s));
        if (!e)
            e = t->e;
        if (e > s || kind == 0) {
            int64_t idx;
            if (!parse_index(s, e, &idx))
                return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: bad %s index '%s'",
                                    r->src.name, (unsigned long long)r->src.line, names[kind],
                                    tok_text(t, text));
            if (idx == 0)
                return vt_error_set(
                    err, VT_ERR_BAD_INPUT, "'%s':%llu: %s index 0 in '%s' (OBJ indices start at 1)",
                    r->src.name, (unsigned long long)r->src.line, names[kind], tok_text(t, text));
            int64_t abs_idx = idx > 0 ? idx - 1 : (int64_t)counts[kind] + idx;
            if (abs_idx < 0 || abs_idx >= (int64_t)counts[kind])
                return vt_error_set(
                    err, VT_ERR_BAD_INPUT,
                    "'%s':%llu: %s index %lld in '%s' out of range (%llu %s defined)", r->src.name,
                    (unsigned long long)r->src.line, names[kind], (long long)idx, tok_text(t, text),
                    (unsigned long long)counts[kind], plural[kind]);
            if (kind == 1)
                *vt = (uint32_t)abs_idx;
        }
        if (e == t->e)
            return 0;
        s = e + 1;
    }
    return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: bad face corner '%s'", r->src.name,
                        (unsigned long long)r->src.line, tok_text(t, text));
}

static int pass1_face(struct run *r, const unsigned char *cur, const unsigned char *end,
                      struct vt_error *err)
{
    struct tok t;
    uint64_t corners = 0;
    bool any_vt = false;
    while (next_tok(&cur, end, &t)) {
        uint32_t vt;
        int rc = pass1_corner(r, &t, &vt, err);
        if (rc < 0)
            return rc;
        if (vt != NONE) {
            any_vt = true;
            rc = use_vt(r, vt, err);
            if (rc < 0)
                return rc;
        }
        corners++;
    }
    if (corners < 3)
        return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: face with %lu corners (needs 3)",
                            r->src.name, (unsigned long long)r->src.line, (unsigned long)corners);
    r->stats.faces++;
    if (!any_vt)
        r->stats.faces_without_vt++;
    return 0;
}

static int pass1_line(struct run *r, const unsigned char *line, size_t n, struct vt_error *err)
{
    const unsigned char *cur = line, *end = line + n;
    struct tok kw;
    if (!next_tok(&cur, end, &kw))
        return 0;
    switch (keyword_of(&kw)) {
    case KW_V:
        return count_vertex(r, &r->nv, "vertices", err);
    case KW_VN:
        return count_vertex(r, &r->nvn, "normals", err);
    case KW_VT:
        return pass1_vt(r, cur, end, err);
    case KW_F:
        return pass1_face(r, cur, end, err);
    case KW_USEMTL: {
        char *name;
        int rc = usemtl_name(r, line, n, &name, err);
        if (rc < 0)
            return rc;
        char *copy = strdup(name);
        if (!copy)
            return vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory", r->src.name);
        free(r->mat_name);
        r->mat_name = copy;
        r->mat_line = r->src.line;
        r->mat = material_index(r, name);
        return 0;
    }
    case KW_MTLLIB: {
        char *name;
        int rc = usemtl_name(r, line, n, &name, err);
        if (rc < 0)
            return rc;
        if (!*name)
            return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: mtllib without a file name",
                                r->src.name, (unsigned long long)r->src.line);
        r->any_mtllib = true;
        return 0;
    }
    default:
        return 0;
    }
}

/* Output indices: vt i's first copy is new_index[i], its k-th extra material new_index[i] + k. */
static int number_outputs(struct run *r, struct vt_error *err)
{
    size_t bytes;
    if (!vt_size_mul((size_t)r->nvt + 1, sizeof(uint32_t), &bytes))
        return vt_error_set(err, VT_ERR_LIMIT, "'%s': too many texcoords", r->src.name);
    r->new_index = malloc(bytes);
    if (!r->new_index)
        return vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory for texcoords", r->src.name);
    uint64_t next = 0;
    for (uint32_t i = 0; i < r->nvt; i++) {
        r->new_index[i] = (uint32_t)next;
        next++;
        for (uint32_t k = r->head[i]; k != NONE; k = r->extra[k].next)
            next++;
        if (next > UINT32_MAX - 1)
            return vt_error_set(err, VT_ERR_LIMIT,
                                "'%s': more than %lu texcoords once shared ones are duplicated",
                                r->src.name, (unsigned long)UINT32_MAX - 1);
    }
    return 0;
}

/* ---- pass 2 ---- */

static const char *line_ending(const unsigned char *line, size_t n)
{
    if (n >= 2 && line[n - 1] == '\n' && line[n - 2] == '\r')
        return "\r\n";
    return "\n";
}

static int changed_error(struct run *r, struct vt_error *err)
{
    return vt_error_set(err, VT_ERR_IO, "'%s':%llu: the file changed while it was read",
                        r->src.name, (unsigned long long)r->src.line);
}

/* Writes one coordinate and measures its round-off against x, scaled to texels. */
static int put_coord(struct run *r, double x, double texels, struct vt_error *err)
{
    char buf[VT_UV_FORMAT_SIZE];
    size_t n = vt_uv_format(x, r->digits, buf);
    double back;
    if (n == 0 || !vt_uv_parse(buf, n, &back))
        return vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%llu: cannot write coordinate %.17g",
                            r->src.name, (unsigned long long)r->src.line, x);
    double e = fabs(back - x) * texels;
    double e32 = fabs((double)(float)back - x) * texels;
    if (e > r->stats.max_error)
        r->stats.max_error = e;
    if (e32 > r->stats.max_error_f32) {
        r->stats.max_error_f32 = e32;
        r->stats.max_error_f32_line = r->src.line;
    }
    return out_put(r, buf, n, err);
}

/* "U V" (and " W" from the original token) of vt i for material m. */
static int put_uv(struct run *r, uint32_t i, uint32_t m, const struct tok *w, struct vt_error *err)
{
    double au, av;
    const struct vt_layout_entry *e = &r->layout->entries[m];
    if (constant_entry(r->layout, e)) {
        au = (e->x + e->width / 2.0) / r->layout->width;
        av = 1.0 - (e->y + e->height / 2.0) / r->layout->height;
    } else {
        vt_layout_map_uv(r->layout, e, r->uv[2 * (size_t)i], r->uv[2 * (size_t)i + 1], &au, &av);
    }
    int rc = put_coord(r, au, r->layout->width, err);
    if (rc == 0)
        rc = out_put(r, " ", 1, err);
    if (rc == 0)
        rc = put_coord(r, av, r->layout->height, err);
    if (rc == 0 && w) {
        rc = out_put(r, " ", 1, err);
        if (rc == 0)
            rc = out_put(r, w->s, (size_t)(w->e - w->s), err);
    }
    return rc;
}

static int pass2_vt(struct run *r, const unsigned char *line, size_t n, const unsigned char *cur,
                    struct vt_error *err)
{
    if (r->in_vt >= r->nvt)
        return changed_error(r, err);
    uint32_t i = r->in_vt++;
    if (r->first[i] == NONE) {
        r->stats.vt_unused++;
        r->out_vt++;
        return out_put(r, line, n, err);
    }
    const unsigned char *end = line + n;
    struct tok t[3];
    int count = 0;
    while (count < 3 && next_tok(&cur, end, &t[count]))
        count++;
    if (count == 0)
        return changed_error(r, err);
    const struct tok *w = count == 3 ? &t[2] : NULL;
    const unsigned char *after = t[count - 1].e;
    int rc = out_put(r, line, (size_t)(t[0].s - line), err);
    if (rc == 0)
        rc = put_uv(r, i, r->first[i], w, err);
    if (rc == 0)
        rc = out_put(r, after, (size_t)(end - after), err);
    r->out_vt++;
    r->stats.vt_rewritten++;
    bool terminated = n && line[n - 1] == '\n';
    const char *eol = line_ending(line, n);
    for (uint32_t k = r->head[i]; rc == 0 && k != NONE; k = r->extra[k].next) {
        if (!terminated)
            rc = out_str(r, eol, err);
        if (rc == 0)
            rc = out_put(r, "vt ", 3, err);
        if (rc == 0)
            rc = put_uv(r, i, r->extra[k].mat, w, err);
        if (rc == 0 && terminated)
            rc = out_str(r, eol, err);
        r->out_vt++;
        r->stats.vt_duplicated++;
    }
    return rc;
}

/* The output index (0-based) of input vt abs for material m (NONE: the first copy). */
static bool output_index(const struct run *r, uint32_t abs_idx, uint32_t m, uint32_t *out)
{
    uint32_t k = 0;
    if (m != NONE && r->first[abs_idx] != m) {
        uint32_t e = r->head[abs_idx];
        for (k = 1; e != NONE && r->extra[e].mat != m; k++)
            e = r->extra[e].next;
        if (e == NONE)
            return false;
    }
    *out = r->new_index[abs_idx] + k;
    return true;
}

/* An index in decimal (printf's %lld without printf), not NUL-terminated. */
static size_t format_index(int64_t value, char buf[24])
{
    char tmp[24];
    size_t n = 0, len = 0;
    uint64_t v = value < 0 ? (uint64_t)0 - (uint64_t)value : (uint64_t)value;
    do {
        tmp[n++] = (char)('0' + v % 10);
        v /= 10;
    } while (v);
    if (value < 0)
        buf[len++] = '-';
    while (n)
        buf[len++] = tmp[--n];
    return len;
}

static int add_repl(struct run *r, size_t count, size_t s, size_t e, int64_t value,
                    struct vt_error *err)
{
    if (count == r->repl_cap) {
        size_t cap = r->repl_cap ? r->repl_cap * 2 : 64;
        struct repl *grown = realloc(r->repl, cap * sizeof *grown);
        if (!grown)
            return vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory for a face", r->src.name);
        r->repl = grown;
        r->repl_cap = cap;
    }
    r->repl[count] = (struct repl){s, e, value};
    return 0;
}

/* An f line (face: strict, material m) or l line (not checked by pass 1: left alone when an index
 * does not resolve; first copies): rewrites the texture indices that change. */
static int pass2_indices(struct run *r, const unsigned char *line, size_t n,
                         const unsigned char *cur, bool face, struct vt_error *err)
{
    const unsigned char *end = line + n;
    uint32_t m = face ? r->mat : NONE;
    size_t count = 0;
    struct tok t;
    while (next_tok(&cur, end, &t)) {
        const unsigned char *a = memchr(t.s, '/', (size_t)(t.e - t.s));
        if (!a)
            continue;
        a++;
        const unsigned char *b = memchr(a, '/', (size_t)(t.e - a));
        if (!b)
            b = t.e;
        if (a == b)
            continue;
        int64_t idx, abs_idx;
        uint32_t out_idx;
        bool ok = parse_index(a, b, &idx) && idx != 0;
        if (ok) {
            abs_idx = idx > 0 ? idx - 1 : (int64_t)r->in_vt + idx;
            ok = abs_idx >= 0 && abs_idx < (int64_t)r->in_vt &&
                 output_index(r, (uint32_t)abs_idx, m, &out_idx);
        }
        if (!ok) {
            if (face)
                return changed_error(r, err);
            return out_put(r, line, n, err); /* an l line we do not understand: unchanged */
        }
        int64_t value = idx > 0 ? (int64_t)out_idx + 1 : -((int64_t)r->out_vt - (int64_t)out_idx);
        if (value != idx) {
            int rc = add_repl(r, count, (size_t)(a - line), (size_t)(b - line), value, err);
            if (rc < 0)
                return rc;
            count++;
        }
    }
    if (count == 0)
        return out_put(r, line, n, err);
    r->stats.faces_rewritten++;
    size_t at = 0;
    for (size_t j = 0; j < count; j++) {
        char num[24];
        size_t len = format_index(r->repl[j].value, num);
        int rc = out_put(r, line + at, r->repl[j].s - at, err);
        if (rc == 0)
            rc = out_put(r, num, len, err);
        if (rc < 0)
            return rc;
        at = r->repl[j].e;
    }
    return out_put(r, line + at, n - at, err);
}

static int pass2_line(struct run *r, const unsigned char *line, size_t n, struct vt_error *err)
{
    const unsigned char *cur = line, *end = line + n;
    struct tok kw;
    int rc;
    if (!r->any_mtllib && !r->mtllib_written) { /* the input names no MTL: name ours first */
        r->mtllib_written = true;
        rc = out_str(r, "mtllib ", err);
        if (rc == 0)
            rc = out_str(r, r->opt->mtllib, err);
        if (rc == 0)
            rc = out_str(r, line_ending(line, n), err);
        if (rc < 0)
            return rc;
    }
    if (!next_tok(&cur, end, &kw))
        return out_put(r, line, n, err);
    switch (keyword_of(&kw)) {
    case KW_VT:
        return pass2_vt(r, line, n, cur, err);
    case KW_F:
        return pass2_indices(r, line, n, cur, true, err);
    case KW_L:
        return pass2_indices(r, line, n, cur, false, err);
    case KW_USEMTL: {
        char *name;
        rc = usemtl_name(r, line, n, &name, err);
        if (rc < 0)
            return rc;
        r->mat = material_index(r, name);
        rc = out_put(r, line, (size_t)(kw.s - line), err); /* indentation */
        if (rc == 0)
            rc = out_str(r, "usemtl ", err);
        if (rc == 0)
            rc = out_str(r, r->opt->material, err);
        if (rc == 0 && n && line[n - 1] == '\n')
            rc = out_str(r, line_ending(line, n), err);
        return rc;
    }
    case KW_MTLLIB:
        if (r->mtllib_written) {
            rc = out_put(r, "# ", 2, err);
            return rc < 0 ? rc : out_put(r, line, n, err);
        }
        r->mtllib_written = true;
        rc = out_put(r, line, (size_t)(kw.s - line), err);
        if (rc == 0)
            rc = out_str(r, "mtllib ", err);
        if (rc == 0)
            rc = out_str(r, r->opt->mtllib, err);
        if (rc == 0 && n && line[n - 1] == '\n')
            rc = out_str(r, line_ending(line, n), err);
        return rc;
    default:
        return out_put(r, line, n, err);
    }
}

/* ---- driver ---- */

static int run_pass(struct run *r, const char *path, const void *mem, size_t size, int pass,
                    struct vt_error *err)
{
    int rc = src_open(&r->src, path, mem, size, r->opt->limits.max_line_bytes, err);
    if (rc < 0)
        return rc;
    const unsigned char *line = NULL;
    size_t n = 0;
    r->mat = MAT_NONE;
    while ((rc = src_next(&r->src, &line, &n, err)) == 1) {
        rc = pass == 1 ? pass1_line(r, line, n, err) : pass2_line(r, line, n, err);
        if (rc < 0)
            break;
    }
    if (rc == 0 && pass == 1)
        r->stats.lines = r->src.physical;
    if (rc == 0 && pass == 2 && (r->in_vt != r->nvt || r->src.physical != r->stats.lines))
        rc = changed_error(r, err);
    src_close(&r->src);
    return rc;
}

static int rewrite(const char *path, const void *mem, size_t size, const struct vt_layout *layout,
                   const struct vt_offset_options *opt, const struct vt_offset_sink *out,
                   struct vt_offset_stats *stats, struct vt_error *err)
{
    struct vt_offset_options defaults;
    if (!opt) {
        vt_offset_options_default(&defaults);
        opt = &defaults;
    }
    if (!layout || !out || !out->write || opt->digits > VT_UV_MAX_DIGITS || !opt->mtllib ||
        !opt->material)
        return vt_error_set(err, VT_ERR_ARG, "vt_offset_rewrite: bad arguments");
    struct run r = {0};
    r.layout = layout;
    r.opt = opt;
    r.out = out;
    r.digits = opt->digits ? opt->digits : vt_offset_default_digits(layout);
    r.stats.digits = r.digits;
    int rc = run_pass(&r, path, mem, size, 1, err);
    if (rc == 0)
        rc = number_outputs(&r, err);
    if (rc == 0) {
        r.obuf = malloc(OUT_CHUNK);
        if (!r.obuf)
            rc = vt_error_set(err, VT_ERR_NOMEM, "'%s': out of memory", path);
    }
    if (rc == 0) {
        r.stats.vt_lines = r.nvt;
        rc = run_pass(&r, path, mem, size, 2, err);
    }
    if (rc == 0 && !r.mtllib_written) { /* an empty input */
        rc = out_str(&r, "mtllib ", err);
        if (rc == 0)
            rc = out_str(&r, opt->mtllib, err);
        if (rc == 0)
            rc = out_str(&r, "\n", err);
    }
    if (rc == 0)
        rc = out_flush(&r, err);
    if (rc == 0 && stats)
        *stats = r.stats;
    free(r.uv);
    free(r.first);
    free(r.head);
    free(r.new_index);
    free(r.extra);
    free(r.mat_name);
    free(r.clean);
    free(r.repl);
    free(r.obuf);
    return rc;
}

int vt_offset_rewrite(const char *obj_path, const struct vt_layout *layout,
                      const struct vt_offset_options *opt, const struct vt_offset_sink *out,
                      struct vt_offset_stats *stats, struct vt_error *err)
{
    return rewrite(obj_path, NULL, 0, layout, opt, out, stats, err);
}

int vt_offset_rewrite_memory(const void *data, size_t size, const char *name,
                             const struct vt_layout *layout, const struct vt_offset_options *opt,
                             const struct vt_offset_sink *out, struct vt_offset_stats *stats,
                             struct vt_error *err)
{
    static const unsigned char empty[1];
    return rewrite(name, data ? data : empty, data ? size : 0, layout, opt, out, stats, err);
}
