/* vt-offset between its passes: the faces pass 1 kept, their charts and whole-repeat moves
 * (lib/chart/vt_chart.h), the cuts on wrap entries (vt_cut.h), the output copies (keys) of every
 * vt with the coverage checks, and the positions and normals new vertices interpolate (see
 * internal/vt_offset_impl.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_offset_impl.h"
#include "internal/vt_offset_src.h"
#include "internal/vt_offset_tok.h"
#include "vt_chart.h"
#include "vt_checked.h"
#include "vt_cut.h"
#include "vt_error.h"
#include "vt_uv_text.h"

/* 0 or VTS_ERR_NOMEM: vt_array_grow() from 1024 elements. */
static int grow(void **p, size_t *cap, size_t need, size_t elem)
{
    return vt_array_grow(p, cap, need, elem, 1024) ? 0 : VTS_ERR_NOMEM;
}

int vt_offset_mesh_add_face(struct vt_offset_run *r, const uint32_t *corners, uint32_t corner_count,
                            struct vts_error *err)
{
    struct vt_offset_faces *f = &r->faces;
    size_t need_corners, fc = f->face_cap, cc = f->corner_cap;
    if (f->count >= UINT32_MAX - 2 || !vt_size_add((size_t)f->corners, corner_count, &need_corners))
        return vt_error_set(err, VTS_ERR_LIMIT, "'%s':%llu: too many faces", r->name,
                            (unsigned long long)r->src.line);
    size_t need_faces = (size_t)f->count + 2;
    if (grow((void **)&f->start, &fc, need_faces, sizeof *f->start) ||
        (fc = f->face_cap, grow((void **)&f->group, &fc, need_faces, sizeof *f->group)) ||
        (fc = f->face_cap, grow((void **)&f->entry, &fc, need_faces, sizeof *f->entry)) ||
        (fc = f->face_cap, grow((void **)&f->line, &fc, need_faces, sizeof *f->line)) ||
        grow((void **)&f->pos, &cc, need_corners, sizeof *f->pos) ||
        (cc = f->corner_cap, grow((void **)&f->tex, &cc, need_corners, sizeof *f->tex)) ||
        (cc = f->corner_cap, grow((void **)&f->nrm, &cc, need_corners, sizeof *f->nrm)))
        return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory for the faces", r->name);
    f->face_cap = fc;
    f->corner_cap = cc;
    if (f->count == 0)
        f->start[0] = 0;
    bool any_vt = false;
    for (uint32_t i = 0; i < corner_count; i++) {
        size_t c = (size_t)f->corners + i;
        f->pos[c] = corners[3 * (size_t)i];
        f->tex[c] = corners[3 * (size_t)i + 1] == VT_OFFSET_NONE ? VT_CHART_NONE
                                                                 : corners[3 * (size_t)i + 1];
        f->nrm[c] = corners[3 * (size_t)i + 2] == VT_OFFSET_NONE ? VT_CHART_NONE
                                                                 : corners[3 * (size_t)i + 2];
        any_vt |= f->tex[c] != VT_CHART_NONE;
    }
    f->corners = need_corners;
    f->group[f->count] = any_vt ? r->mat_group : VT_CHART_NONE;
    f->entry[f->count] = r->mat;
    f->line[f->count] = r->src.line;
    f->count++;
    f->start[f->count] = f->corners;
    return 0;
}

void vt_offset_map(const struct vt_offset_run *r, uint32_t entry, double u, double v, double *au,
                   double *av)
{
    const struct vt_layout_entry *e = &r->layout->entries[entry];
    if (vt_offset_run_constant_entry(r->layout, e)) {
        *au = (e->x + e->width / 2.0) / r->layout->width;
        *av = 1.0 - (e->y + e->height / 2.0) / r->layout->height;
        return;
    }
    vt_layout_map_uv(r->layout, e, u, v, au, av);
}

/* ---- keys: one output copy of a vt per (entry, move) its kept faces use ---- */

static int key_of(struct vt_offset_run *r, uint32_t entry, double du, double dv, uint32_t *out,
                  struct vts_error *err)
{
    /* few distinct moves per scene in practice; a linear probe over the last keys first */
    for (uint32_t k = r->key_count; k-- > 0 && r->key_count - k <= 64;)
        if (r->keys[k].entry == entry && r->keys[k].du == du && r->keys[k].dv == dv) {
            *out = k;
            return 0;
        }
    for (uint32_t k = 0; k + 64 < r->key_count; k++)
        if (r->keys[k].entry == entry && r->keys[k].du == du && r->keys[k].dv == dv) {
            *out = k;
            return 0;
        }
    size_t cap = r->key_cap;
    if (r->key_count >= UINT32_MAX - 1 ||
        grow((void **)&r->keys, &cap, (size_t)r->key_count + 1, sizeof *r->keys))
        return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory for the moves", r->name);
    r->key_cap = (uint32_t)(cap > UINT32_MAX ? UINT32_MAX : cap);
    r->keys[r->key_count] = (struct vt_offset_key){entry, du, dv};
    *out = r->key_count++;
    return 0;
}

static int covered_error(struct vt_offset_run *r, uint64_t line, uint32_t vt, double u, double v,
                         double du, double dv, uint32_t entry, struct vts_error *err)
{
    const struct vt_layout_entry *e = &r->layout->entries[entry];
    double u0 = e->origin_u + (double)e->crop_x / e->width;
    double u1 = e->origin_u + (double)(e->crop_x + e->crop_width) / e->width;
    double v1 = e->origin_v + e->repeat_v - (double)e->crop_y / e->height;
    double v0 = e->origin_v + e->repeat_v - (double)(e->crop_y + e->crop_height) / e->height;
    char which[48] = "a cut corner", moved[64] = "";
    if (vt != VT_OFFSET_NONE)
        snprintf(which, sizeof which, "vt %lu", (unsigned long)vt + 1);
    if (du != 0 || dv != 0)
        snprintf(moved, sizeof moved, ", moved by %g %g", du + 0.0, dv + 0.0);
    return vt_error_set(err, VTS_ERR_BAD_INPUT,
                        "'%s':%llu: %s (%.9g %.9g%s) is outside the UV range of material '%s' in "
                        "'%s' (u %.6g..%.6g, v %.6g..%.6g): rebuild the atlas from this OBJ",
                        r->name, (unsigned long long)line, which, u - du, v - dv, moved, e->name,
                        r->opt->layout_name, u0, u1, v0, v1);
}

/* Records that a kept face with key k uses vt i. */
static int use_vt(struct vt_offset_run *r, uint32_t i, uint32_t k, struct vts_error *err)
{
    if (r->first[i] == k)
        return 0;
    if (r->first[i] == VT_OFFSET_NONE) {
        r->first[i] = k;
        return 0;
    }
    uint32_t prev = VT_OFFSET_NONE;
    for (uint32_t x = r->head[i]; x != VT_OFFSET_NONE; prev = x, x = r->extra[x].next)
        if (r->extra[x].key == k)
            return 0;
    if (r->extra_count == r->extra_cap) {
        if (r->extra_cap >= UINT32_MAX / 2)
            return vt_error_set(err, VTS_ERR_LIMIT, "'%s': too many shared texcoords", r->name);
        uint32_t cap = r->extra_cap ? r->extra_cap * 2 : 256;
        struct vt_offset_extra *grown = realloc(r->extra, (size_t)cap * sizeof *grown);
        if (!grown)
            return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory for shared texcoords",
                                r->name);
        r->extra = grown;
        r->extra_cap = cap;
    }
    uint32_t at = r->extra_count++;
    r->extra[at] = (struct vt_offset_extra){k, VT_OFFSET_NONE};
    if (prev == VT_OFFSET_NONE)
        r->head[i] = at;
    else
        r->extra[prev].next = at;
    return 0;
}

/* Keys of the kept faces and every vt's copies; the coverage of every written coordinate. */
static int assign_keys(struct vt_offset_run *r, struct vts_error *err)
{
    const struct vt_offset_faces *f = &r->faces;
    const struct vt_cut_result *c = &r->cut;
    for (uint32_t fi = 0; fi < f->count; fi++) {
        r->face_key[fi] = VT_OFFSET_NONE;
        uint32_t entry = f->entry[fi];
        if (entry == VT_OFFSET_MAT_WANG) {
            /* a pack material: its vt are copied as they are (a copy of their own when a face
             * of an atlas material shares them) */
            int rc = key_of(r, VT_OFFSET_MAT_WANG, 0, 0, &r->face_key[fi], err);
            for (uint64_t k = f->start[fi]; rc == 0 && k < f->start[fi + 1]; k++)
                if (f->tex[k] != VT_CHART_NONE)
                    rc = use_vt(r, f->tex[k], r->face_key[fi], err);
            if (rc < 0)
                return rc;
            continue;
        }
        if (f->group[fi] == VT_CHART_NONE || entry >= r->layout->entry_count)
            continue; /* no texcoords (or nothing to map them with: refused in pass 1) */
        const struct vt_layout_entry *e = &r->layout->entries[entry];
        bool constant = vt_offset_run_constant_entry(r->layout, e);
        if (c->changed[fi]) {
            for (uint64_t p = c->face_poly[fi]; p < c->face_poly[fi + 1]; p++)
                for (uint64_t k = c->poly_start[p]; k < c->poly_start[p + 1] && !constant; k++) {
                    const struct vt_cut_corner *cc = &c->corners[k];
                    if (cc->has_uv && !vt_layout_uv_covered(e, cc->u, cc->v))
                        return covered_error(r, f->line[fi], VT_OFFSET_NONE, cc->u, cc->v, 0, 0,
                                             entry, err);
                }
            continue;
        }
        double du = c->face_shift[2 * (size_t)fi], dv = c->face_shift[2 * (size_t)fi + 1];
        uint32_t key = VT_OFFSET_NONE;
        int rc = key_of(r, entry, du, dv, &key, err);
        if (rc < 0)
            return rc;
        r->face_key[fi] = key;
        for (uint64_t k = f->start[fi]; k < f->start[fi + 1]; k++) {
            uint32_t t = f->tex[k];
            if (t == VT_CHART_NONE)
                continue;
            double u = r->uv[2 * (size_t)t] + du, v = r->uv[2 * (size_t)t + 1] + dv;
            if (!constant && !vt_layout_uv_covered(e, u, v))
                return covered_error(r, f->line[fi], t, u, v, du, dv, entry, err);
            if ((rc = use_vt(r, t, key, err)) < 0)
                return rc;
        }
    }
    return 0;
}

/* ---- the values new vertices interpolate ---- */

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

/* Sorts and dedupes list[0 .. *n). */
static void sort_unique(uint32_t *list, size_t *n)
{
    if (*n == 0)
        return;
    qsort(list, *n, sizeof *list, cmp_u32);
    size_t k = 1;
    for (size_t i = 1; i < *n; i++)
        if (list[i] != list[k - 1])
            list[k++] = list[i];
    *n = k;
}

/* Index of value in the sorted list (it is there). */
static size_t find_u32(const uint32_t *list, size_t n, uint32_t value)
{
    size_t lo = 0, hi = n;
    while (lo + 1 < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (list[mid] <= value)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* Parses up to 3 numbers of a v or vn line into out (missing ones 0). */
static int parse_xyz(struct vt_offset_run *r, const unsigned char *cur, const unsigned char *end,
                     double out[3], struct vts_error *err)
{
    struct vt_offset_tok t;
    out[0] = out[1] = out[2] = 0;
    for (int n = 0; n < 3 && vt_offset_tok_next(&cur, end, &t); n++) {
        char text[64];
        if (!vt_uv_parse((const char *)t.s, (size_t)(t.e - t.s), &out[n]))
            return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: bad number '%s'", r->name,
                                (unsigned long long)r->src.line, vt_offset_tok_text(&t, text));
    }
    return 0;
}

/* One more pass over the file: the values of the v and vn in the sorted lists (nv_need and
 * nn_need long) into pv and pn (3 doubles each). */
static int read_values(struct vt_offset_run *r, const char *path, const void *mem, size_t size,
                       const uint32_t *v_need, size_t nv_need, double *pv, const uint32_t *n_need,
                       size_t nn_need, double *pn, struct vts_error *err)
{
    int rc = vt_offset_src_open(&r->src, path, mem, size, r->opt->limits.max_line_bytes, err);
    if (rc < 0)
        return rc;
    const unsigned char *line = NULL;
    size_t n = 0, kv = 0, kn = 0;
    uint64_t iv = 0, in = 0;
    while ((kv < nv_need || kn < nn_need) &&
           (rc = vt_offset_src_next(&r->src, &line, &n, err)) == 1) {
        const unsigned char *cur = line, *end = line + n;
        struct vt_offset_tok kw;
        rc = 0;
        if (!vt_offset_tok_next(&cur, end, &kw))
            continue;
        enum vt_offset_keyword k = vt_offset_tok_keyword(&kw);
        if (k == VT_OFFSET_KW_V) {
            if (kv < nv_need && v_need[kv] == iv)
                rc = parse_xyz(r, cur, end, pv + 3 * kv++, err);
            iv++;
        } else if (k == VT_OFFSET_KW_VN) {
            if (kn < nn_need && n_need[kn] == in)
                rc = parse_xyz(r, cur, end, pn + 3 * kn++, err);
            in++;
        }
        if (rc < 0)
            break;
    }
    if (rc >= 0 && (kv < nv_need || kn < nn_need))
        rc = vt_offset_run_changed_error(r, err);
    vt_offset_src_close(&r->src);
    return rc < 0 ? rc : 0;
}

/* New positions (r->new_pos) and the normals replaced faces interpolate (r->normals: 3 per vn,
 * only the needed ones filled). */
static int interpolate(struct vt_offset_run *r, const char *path, const void *mem, size_t size,
                       struct vts_error *err)
{
    const struct vt_cut_result *c = &r->cut;
    const struct vt_offset_faces *f = &r->faces;
    size_t nv_need = 0, nn_need = 0, vcap = (size_t)c->vertex_count * 3 + 1, ncap = 0;
    for (uint32_t fi = 0; fi < f->count; fi++)
        if (c->changed[fi])
            ncap += (size_t)(f->start[fi + 1] - f->start[fi]);
    uint32_t *v_need = malloc(vcap * sizeof *v_need);
    uint32_t *n_need = malloc((ncap + 1) * sizeof *n_need);
    double *pv = NULL, *pn = NULL;
    int rc = 0;
    if (!v_need || !n_need)
        goto nomem;
    for (uint32_t j = 0; j < c->vertex_count; j++)
        for (int k = 0; k < 3; k++)
            if (c->vertices[j].pos[k] != VT_CHART_NONE)
                v_need[nv_need++] = c->vertices[j].pos[k];
    for (uint32_t fi = 0; fi < f->count; fi++)
        if (c->changed[fi])
            for (uint64_t k = f->start[fi]; k < f->start[fi + 1]; k++)
                if (f->nrm[k] != VT_CHART_NONE)
                    n_need[nn_need++] = f->nrm[k];
    sort_unique(v_need, &nv_need);
    sort_unique(n_need, &nn_need);
    pv = malloc((nv_need + 1) * 3 * sizeof *pv);
    pn = malloc((nn_need + 1) * 3 * sizeof *pn);
    r->new_pos = malloc(((size_t)c->vertex_count + 1) * 3 * sizeof *r->new_pos);
    if (!pv || !pn || !r->new_pos)
        goto nomem;
    rc = read_values(r, path, mem, size, v_need, nv_need, pv, n_need, nn_need, pn, err);
    if (rc < 0)
        goto out;
    for (uint32_t j = 0; j < c->vertex_count; j++) {
        const struct vt_cut_vertex *x = &c->vertices[j];
        double *o = r->new_pos + 3 * (size_t)j;
        o[0] = o[1] = o[2] = 0;
        for (int k = 0; k < 3; k++) {
            if (x->pos[k] == VT_CHART_NONE)
                continue;
            const double *p = pv + 3 * find_u32(v_need, nv_need, x->pos[k]);
            for (int a = 0; a < 3; a++)
                o[a] += x->w[k] * p[a];
        }
    }
    if (nn_need) { /* a sparse copy indexed by vn: 3 doubles per needed one */
        r->normal_index = n_need;
        r->normal_count = nn_need;
        r->normals = pn;
        n_need = NULL;
        pn = NULL;
    }
out:
    free(v_need);
    free(n_need);
    free(pv);
    free(pn);
    return rc;
nomem:
    rc = vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory for the cut vertices", r->name);
    goto out;
}

/* lib/chart does not know the file: its messages ("cannot cut face 3 along the UV grid: it spans
 * 2000000 x 1 cells (at most 1048576)") get the input's name first, as every message of the
 * rewriter has. */
static int name_chart_error(const struct vt_offset_run *r, int rc, struct vts_error *err)
{
    if (!err)
        return rc;
    char reason[sizeof err->message];
    snprintf(reason, sizeof reason, "%s", err->message);
    return vt_error_set(err, rc, "'%s': %s", r->name, reason);
}

int vt_offset_mesh_resolve(struct vt_offset_run *r, const char *path, const void *mem, size_t size,
                           struct vts_error *err)
{
    struct vt_offset_faces *f = &r->faces;
    size_t idx_bytes;
    if (!vt_size_mul((size_t)r->nvt + 1, sizeof(uint32_t), &idx_bytes))
        return vt_error_set(err, VTS_ERR_LIMIT, "'%s': too many texcoords", r->name);
    r->new_index = malloc(idx_bytes);
    r->face_key = malloc(((size_t)f->count + 1) * sizeof *r->face_key);
    uint32_t *chart = malloc(((size_t)f->count + 1) * sizeof *chart);
    uint8_t *wrap = malloc((size_t)f->count + 1);
    double *shift = malloc(((size_t)f->count + 1) * 2 * sizeof *shift);
    struct vt_chart_box *boxes = NULL;
    int rc = 0;
    if (!r->new_index || !r->face_key || !chart || !wrap || !shift) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory for the charts", r->name);
        goto out;
    }
    if (f->count == 0) {
        f->start = calloc(1, sizeof *f->start);
        if (!f->start) {
            rc = vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory", r->name);
            goto out;
        }
    }
    struct vt_chart_mesh m = {.face_count = f->count,
                              .face_start = f->start,
                              .pos = f->pos,
                              .tex = f->tex,
                              .nrm = f->nrm,
                              .group = f->group,
                              .uv = r->uv,
                              .position_count = (uint32_t)r->nv,
                              .texcoord_count = r->nvt};
    uint32_t nc = 0;
    if ((rc = vt_chart_label(&m, chart, &nc, err)) < 0) {
        rc = name_chart_error(r, rc, err);
        goto out;
    }
    boxes = malloc(((size_t)nc + 1) * sizeof *boxes);
    if (!boxes) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory for the charts", r->name);
        goto out;
    }
    vt_chart_boxes(&m, chart, nc, boxes);
    /* A chart its entry covers where it is (a layout of vt-atlas 0.1 with origin -1, or a chart
     * on the second of two replicated copies) stays there; any other is moved. */
    for (uint32_t fi = 0; fi < f->count; fi++) {
        uint32_t ch = chart[fi], e = f->entry[fi];
        if (ch == VT_CHART_NONE || boxes[ch].faces == 0 || e >= r->layout->entry_count)
            continue;
        struct vt_chart_box *b = &boxes[ch];
        const struct vt_layout_entry *en = &r->layout->entries[e];
        if ((b->du != 0 || b->dv != 0) && vt_layout_uv_covered(en, b->umin, b->vmin) &&
            vt_layout_uv_covered(en, b->umax, b->vmax))
            b->du = b->dv = 0;
        b->faces = 0; /* decided */
    }
    r->stats.charts = nc;
    for (uint32_t i = 0; i < nc; i++)
        r->stats.charts_moved += boxes[i].du != 0 || boxes[i].dv != 0;
    for (uint32_t fi = 0; fi < f->count; fi++) {
        uint32_t ch = chart[fi], e = f->entry[fi];
        shift[2 * (size_t)fi] = ch == VT_CHART_NONE ? 0 : boxes[ch].du;
        shift[2 * (size_t)fi + 1] = ch == VT_CHART_NONE ? 0 : boxes[ch].dv;
        wrap[fi] = ch != VT_CHART_NONE && e < r->layout->entry_count && r->layout->entries[e].wrap;
    }
    if ((rc = vt_cut(&m, wrap, shift, &r->cut, err)) < 0) {
        rc = name_chart_error(r, rc, err);
        goto out;
    }
    r->stats.faces_cut = r->cut.faces_cut;
    r->stats.faces_split = r->cut.faces_split;
    r->stats.pieces = r->cut.pieces;
    r->any_changed = r->cut.faces_cut + r->cut.faces_split > 0;
    if ((rc = assign_keys(r, err)) < 0)
        goto out;
    if (r->any_changed) {
        r->v_out = malloc(((size_t)r->nv + 1) * sizeof *r->v_out);
        r->vn_out = malloc(((size_t)r->nvn + 1) * sizeof *r->vn_out);
        r->new_pos_out = malloc(((size_t)r->cut.vertex_count + 1) * sizeof *r->new_pos_out);
        if (!r->v_out || !r->vn_out || !r->new_pos_out) {
            rc = vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory", r->name);
            goto out;
        }
        for (uint32_t j = 0; j < r->cut.vertex_count; j++)
            r->new_pos_out[j] = VT_OFFSET_NONE;
        rc = interpolate(r, path, mem, size, err);
    }
out:
    free(chart);
    free(wrap);
    free(shift);
    free(boxes);
    return rc;
}

void vt_offset_mesh_release(struct vt_offset_run *r)
{
    struct vt_offset_faces *f = &r->faces;
    free(f->start);
    free(f->pos);
    free(f->tex);
    free(f->nrm);
    free(f->group);
    free(f->entry);
    free(f->line);
    free(r->keys);
    free(r->face_key);
    vt_cut_release(&r->cut);
    free(r->new_pos);
    free(r->normals);
    free(r->normal_index);
    free(r->v_out);
    free(r->vn_out);
    free(r->new_pos_out);
    free(r->corner);
}
