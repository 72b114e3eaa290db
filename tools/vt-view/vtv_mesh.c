/* vt-view geometry: quad or OBJ. */
#include "vtv_mesh.h"

#include <stdlib.h>
#include <string.h>

#include "vt_error.h"
#include "vt_obj.h"

static int push_vertex(struct vtv_mesh *m, uint32_t *cap, const float v[5])
{
    if (m->vertex_count == *cap) {
        if (*cap >= (1u << 27))
            return VTS_ERR_LIMIT;
        uint32_t nc = *cap ? *cap * 2 : 1024;
        float *p = realloc(m->vertices, (size_t)nc * 5 * sizeof(float));
        uint32_t *q = realloc(m->indices, (size_t)nc * sizeof(uint32_t));
        if (p)
            m->vertices = p;
        if (q)
            m->indices = q;
        if (!p || !q)
            return VTS_ERR_NOMEM;
        *cap = nc;
    }
    memcpy(m->vertices + (size_t)m->vertex_count * 5, v, 5 * sizeof(float));
    m->indices[m->index_count++] = m->vertex_count++;
    for (int k = 0; k < 3; k++) {
        if (v[k] < m->lo[k])
            m->lo[k] = v[k];
        if (v[k] > m->hi[k])
            m->hi[k] = v[k];
    }
    return 0;
}

int vtv_mesh_quad(struct vtv_mesh *m, double width, double height, struct vts_error *err)
{
    memset(m, 0, sizeof(*m));
    m->vertices = malloc(4 * 5 * sizeof(float));
    m->indices = malloc(6 * sizeof(uint32_t));
    if (!m->vertices || !m->indices) {
        vtv_mesh_free(m);
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    }
    const float w = (float)width, h = (float)height;
    const float v[20] = {0, 0, 0, 0, 0, w, 0, 0, 1, 0, w, h, 0, 1, 1, 0, h, 0, 0, 1};
    const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
    memcpy(m->vertices, v, sizeof(v));
    memcpy(m->indices, idx, sizeof(idx));
    m->vertex_count = 4;
    m->index_count = 6;
    m->hi[0] = width;
    m->hi[1] = height;
    return 0;
}

struct obj_ctx {
    struct vtv_mesh *m;
    uint32_t cap;
    const char *path;
};

static void corner(const struct vt_obj *obj, const struct vt_obj_corner *c, float out[5])
{
    const double *p = vt_obj_positions(obj) + (size_t)c->v * 3;
    out[0] = (float)p[0];
    out[1] = (float)p[1];
    out[2] = (float)p[2];
    out[3] = out[4] = 0.0f;
    if (c->vt != VT_OBJ_NONE) {
        const double *t = vt_obj_texcoords(obj) + (size_t)c->vt * 3;
        out[3] = (float)t[0];
        out[4] = (float)(1.0 - t[1]);
    }
}

static int on_face(void *user, const struct vt_obj *obj, const struct vt_obj_face *f,
                   struct vts_error *err)
{
    struct obj_ctx *ctx = user;
    float a[5], b[5], c[5];
    corner(obj, &f->corners[0], a);
    for (uint32_t i = 1; i + 1 < f->corner_count; i++) {
        corner(obj, &f->corners[i], b);
        corner(obj, &f->corners[i + 1], c);
        int st = push_vertex(ctx->m, &ctx->cap, a);
        if (st == 0)
            st = push_vertex(ctx->m, &ctx->cap, b);
        if (st == 0)
            st = push_vertex(ctx->m, &ctx->cap, c);
        if (st != 0)
            return vt_error_set(err, st, "'%s':%llu: too many triangles", ctx->path,
                                (unsigned long long)f->line);
    }
    return 0;
}

int vtv_mesh_read_obj(struct vtv_mesh *m, const char *path, struct vts_error *err)
{
    memset(m, 0, sizeof(*m));
    for (int k = 0; k < 3; k++) {
        m->lo[k] = 1e300;
        m->hi[k] = -1e300;
    }
    struct obj_ctx ctx = {m, 0, path};
    struct vt_obj *obj = vt_obj_create(NULL, err);
    if (!obj)
        return err->status;
    struct vt_obj_callbacks cb = {.face = on_face, .user = &ctx};
    int st = vt_obj_read(obj, path, &cb, err);
    vt_obj_destroy(obj);
    if (st == 0 && m->index_count == 0)
        st = vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': no faces", path);
    if (st != 0)
        vtv_mesh_free(m);
    return st;
}

void vtv_mesh_free(struct vtv_mesh *m)
{
    free(m->vertices);
    free(m->indices);
    memset(m, 0, sizeof(*m));
}
