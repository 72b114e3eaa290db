/* Pass 2 of vt-offset (see vt_offset_write.h). */
#include "internal/vt_offset_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_offset_tok.h"
#include "vt_error.h"
#include "vt_text.h"
#include "vt_uv_text.h"

static const char *line_ending(const unsigned char *line, size_t n)
{
    if (n >= 2 && line[n - 1] == '\n' && line[n - 2] == '\r')
        return "\r\n";
    return "\n";
}

/* Writes one coordinate and measures its round-off against x, scaled to texels. */
static int put_coord(struct vt_offset_run *r, double x, double texels, struct vts_error *err)
{
    char buf[VT_UV_FORMAT_SIZE];
    size_t n = vt_uv_format(x, r->digits, buf);
    double back;
    if (n == 0 || !vt_uv_parse(buf, n, &back))
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: cannot write coordinate %.17g",
                            r->src.name, (unsigned long long)r->src.line, x);
    double e = fabs(back - x) * texels;
    double e32 = fabs((double)(float)back - x) * texels;
    if (e > r->stats.max_error)
        r->stats.max_error = e;
    if (e32 > r->stats.max_error_f32) {
        r->stats.max_error_f32 = e32;
        r->stats.max_error_f32_line = r->src.line;
    }
    return vt_offset_run_put(r, buf, n, err);
}

/* "U V" (and " W" from the original token) of vt i for material m. */
static int put_uv(struct vt_offset_run *r, uint32_t i, uint32_t m, const struct vt_offset_tok *w,
                  struct vts_error *err)
{
    double au, av;
    const struct vt_layout_entry *e = &r->layout->entries[m];
    if (vt_offset_run_constant_entry(r->layout, e)) {
        au = (e->x + e->width / 2.0) / r->layout->width;
        av = 1.0 - (e->y + e->height / 2.0) / r->layout->height;
    } else {
        vt_layout_map_uv(r->layout, e, r->uv[2 * (size_t)i], r->uv[2 * (size_t)i + 1], &au, &av);
    }
    int rc = put_coord(r, au, r->layout->width, err);
    if (rc == 0)
        rc = vt_offset_run_put(r, " ", 1, err);
    if (rc == 0)
        rc = put_coord(r, av, r->layout->height, err);
    if (rc == 0 && w) {
        rc = vt_offset_run_put(r, " ", 1, err);
        if (rc == 0)
            rc = vt_offset_run_put(r, w->s, (size_t)(w->e - w->s), err);
    }
    return rc;
}

static int pass2_vt(struct vt_offset_run *r, const unsigned char *line, size_t n,
                    const unsigned char *cur, struct vts_error *err)
{
    if (r->in_vt >= r->nvt)
        return vt_offset_run_changed_error(r, err);
    uint32_t i = r->in_vt++;
    if (r->first[i] == VT_OFFSET_NONE) {
        r->stats.vt_unused++;
        r->out_vt++;
        return vt_offset_run_put(r, line, n, err);
    }
    const unsigned char *end = line + n;
    struct vt_offset_tok t[3];
    int count = 0;
    while (count < 3 && vt_offset_tok_next(&cur, end, &t[count]))
        count++;
    if (count == 0)
        return vt_offset_run_changed_error(r, err);
    const struct vt_offset_tok *w = count == 3 ? &t[2] : NULL;
    const unsigned char *after = t[count - 1].e;
    int rc = vt_offset_run_put(r, line, (size_t)(t[0].s - line), err);
    if (rc == 0)
        rc = put_uv(r, i, r->first[i], w, err);
    if (rc == 0)
        rc = vt_offset_run_put(r, after, (size_t)(end - after), err);
    r->out_vt++;
    r->stats.vt_rewritten++;
    bool terminated = n && line[n - 1] == '\n';
    const char *eol = line_ending(line, n);
    for (uint32_t k = r->head[i]; rc == 0 && k != VT_OFFSET_NONE; k = r->extra[k].next) {
        if (!terminated)
            rc = vt_offset_run_str(r, eol, err);
        if (rc == 0)
            rc = vt_offset_run_put(r, "vt ", 3, err);
        if (rc == 0)
            rc = put_uv(r, i, r->extra[k].mat, w, err);
        if (rc == 0 && terminated)
            rc = vt_offset_run_str(r, eol, err);
        r->out_vt++;
        r->stats.vt_duplicated++;
    }
    return rc;
}

/* The output index (0-based) of input vt abs for material m (VT_OFFSET_NONE: the first copy). */
static bool output_index(const struct vt_offset_run *r, uint32_t abs_idx, uint32_t m, uint32_t *out)
{
    uint32_t k = 0;
    if (m != VT_OFFSET_NONE && r->first[abs_idx] != m) {
        uint32_t e = r->head[abs_idx];
        for (k = 1; e != VT_OFFSET_NONE && r->extra[e].mat != m; k++)
            e = r->extra[e].next;
        if (e == VT_OFFSET_NONE)
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

static int add_repl(struct vt_offset_run *r, size_t count, size_t s, size_t e, int64_t value,
                    struct vts_error *err)
{
    if (count == r->repl_cap) {
        size_t cap = r->repl_cap ? r->repl_cap * 2 : 64;
        struct vt_offset_repl *grown = realloc(r->repl, cap * sizeof *grown);
        if (!grown)
            return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory for a face", r->src.name);
        r->repl = grown;
        r->repl_cap = cap;
    }
    r->repl[count] = (struct vt_offset_repl){s, e, value};
    return 0;
}

/* An f line (face: strict, material m) or l line (not checked by pass 1: left alone when an index
 * does not resolve; first copies): rewrites the texture indices that change. */
static int pass2_indices(struct vt_offset_run *r, const unsigned char *line, size_t n,
                         const unsigned char *cur, bool face, struct vts_error *err)
{
    const unsigned char *end = line + n;
    uint32_t m = face ? r->mat : VT_OFFSET_NONE;
    size_t count = 0;
    struct vt_offset_tok t;
    while (vt_offset_tok_next(&cur, end, &t)) {
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
        bool ok = vt_text_index((const char *)a, (const char *)b, &idx) && idx != 0;
        if (ok) {
            abs_idx = idx > 0 ? idx - 1 : (int64_t)r->in_vt + idx;
            ok = abs_idx >= 0 && abs_idx < (int64_t)r->in_vt &&
                 output_index(r, (uint32_t)abs_idx, m, &out_idx);
        }
        if (!ok) {
            if (face)
                return vt_offset_run_changed_error(r, err);
            return vt_offset_run_put(r, line, n,
                                     err); /* an l line we do not understand: unchanged */
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
        return vt_offset_run_put(r, line, n, err);
    r->stats.faces_rewritten++;
    size_t at = 0;
    for (size_t j = 0; j < count; j++) {
        char num[24];
        size_t len = format_index(r->repl[j].value, num);
        int rc = vt_offset_run_put(r, line + at, r->repl[j].s - at, err);
        if (rc == 0)
            rc = vt_offset_run_put(r, num, len, err);
        if (rc < 0)
            return rc;
        at = r->repl[j].e;
    }
    return vt_offset_run_put(r, line + at, n - at, err);
}

int vt_offset_write_line(struct vt_offset_run *r, const unsigned char *line, size_t n,
                         struct vts_error *err)
{
    const unsigned char *cur = line, *end = line + n;
    struct vt_offset_tok kw;
    int rc;
    if (!r->any_mtllib && !r->mtllib_written) { /* the input names no MTL: name ours first */
        r->mtllib_written = true;
        rc = vt_offset_run_str(r, "mtllib ", err);
        if (rc == 0)
            rc = vt_offset_run_str(r, r->opt->mtllib, err);
        if (rc == 0)
            rc = vt_offset_run_str(r, line_ending(line, n), err);
        if (rc < 0)
            return rc;
    }
    if (!vt_offset_tok_next(&cur, end, &kw))
        return vt_offset_run_put(r, line, n, err);
    switch (vt_offset_tok_keyword(&kw)) {
    case VT_OFFSET_KW_VT:
        return pass2_vt(r, line, n, cur, err);
    case VT_OFFSET_KW_F:
        return pass2_indices(r, line, n, cur, true, err);
    case VT_OFFSET_KW_L:
        return pass2_indices(r, line, n, cur, false, err);
    case VT_OFFSET_KW_USEMTL: {
        char *name;
        rc = vt_offset_run_usemtl_name(r, line, n, &name, err);
        if (rc < 0)
            return rc;
        r->mat = vt_offset_run_material(r, name);
        rc = vt_offset_run_put(r, line, (size_t)(kw.s - line), err); /* indentation */
        if (rc == 0)
            rc = vt_offset_run_str(r, "usemtl ", err);
        if (rc == 0)
            rc = vt_offset_run_str(r, r->opt->material, err);
        if (rc == 0 && n && line[n - 1] == '\n')
            rc = vt_offset_run_str(r, line_ending(line, n), err);
        return rc;
    }
    case VT_OFFSET_KW_MTLLIB:
        if (r->mtllib_written) {
            rc = vt_offset_run_put(r, "# ", 2, err);
            return rc < 0 ? rc : vt_offset_run_put(r, line, n, err);
        }
        r->mtllib_written = true;
        rc = vt_offset_run_put(r, line, (size_t)(kw.s - line), err);
        if (rc == 0)
            rc = vt_offset_run_str(r, "mtllib ", err);
        if (rc == 0)
            rc = vt_offset_run_str(r, r->opt->mtllib, err);
        if (rc == 0 && n && line[n - 1] == '\n')
            rc = vt_offset_run_str(r, line_ending(line, n), err);
        return rc;
    default:
        return vt_offset_run_put(r, line, n, err);
    }
}
