/* Pass 1 of vt-offset (see vt_offset_scan.h). */
#include "internal/vt_offset_impl.h"

#include <stdlib.h>
#include <string.h>

#include "internal/vt_offset_tok.h"
#include "vt_checked.h"
#include "vt_error.h"
#include "vt_text.h"
#include "vt_uv_text.h"

static int grow_vt(struct vt_offset_run *r, struct vts_error *err)
{
    if (r->nvt >= r->opt->limits.max_vertices || r->nvt >= UINT32_MAX - 1)
        return vt_error_set(err, VTS_ERR_LIMIT, "'%s':%llu: more than %lu texcoords (the limit)",
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
        return vt_error_set(err, VTS_ERR_LIMIT, "'%s': too many texcoords", r->src.name);
    double *uv = realloc(r->uv, uv_bytes);
    if (uv)
        r->uv = uv;
    uint32_t *first = uv ? realloc(r->first, idx_bytes) : NULL;
    if (first)
        r->first = first;
    uint32_t *head = first ? realloc(r->head, idx_bytes) : NULL;
    if (!head)
        return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory for texcoords", r->src.name);
    r->head = head;
    r->cap = (uint32_t)cap;
    return 0;
}

static int count_vertex(struct vt_offset_run *r, uint64_t *count, const char *what,
                        struct vts_error *err)
{
    if (*count >= r->opt->limits.max_vertices)
        return vt_error_set(err, VTS_ERR_LIMIT, "'%s':%llu: more than %lu %s (the limit)",
                            r->src.name, (unsigned long long)r->src.line,
                            (unsigned long)r->opt->limits.max_vertices, what);
    (*count)++;
    return 0;
}

static int pass1_vt(struct vt_offset_run *r, const unsigned char *cur, const unsigned char *end,
                    struct vts_error *err)
{
    double vals[3] = {0, 0, 0};
    int n = 0;
    struct vt_offset_tok t;
    char text[64];
    while (vt_offset_tok_next(&cur, end, &t)) {
        if (n == 3)
            return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: 'vt' needs 1 to 3 numbers",
                                r->src.name, (unsigned long long)r->src.line);
        if (!vt_uv_parse((const char *)t.s, (size_t)(t.e - t.s), &vals[n]))
            return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: bad number '%s' in 'vt'",
                                r->src.name, (unsigned long long)r->src.line,
                                vt_offset_tok_text(&t, text));
        n++;
    }
    if (n == 0)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: 'vt' needs 1 to 3 numbers",
                            r->src.name, (unsigned long long)r->src.line);
    int rc = grow_vt(r, err);
    if (rc < 0)
        return rc;
    r->uv[2 * (size_t)r->nvt] = vals[0];
    r->uv[2 * (size_t)r->nvt + 1] = vals[1];
    r->first[r->nvt] = VT_OFFSET_NONE;
    r->head[r->nvt] = VT_OFFSET_NONE;
    r->nvt++;
    return 0;
}

/* A face corner with texcoords needs a material the layout has. */
static int check_material(struct vt_offset_run *r, struct vts_error *err)
{
    uint32_t m = r->mat;
    if (m == VT_OFFSET_MAT_NONE)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "'%s':%llu: face with texture coordinates before any usemtl",
                            r->src.name, (unsigned long long)r->src.line);
    if (m == VT_OFFSET_MAT_MISSING)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "'%s':%llu: material '%s' (usemtl on line %llu) is not in '%s'",
                            r->src.name, (unsigned long long)r->src.line, r->mat_name,
                            (unsigned long long)r->mat_line, r->opt->layout_name);
    return 0;
}

/* One face corner: v, v/vt, v//vn or v/vt/vn, checked like vt_obj; out[0..2] get the 0-based
 * position, texture and normal indices in out (VT_OFFSET_NONE when missing). */
static int pass1_corner(struct vt_offset_run *r, const struct vt_offset_tok *t, uint32_t out[3],
                        struct vts_error *err)
{
    static const char *const names[3] = {"vertex", "texture", "normal"};
    static const char *const plural[3] = {"vertices", "texcoords", "normals"};
    const uint64_t counts[3] = {r->nv, r->nvt, r->nvn};
    char text[64];
    const unsigned char *s = t->s;
    out[0] = out[1] = out[2] = VT_OFFSET_NONE;
    for (int kind = 0; kind < 3; kind++) {
        const unsigned char *e = memchr(s, '/', (size_t)(t->e - s));
        if (!e)
            e = t->e;
        if (e > s || kind == 0) {
            int64_t idx;
            if (!vt_text_index((const char *)s, (const char *)e, &idx))
                return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: bad %s index '%s'",
                                    r->src.name, (unsigned long long)r->src.line, names[kind],
                                    vt_offset_tok_text(t, text));
            if (idx == 0)
                return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                    "'%s':%llu: %s index 0 in '%s' (OBJ indices start at 1)",
                                    r->src.name, (unsigned long long)r->src.line, names[kind],
                                    vt_offset_tok_text(t, text));
            int64_t abs_idx = idx > 0 ? idx - 1 : (int64_t)counts[kind] + idx;
            if (abs_idx < 0 || abs_idx >= (int64_t)counts[kind])
                return vt_error_set(
                    err, VTS_ERR_BAD_INPUT,
                    "'%s':%llu: %s index %lld in '%s' out of range (%llu %s defined)", r->src.name,
                    (unsigned long long)r->src.line, names[kind], (long long)idx,
                    vt_offset_tok_text(t, text), (unsigned long long)counts[kind], plural[kind]);
            out[kind] = (uint32_t)abs_idx;
        }
        if (e == t->e)
            return 0;
        s = e + 1;
    }
    return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: bad face corner '%s'", r->src.name,
                        (unsigned long long)r->src.line, vt_offset_tok_text(t, text));
}

/* opt->used: the face just read uses the current material. */
static int mark_used(struct vt_offset_run *r, struct vts_error *err)
{
    struct vt_offset_used *u = r->opt->used;
    if (!u || r->mat == VT_OFFSET_MAT_NONE)
        return 0;
    if (r->mat_group != VT_CHART_NONE) {
        if (!r->slot_used && !(r->slot_used = calloc(r->layout->name_count + 1, 1)))
            return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory", r->src.name);
        r->slot_used[r->mat_group] = true;
        return 0;
    }
    if (r->unknown_line == r->mat_line) /* this usemtl's name is in already */
        return 0;
    if (u->unknown_count == r->unknown_cap) {
        uint32_t cap = r->unknown_cap ? 2 * r->unknown_cap : 8;
        char **grown = cap > (1u << 28) ? NULL : realloc(u->unknown, cap * sizeof *grown);
        if (!grown)
            return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory", r->src.name);
        u->unknown = grown;
        r->unknown_cap = cap;
    }
    if (!(u->unknown[u->unknown_count] = strdup(r->mat_name)))
        return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory", r->src.name);
    u->unknown_count++;
    r->unknown_line = r->mat_line;
    return 0;
}

static int pass1_face(struct vt_offset_run *r, const unsigned char *cur, const unsigned char *end,
                      struct vts_error *err)
{
    struct vt_offset_tok t;
    uint32_t corners = 0;
    bool any_vt = false;
    while (vt_offset_tok_next(&cur, end, &t)) {
        uint32_t idx[3];
        int rc = pass1_corner(r, &t, idx, err);
        if (rc < 0)
            return rc;
        if (idx[1] != VT_OFFSET_NONE && !any_vt) {
            any_vt = true;
            if ((rc = check_material(r, err)) < 0)
                return rc;
        }
        if (corners == r->corner_cap) {
            uint32_t cap = r->corner_cap ? 2 * r->corner_cap : 64;
            uint32_t *grown = cap > (1u << 28) ? NULL : realloc(r->corner, cap * 3 * sizeof *grown);
            if (!grown)
                return vt_error_set(err, VTS_ERR_NOMEM, "'%s':%llu: out of memory for a face",
                                    r->src.name, (unsigned long long)r->src.line);
            r->corner = grown;
            r->corner_cap = cap;
        }
        for (int k = 0; k < 3; k++)
            r->corner[3 * (size_t)corners + k] = idx[k];
        corners++;
    }
    if (corners < 3)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: face with %lu corners (needs 3)",
                            r->src.name, (unsigned long long)r->src.line, (unsigned long)corners);
    r->stats.faces++;
    if (!any_vt)
        r->stats.faces_without_vt++;
    int rc = mark_used(r, err);
    return rc < 0 ? rc : vt_offset_mesh_add_face(r, r->corner, corners, err);
}

int vt_offset_scan_line(struct vt_offset_run *r, const unsigned char *line, size_t n,
                        struct vts_error *err)
{
    const unsigned char *cur = line, *end = line + n;
    struct vt_offset_tok kw;
    if (!vt_offset_tok_next(&cur, end, &kw))
        return 0;
    switch (vt_offset_tok_keyword(&kw)) {
    case VT_OFFSET_KW_V:
        return count_vertex(r, &r->nv, "vertices", err);
    case VT_OFFSET_KW_VN:
        return count_vertex(r, &r->nvn, "normals", err);
    case VT_OFFSET_KW_VT:
        return pass1_vt(r, cur, end, err);
    case VT_OFFSET_KW_F:
        return pass1_face(r, cur, end, err);
    case VT_OFFSET_KW_USEMTL: {
        char *name;
        int rc = vt_offset_run_usemtl_name(r, line, n, &name, err);
        if (rc < 0)
            return rc;
        char *copy = strdup(name);
        if (!copy)
            return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory", r->src.name);
        free(r->mat_name);
        r->mat_name = copy;
        r->mat_line = r->src.line;
        r->mat = vt_offset_run_material(r, name);
        r->mat_group = vt_offset_run_name_slot(r, name);
        return 0;
    }
    case VT_OFFSET_KW_MTLLIB: {
        char *name;
        int rc = vt_offset_run_usemtl_name(r, line, n, &name, err);
        if (rc < 0)
            return rc;
        if (!*name)
            return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: mtllib without a file name",
                                r->src.name, (unsigned long long)r->src.line);
        r->any_mtllib = true;
        return 0;
    }
    default:
        return 0;
    }
}
