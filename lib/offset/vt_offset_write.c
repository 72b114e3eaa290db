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

/* "U V" of atlas coordinate (au, av). */
static int put_au_av(struct vt_offset_run *r, double au, double av, struct vts_error *err)
{
    int rc = put_coord(r, au, r->layout->width, err);
    if (rc == 0)
        rc = vt_offset_run_put(r, " ", 1, err);
    if (rc == 0)
        rc = put_coord(r, av, r->layout->height, err);
    return rc;
}

/* "U V" (and " W" from the original token) of vt i for key k (entry and move); on a pack
 * material's key the text of uv (u and v as written: s..e of the first two tokens). */
static int put_uv(struct vt_offset_run *r, uint32_t i, uint32_t k, const struct vt_offset_tok *uv,
                  const struct vt_offset_tok *w, struct vts_error *err)
{
    double au, av;
    const struct vt_offset_key *key = &r->keys[k];
    int rc;
    if (key->entry == VT_OFFSET_MAT_WANG) { /* a pack material's: the u v as written */
        rc = vt_offset_run_put(r, uv->s, (size_t)(uv->e - uv->s), err);
    } else {
        vt_offset_map(r, key->entry, r->uv[2 * (size_t)i] + key->du,
                      r->uv[2 * (size_t)i + 1] + key->dv, &au, &av);
        rc = put_au_av(r, au, av, err);
    }
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
    r->new_index[i] = (uint32_t)r->out_vt;
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
    struct vt_offset_tok uv = {t[0].s, t[count > 1 ? 1 : 0].e};
    const unsigned char *after = t[count - 1].e;
    int rc = vt_offset_run_put(r, line, (size_t)(t[0].s - line), err);
    if (rc == 0)
        rc = put_uv(r, i, r->first[i], &uv, w, err);
    if (rc == 0)
        rc = vt_offset_run_put(r, after, (size_t)(end - after), err);
    r->out_vt++;
    if (r->keys[r->first[i]].entry == VT_OFFSET_MAT_WANG)
        r->stats.vt_wang++;
    else
        r->stats.vt_rewritten++;
    bool terminated = n && line[n - 1] == '\n';
    const char *eol = line_ending(line, n);
    for (uint32_t k = r->head[i]; rc == 0 && k != VT_OFFSET_NONE; k = r->extra[k].next) {
        if (!terminated)
            rc = vt_offset_run_str(r, eol, err);
        if (rc == 0)
            rc = vt_offset_run_put(r, "vt ", 3, err);
        if (rc == 0)
            rc = put_uv(r, i, r->extra[k].key, &uv, w, err);
        if (rc == 0 && terminated)
            rc = vt_offset_run_str(r, eol, err);
        r->out_vt++;
        r->stats.vt_duplicated++;
    }
    return rc;
}

/* The output index (0-based) of input vt abs for key k (VT_OFFSET_NONE: the first copy). */
static bool output_index(const struct vt_offset_run *r, uint32_t abs_idx, uint32_t k, uint32_t *out)
{
    uint32_t n = 0;
    if (k != VT_OFFSET_NONE && r->first[abs_idx] != k) {
        uint32_t e = r->head[abs_idx];
        for (n = 1; e != VT_OFFSET_NONE && r->extra[e].key != k; n++)
            e = r->extra[e].next;
        if (e == VT_OFFSET_NONE)
            return false;
    }
    *out = r->new_index[abs_idx] + n;
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

/* The output index of index text [a, b) of kind 0 (v), 1 (vt) or 2 (vn) of a face with key k,
 * in the same style (positive or negative); false when it does not resolve. */
static bool renumber(const struct vt_offset_run *r, int kind, const unsigned char *a,
                     const unsigned char *b, uint32_t k, int64_t *idx, int64_t *value)
{
    const uint64_t in_count[3] = {r->in_v, r->in_vt, r->in_vn};
    const uint64_t out_count[3] = {r->out_v, r->out_vt, r->out_vn};
    if (!vt_text_index((const char *)a, (const char *)b, idx) || *idx == 0)
        return false;
    int64_t abs_idx = *idx > 0 ? *idx - 1 : (int64_t)in_count[kind] + *idx;
    if (abs_idx < 0 || abs_idx >= (int64_t)in_count[kind])
        return false;
    uint32_t out_idx = (uint32_t)abs_idx;
    if (kind == 1 && !output_index(r, (uint32_t)abs_idx, k, &out_idx))
        return false;
    if (kind != 1 && r->any_changed)
        out_idx = (kind == 0 ? r->v_out : r->vn_out)[abs_idx];
    *value = *idx > 0 ? (int64_t)out_idx + 1 : -((int64_t)out_count[kind] - (int64_t)out_idx);
    return true;
}

/* An f line (face: strict, kept, with key k) or l line (not checked by pass 1: left alone when an
 * index does not resolve; first copies): rewrites the indices that change. */
static int pass2_indices(struct vt_offset_run *r, const unsigned char *line, size_t n,
                         const unsigned char *cur, bool face, uint32_t k, struct vts_error *err)
{
    const unsigned char *end = line + n;
    size_t count = 0;
    struct vt_offset_tok t;
    while (vt_offset_tok_next(&cur, end, &t)) {
        const unsigned char *a = t.s;
        for (int kind = 0; kind < 3 && a <= t.e; kind++) {
            const unsigned char *b = memchr(a, '/', (size_t)(t.e - a));
            if (!b)
                b = t.e;
            if (a < b && (kind == 1 || r->any_changed)) {
                int64_t idx, value;
                if (!renumber(r, kind, a, b, k, &idx, &value)) {
                    if (face)
                        return vt_offset_run_changed_error(r, err);
                    return vt_offset_run_put(r, line, n, err); /* an l line we do not
                                                                  understand: unchanged */
                }
                if (value != idx) {
                    int rc = add_repl(r, count, (size_t)(a - line), (size_t)(b - line), value, err);
                    if (rc < 0)
                        return rc;
                    count++;
                }
            }
            if (b == t.e)
                break;
            a = b + 1;
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

/* "x y z" with every digit a double needs. */
static int put_xyz(struct vt_offset_run *r, const char *kw, const double p[3], const char *eol,
                   struct vts_error *err)
{
    char buf[128];
    int len = snprintf(buf, sizeof buf, "%s %.17g %.17g %.17g%s", kw, p[0], p[1], p[2], eol);
    return vt_offset_run_put(r, buf, (size_t)len, err);
}

static int put_index(struct vt_offset_run *r, uint64_t one_based, struct vts_error *err)
{
    char num[24];
    size_t len = format_index((int64_t)one_based, num);
    return vt_offset_run_put(r, num, len, err);
}

/* The normal of corner c of face fi, interpolated from the face's own (all present). */
static void corner_normal(const struct vt_offset_run *r, uint32_t fi, const struct vt_cut_corner *c,
                          double n[3])
{
    const struct vt_offset_faces *f = &r->faces;
    n[0] = n[1] = n[2] = 0;
    for (int k = 0; k < 3; k++) {
        if (c->src[k] == VT_CHART_NONE)
            continue;
        uint32_t vn = f->nrm[f->start[fi] + c->src[k]];
        size_t lo = 0, hi = r->normal_count;
        while (lo + 1 < hi) {
            size_t mid = lo + (hi - lo) / 2;
            if (r->normal_index[mid] <= vn)
                lo = mid;
            else
                hi = mid;
        }
        for (int a = 0; a < 3; a++)
            n[a] += c->w[k] * r->normals[3 * lo + a];
    }
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len > 0)
        for (int a = 0; a < 3; a++)
            n[a] /= len;
}

/* A cut or split face: its new positions, one vn and vt per corner, one f line per piece. */
static int pass2_changed(struct vt_offset_run *r, uint32_t fi, const unsigned char *line, size_t n,
                         struct vts_error *err)
{
    const struct vt_offset_faces *f = &r->faces;
    const struct vt_cut_result *c = &r->cut;
    const char *eol = line_ending(line, n);
    bool normals = true;
    for (uint64_t k = f->start[fi]; k < f->start[fi + 1]; k++)
        normals &= f->nrm[k] != VT_CHART_NONE;
    uint32_t entry = f->entry[fi];
    uint64_t p0 = c->face_poly[fi], p1 = c->face_poly[fi + 1];
    uint64_t k0 = c->poly_start[p0], k1 = c->poly_start[p1];
    bool uv = k1 > k0 && c->corners[k0].has_uv && entry < r->layout->entry_count;
    int rc = 0;
    for (uint64_t k = k0; rc == 0 && k < k1; k++) {
        uint32_t pos = c->corners[k].pos;
        if (pos < r->nv || r->new_pos_out[pos - r->nv] != VT_OFFSET_NONE)
            continue;
        r->new_pos_out[pos - r->nv] = (uint32_t)r->out_v++;
        r->stats.positions_added++; /* only the new positions a piece uses are written */
        rc = put_xyz(r, "v", r->new_pos + 3 * (size_t)(pos - r->nv), eol, err);
    }
    uint64_t first_vn = r->out_vn, first_vt = r->out_vt;
    for (uint64_t k = k0; rc == 0 && normals && k < k1; k++) {
        double nn[3];
        corner_normal(r, fi, &c->corners[k], nn);
        rc = put_xyz(r, "vn", nn, eol, err);
        r->out_vn++;
        r->stats.vn_added++;
    }
    for (uint64_t k = k0; rc == 0 && uv && k < k1; k++) {
        double au, av;
        vt_offset_map(r, entry, c->corners[k].u, c->corners[k].v, &au, &av);
        rc = vt_offset_run_put(r, "vt ", 3, err);
        if (rc == 0)
            rc = put_au_av(r, au, av, err);
        if (rc == 0)
            rc = vt_offset_run_str(r, eol, err);
        r->out_vt++;
        r->stats.vt_added++;
    }
    for (uint64_t p = p0; rc == 0 && p < p1; p++) {
        rc = vt_offset_run_put(r, "f", 1, err);
        for (uint64_t k = c->poly_start[p]; rc == 0 && k < c->poly_start[p + 1]; k++) {
            uint32_t pos = c->corners[k].pos;
            uint64_t vo = pos < r->nv ? r->v_out[pos] : r->new_pos_out[pos - r->nv];
            rc = vt_offset_run_put(r, " ", 1, err);
            if (rc == 0)
                rc = put_index(r, vo + 1, err);
            if (rc == 0 && (uv || normals))
                rc = vt_offset_run_put(r, "/", 1, err);
            if (rc == 0 && uv)
                rc = put_index(r, first_vt + (k - k0) + 1, err);
            if (rc == 0 && normals)
                rc = vt_offset_run_put(r, "/", 1, err);
            if (rc == 0 && normals)
                rc = put_index(r, first_vn + (k - k0) + 1, err);
        }
        bool last = p + 1 == p1;
        if (rc == 0 && (!last || (n && line[n - 1] == '\n')))
            rc = vt_offset_run_str(r, eol, err);
        r->stats.faces_written++;
    }
    return rc;
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
    case VT_OFFSET_KW_V:
        if (r->any_changed && r->in_v < r->nv)
            r->v_out[r->in_v] = (uint32_t)r->out_v;
        r->in_v++;
        r->out_v++;
        return vt_offset_run_put(r, line, n, err);
    case VT_OFFSET_KW_VN:
        if (r->any_changed && r->in_vn < r->nvn)
            r->vn_out[r->in_vn] = (uint32_t)r->out_vn;
        r->in_vn++;
        r->out_vn++;
        return vt_offset_run_put(r, line, n, err);
    case VT_OFFSET_KW_VT:
        return pass2_vt(r, line, n, cur, err);
    case VT_OFFSET_KW_F: {
        if (r->in_face >= r->faces.count)
            return vt_offset_run_changed_error(r, err);
        uint32_t fi = r->in_face++;
        if (r->cut.changed[fi])
            return pass2_changed(r, fi, line, n, err);
        return pass2_indices(r, line, n, cur, true, r->face_key[fi], err);
    }
    case VT_OFFSET_KW_L:
        return pass2_indices(r, line, n, cur, false, VT_OFFSET_NONE, err);
    case VT_OFFSET_KW_USEMTL: {
        char *name;
        rc = vt_offset_run_usemtl_name(r, line, n, &name, err);
        if (rc < 0)
            return rc;
        r->mat = vt_offset_run_material(r, name);
        if (!r->opt->material) /* each face keeps its material */
            return vt_offset_run_put(r, line, n, err);
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
