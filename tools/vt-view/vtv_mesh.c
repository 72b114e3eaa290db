/* vt-view geometry: quad or OBJ. */
#include "vtv_mesh.h"

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

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
    char *mtl; /* the first mtllib file, resolved (malloc'ed) */
};

static int on_mtllib(void *user, const struct vt_obj *obj, const char *mtl_path, uint64_t line,
                     struct vts_error *err)
{
    struct obj_ctx *ctx = user;
    (void)obj, (void)line;
    if (!ctx->mtl && !(ctx->mtl = strdup(mtl_path)))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    return 0;
}

/* The scene's UVs are the atlas's only when vt-offset wrote it: its MTL's maps name the store
 * (map_Kd scene.vts#diffuse). An MTL that maps textures but no store belongs to the scene before
 * vt-offset, whose UVs mean nothing on the store: refused. An MTL that cannot be read, or maps
 * nothing, is not judged. */
static int check_mtl(const char *obj_path, const char *mtl_path, struct vts_error *err)
{
    FILE *f = fopen(mtl_path, "r");
    if (!f)
        return 0;
    char line[4096], first[256] = "";
    bool store = false;
    while (!store && fgets(line, sizeof line, f)) {
        const char *p = line + strspn(line, " \t");
        if (strncmp(p, "map_", 4) != 0 && strncmp(p, "norm", 4) != 0 &&
            strncmp(p, "bump", 4) != 0 && strncmp(p, "disp", 4) != 0)
            continue;
        for (const char *q = p; *q && !store; q++)
            store = strncasecmp(q, ".vts", 4) == 0;
        if (!first[0]) {
            snprintf(first, sizeof first, "%s", p);
            first[strcspn(first, "\r\n")] = '\0';
        }
    }
    fclose(f);
    if (store || !first[0])
        return 0;
    return vt_error_set(err, VTS_ERR_BAD_INPUT,
                        "'%s' is not a vt-offset output: its MTL '%s' maps textures ('%s'), not "
                        "the store, so its UVs do not lie on the atlas: view the .vt.obj vt-offset "
                        "writes from it",
                        obj_path, mtl_path, first);
}

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
    struct obj_ctx ctx = {m, 0, path, NULL};
    struct vt_obj *obj = vt_obj_create(NULL, err);
    if (!obj)
        return err->status;
    struct vt_obj_callbacks cb = {.face = on_face, .mtllib = on_mtllib, .user = &ctx};
    int st = vt_obj_read(obj, path, &cb, err);
    vt_obj_destroy(obj);
    if (st == 0 && ctx.mtl)
        st = check_mtl(path, ctx.mtl, err);
    free(ctx.mtl);
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
