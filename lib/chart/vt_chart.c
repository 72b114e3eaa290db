/* UV charts of a polygon mesh and their whole-repeat moves (vt_chart.h). */
#include "vt_chart.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_keymap.h"
#include "vt_checked.h"

/* Union-find over faces: the root of a set is its lowest face, so a chart's root is its first face
 * and numbering charts in face order needs no second table. */
static uint32_t find_root(uint32_t *parent, uint32_t f)
{
    while (parent[f] != f) {
        parent[f] = parent[parent[f]]; /* path halving */
        f = parent[f];
    }
    return f;
}

static void join(uint32_t *parent, uint32_t a, uint32_t b)
{
    a = find_root(parent, a);
    b = find_root(parent, b);
    if (a < b)
        parent[b] = a;
    else if (b < a)
        parent[a] = b;
}

static uint64_t u64_of(double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    return bits;
}

/* A face is in a chart when it has a group and a texcoord at one corner at least. */
static bool face_in_chart(const struct vt_chart_mesh *m, uint32_t f)
{
    if (m->group[f] == VT_CHART_NONE)
        return false;
    for (uint64_t c = m->face_start[f]; c < m->face_start[f + 1]; c++)
        if (m->tex[c] != VT_CHART_NONE)
            return true;
    return false;
}

/* Joins f with the earlier faces of its group that use one of its texcoord indices. */
static int join_shared_texcoords(const struct vt_chart_mesh *m, uint32_t f, uint32_t *parent,
                                 struct vt_keymap *by_tex)
{
    for (uint64_t c = m->face_start[f]; c < m->face_start[f + 1]; c++) {
        if (m->tex[c] == VT_CHART_NONE)
            continue;
        uint64_t key = (uint64_t)m->tex[c] << 32 | m->group[f], first = f;
        int rc;
        if (!vt_keymap_put_new(by_tex, &key, &first, &rc)) {
            if (rc)
                return rc;
            join(parent, f, (uint32_t)first);
        }
    }
    return 0;
}

/* Joins f with the earlier faces of its group that have one of its edges (the same two positions)
 * with bitwise-equal texcoord values at both ends. The key orients the edge from its lower
 * position index, so both faces of the edge build the same key whatever their winding. */
static int join_shared_edges(const struct vt_chart_mesh *m, uint32_t f, uint32_t *parent,
                             struct vt_keymap *by_edge)
{
    uint64_t c0 = m->face_start[f], n = m->face_start[f + 1] - c0;
    for (uint64_t i = 0; i < n; i++) {
        uint64_t ca = c0 + i, cb = c0 + (i + 1) % n;
        if (m->tex[ca] == VT_CHART_NONE || m->tex[cb] == VT_CHART_NONE || m->pos[ca] == m->pos[cb])
            continue;
        if (m->pos[ca] > m->pos[cb]) {
            uint64_t t = ca;
            ca = cb;
            cb = t;
        }
        const double *ua = m->uv + 2 * (size_t)m->tex[ca], *ub = m->uv + 2 * (size_t)m->tex[cb];
        uint64_t key[6] = {(uint64_t)m->pos[ca] << 32 | m->pos[cb],
                           m->group[f],
                           u64_of(ua[0]),
                           u64_of(ua[1]),
                           u64_of(ub[0]),
                           u64_of(ub[1])};
        uint64_t first = f;
        int rc;
        if (!vt_keymap_put_new(by_edge, key, &first, &rc)) {
            if (rc)
                return rc;
            join(parent, f, (uint32_t)first);
        }
    }
    return 0;
}

int vt_chart_label(const struct vt_chart_mesh *m, uint32_t *chart, uint32_t *chart_count,
                   struct vts_error *err)
{
    int rc = 0;
    size_t bytes;
    *chart_count = 0;
    if (!vt_size_mul(m->face_count ? m->face_count : 1, sizeof(uint32_t), &bytes))
        return vt_error_set(err, VTS_ERR_NOMEM, "cannot label charts: %u faces", m->face_count);
    uint32_t *parent = malloc(bytes);
    struct vt_keymap by_tex, by_edge;
    vt_keymap_init(&by_tex, 1);
    vt_keymap_init(&by_edge, 6);
    if (!parent)
        goto out_nomem;
    for (uint32_t f = 0; f < m->face_count; f++)
        parent[f] = face_in_chart(m, f) ? f : VT_CHART_NONE;
    for (uint32_t f = 0; f < m->face_count; f++) {
        if (parent[f] == VT_CHART_NONE)
            continue;
        rc = join_shared_texcoords(m, f, parent, &by_tex);
        if (!rc)
            rc = join_shared_edges(m, f, parent, &by_edge);
        if (rc)
            goto out_nomem;
    }
    /* A root is the lowest face of its set: it is labelled before the other faces of its chart. */
    uint32_t count = 0;
    for (uint32_t f = 0; f < m->face_count; f++) {
        if (parent[f] == VT_CHART_NONE) {
            chart[f] = VT_CHART_NONE;
            continue;
        }
        uint32_t root = find_root(parent, f);
        if (root == f) {
            if (count == VT_CHART_NONE - 1) {
                rc = vt_error_set(err, VTS_ERR_LIMIT, "cannot label charts: more than %u charts",
                                  VT_CHART_NONE - 2);
                goto out_free;
            }
            chart[f] = count++;
        } else {
            chart[f] = chart[root];
        }
    }
    *chart_count = count;
    goto out_free;
out_nomem:
    rc = vt_error_set(err, VTS_ERR_NOMEM, "cannot label the charts of %u faces: out of memory",
                      m->face_count);
out_free:
    vt_keymap_release(&by_tex);
    vt_keymap_release(&by_edge);
    free(parent);
    return rc;
}

void vt_chart_boxes(const struct vt_chart_mesh *m, const uint32_t *chart, uint32_t chart_count,
                    struct vt_chart_box *boxes)
{
    for (uint32_t i = 0; i < chart_count; i++)
        boxes[i] = (struct vt_chart_box){VT_CHART_NONE, 0,         INFINITY, -INFINITY,
                                         INFINITY,      -INFINITY, 0.0,      0.0};
    for (uint32_t f = 0; f < m->face_count; f++) {
        if (chart[f] == VT_CHART_NONE)
            continue;
        struct vt_chart_box *b = &boxes[chart[f]];
        b->group = m->group[f];
        b->faces++;
        for (uint64_t c = m->face_start[f]; c < m->face_start[f + 1]; c++) {
            if (m->tex[c] == VT_CHART_NONE)
                continue;
            double u = m->uv[2 * (size_t)m->tex[c]], v = m->uv[2 * (size_t)m->tex[c] + 1];
            b->umin = fmin(b->umin, u);
            b->umax = fmax(b->umax, u);
            b->vmin = fmin(b->vmin, v);
            b->vmax = fmax(b->vmax, v);
        }
    }
    /* 0.0 - floor(x): a move of +0.0, never -0.0, for a box starting in [0, 1); an axis whose
     * range lies in [0, 1], bounds included, is not moved (a chart at u = 1 exactly stays the
     * right edge of one copy) */
    for (uint32_t i = 0; i < chart_count; i++) {
        struct vt_chart_box *b = &boxes[i];
        b->du = b->umin >= 0 && b->umax <= 1 ? 0.0 : 0.0 - floor(b->umin);
        b->dv = b->vmin >= 0 && b->vmax <= 1 ? 0.0 : 0.0 - floor(b->vmin);
    }
}
