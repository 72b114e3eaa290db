/* vt-view geometry: quad or OBJ, faces grouped by material feature set. */
#include "vtv_mesh.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "tool_common.h"
#include "vt_error.h"
#include "vt_obj.h"

/* The triangles of one material as read. */
struct bucket {
    char *name;
    float *v;       /* VTV_VERTEX_FLOATS per vertex */
    uint32_t *keys; /* v, vt, vn per vertex */
    size_t n, cap;
    uint64_t faces;
};

struct obj_ctx {
    struct vtv_mesh *m;
    const char *path;
    bool materials;
    char **mtls; /* mtllib files, resolved */
    size_t mtl_count;
    struct bucket *b;
    uint32_t bucket_count, cur;
};

static int on_mtllib(void *user, const struct vt_obj *obj, const char *mtl_path, uint64_t line,
                     struct vts_error *err)
{
    struct obj_ctx *ctx = user;
    (void)obj, (void)line;
    char **p = realloc(ctx->mtls, (ctx->mtl_count + 1) * sizeof(*p));
    if (!p)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    ctx->mtls = p;
    if (!(p[ctx->mtl_count] = strdup(mtl_path)))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    ctx->mtl_count++;
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

static int bucket_of(struct obj_ctx *c, const char *name, struct vts_error *err)
{
    if (!c->materials)
        name = "";
    if (c->cur < c->bucket_count && strcmp(c->b[c->cur].name, name) == 0)
        return 0;
    for (c->cur = 0; c->cur < c->bucket_count; c->cur++)
        if (strcmp(c->b[c->cur].name, name) == 0)
            return 0;
    struct bucket *b = realloc(c->b, (c->bucket_count + 1) * sizeof(*b));
    if (!b)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    c->b = b;
    memset(&b[c->bucket_count], 0, sizeof(*b));
    if (!(b[c->bucket_count].name = strdup(name)))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    c->cur = c->bucket_count++;
    return 0;
}

static int push_corner(struct obj_ctx *c, const struct vt_obj *obj, const struct vt_obj_corner *k)
{
    struct bucket *b = &c->b[c->cur];
    if (b->n == b->cap) {
        if (b->cap >= (1u << 27))
            return VTS_ERR_LIMIT;
        size_t nc = b->cap ? b->cap * 2 : 768;
        float *v = realloc(b->v, nc * VTV_VERTEX_FLOATS * sizeof(float));
        if (v)
            b->v = v;
        uint32_t *keys = realloc(b->keys, nc * 3 * sizeof(uint32_t));
        if (keys)
            b->keys = keys;
        if (!v || !keys)
            return VTS_ERR_NOMEM;
        b->cap = nc;
    }
    float *out = b->v + b->n * VTV_VERTEX_FLOATS;
    memset(out, 0, VTV_VERTEX_FLOATS * sizeof(float));
    const double *p = vt_obj_positions(obj) + (size_t)k->v * 3;
    for (int i = 0; i < 3; i++) {
        out[i] = (float)p[i];
        if (out[i] < c->m->lo[i])
            c->m->lo[i] = out[i];
        if (out[i] > c->m->hi[i])
            c->m->hi[i] = out[i];
    }
    if (k->vt != VT_OBJ_NONE) {
        const double *t = vt_obj_texcoords(obj) + (size_t)k->vt * 3;
        out[3] = (float)t[0];
        out[4] = (float)(1.0 - t[1]);
    }
    if (k->vn != VT_OBJ_NONE) {
        const double *nn = vt_obj_normals(obj) + (size_t)k->vn * 3;
        for (int i = 0; i < 3; i++)
            out[5 + i] = (float)nn[i];
    }
    b->keys[b->n * 3] = k->v;
    b->keys[b->n * 3 + 1] = k->vt;
    b->keys[b->n * 3 + 2] = k->vn;
    b->n++;
    return 0;
}

static int on_face(void *user, const struct vt_obj *obj, const struct vt_obj_face *f,
                   struct vts_error *err)
{
    struct obj_ctx *ctx = user;
    int st = bucket_of(ctx, f->material, err);
    if (st != 0)
        return st;
    ctx->b[ctx->cur].faces++;
    for (uint32_t i = 1; i + 1 < f->corner_count; i++) {
        st = push_corner(ctx, obj, &f->corners[0]);
        if (st == 0)
            st = push_corner(ctx, obj, &f->corners[i]);
        if (st == 0)
            st = push_corner(ctx, obj, &f->corners[i + 1]);
        if (st == VTS_ERR_NOMEM)
            return vt_error_set(err, st, "out of memory");
        if (st != 0)
            return vt_error_set(err, st, "'%s':%llu: too many triangles", ctx->path,
                                (unsigned long long)f->line);
    }
    return 0;
}

/* The store layer a map statement names: what follows the last '#' of "STORE#LAYER", "" for a map
 * that names the store alone (the shown layer). */
static const char *map_layer(const char *file)
{
    const char *h = file ? strrchr(file, '#') : NULL;
    return h ? h + 1 : "";
}

/* Records that map kind k of material name is drawn from layer; one layer per map kind. */
static int use_layer(struct vtv_mesh *m, unsigned k, const char *layer, const char *name,
                     struct vts_error *err)
{
    static const char *const stmt[VTV_MAP_COUNT] = {"map_Kd", "norm/bump", "map_Ks", "map_d"};
    if (m->layers[k])
        return strcmp(m->layers[k], layer) == 0
                   ? 0
                   : vt_error_set(err, VTS_ERR_BAD_INPUT,
                                  "material '%s': %s names layer '%s', another material '%s': "
                                  "vt-view draws each map kind from one store layer",
                                  name, stmt[k], layer, m->layers[k]);
    if (!(m->layers[k] = strdup(layer)))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    return 0;
}

/* 1 + the index of pack path in m->wang_paths, added when new; 0 when out of memory. */
static uint32_t use_wang(struct vtv_mesh *m, const char *path)
{
    for (uint32_t i = 0; i < m->wang_count; i++)
        if (strcmp(m->wang_paths[i], path) == 0)
            return i + 1;
    char **p = realloc(m->wang_paths, (m->wang_count + 1) * sizeof(*p));
    if (!p)
        return 0;
    m->wang_paths = p;
    if (!(p[m->wang_count] = strdup(path)))
        return 0;
    return ++m->wang_count;
}

/* The material of bucket b from the MTL files (the first that defines it, as vt-atlas reads). */
static int resolve(struct obj_ctx *c, const struct vt_mtl *mtls, struct vtv_mesh_group *g,
                   const struct bucket *b, struct vts_error *err)
{
    const struct vt_mtl_material *mm = NULL;
    for (size_t i = 0; c->materials && i < c->mtl_count && !mm; i++)
        mm = vt_mtl_find(&mtls[i], b->name);
    if (!mm) { /* no materials, or one no MTL defines: the shown layer as it is */
        vtv_material_plain(&g->mat);
        return use_layer(c->m, VTV_MAP_DIFFUSE, "", b->name, err);
    }
    static const unsigned kinds[][2] = {{VT_MTL_MAP_KD, VTV_MAP_DIFFUSE},
                                        {VT_MTL_MAP_NORM, VTV_MAP_NORMAL},
                                        {VT_MTL_MAP_BUMP, VTV_MAP_NORMAL},
                                        {VT_MTL_MAP_KS, VTV_MAP_SPECULAR},
                                        {VT_MTL_MAP_D, VTV_MAP_ALPHA}};
    unsigned maps = 0;
    for (size_t i = 0; mm && i < sizeof(kinds) / sizeof(kinds[0]); i++) {
        const char *file = mm->maps[kinds[i][0]].file;
        if (!file || (maps & (1u << kinds[i][1])))
            continue;
        int st = use_layer(c->m, kinds[i][1], map_layer(file), b->name, err);
        if (st != 0)
            return st;
        maps |= 1u << kinds[i][1];
    }
    vtv_material_from_mtl(mm, maps, false, &g->mat);
    if (mm->wang_path) { /* vt_wang: the diffuse from a pack (docs/wang.md, "Packs in scenes") */
        if (!(g->mat.wang = use_wang(c->m, mm->wang_path)))
            return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        g->mat.wang_scale = (float)mm->wang_scale;
        if (!(mm->flags & VT_MTL_HAS_KD))
            g->mat.kd[0] = g->mat.kd[1] = g->mat.kd[2] = 1.0f;
    }
    return 0;
}

static int cmp_group(const void *a, const void *b)
{
    const struct vtv_mesh_group *x = a, *y = b;
    bool bx = x->features & VTV_F_ALPHA_BLEND, by = y->features & VTV_F_ALPHA_BLEND;
    if (bx != by)
        return bx ? 1 : -1;
    if (x->features != y->features)
        return x->features < y->features ? -1 : 1;
    return x->first < y->first ? -1 : x->first > y->first; /* stable: order of first use */
}

/* Groups from the buckets, sorted by feature set, then one vertex buffer in that order. */
static int build(struct obj_ctx *c, struct vts_error *err)
{
    struct vtv_mesh *m = c->m;
    struct vt_mtl *mtls = calloc(c->mtl_count ? c->mtl_count : 1, sizeof(*mtls));
    m->groups = calloc(c->bucket_count ? c->bucket_count : 1, sizeof(*m->groups));
    if (!mtls || !m->groups) {
        free(mtls);
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    }
    int st = 0;
    for (size_t i = 0; c->materials && i < c->mtl_count && st == 0; i++)
        if (vt_mtl_read(c->mtls[i], NULL, &mtls[i], err) != 0) { /* unreadable: as vt-atlas, */
            vt_log(VT_LOG_WARN, "%s (its materials are drawn plain)", err->message);
            vt_mtl_release(&mtls[i]); /* the materials it lacks */
            *err = (struct vts_error){0};
        }
    size_t total = 0;
    for (uint32_t i = 0; i < c->bucket_count && st == 0; i++) {
        struct vtv_mesh_group *g = &m->groups[m->group_count++];
        st = resolve(c, mtls, g, &c->b[i], err);
        g->features = vtv_material_features(&g->mat);
        g->first = i; /* the bucket, until the buffer is laid out */
        g->count = (uint32_t)c->b[i].n;
        g->faces = c->b[i].faces;
        total += c->b[i].n;
    }
    for (size_t i = 0; i < c->mtl_count; i++)
        vt_mtl_release(&mtls[i]);
    free(mtls);
    if (st != 0)
        return st;
    if (total >= (1u << 30))
        return vt_error_set(err, VTS_ERR_LIMIT, "'%s': too many triangles", c->path);
    qsort(m->groups, m->group_count, sizeof(*m->groups), cmp_group);
    m->vertices = malloc((total ? total : 1) * VTV_VERTEX_FLOATS * sizeof(float));
    uint32_t *keys = malloc((total ? total : 1) * 3 * sizeof(uint32_t));
    if (!m->vertices || !keys) {
        free(keys);
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    }
    uint32_t at = 0;
    for (uint32_t i = 0; i < m->group_count; i++) {
        const struct bucket *b = &c->b[m->groups[i].first];
        memcpy(m->vertices + (size_t)at * VTV_VERTEX_FLOATS, b->v,
               b->n * VTV_VERTEX_FLOATS * sizeof(float));
        memcpy(keys + (size_t)at * 3, b->keys, b->n * 3 * sizeof(uint32_t));
        m->groups[i].first = at;
        at += (uint32_t)b->n;
    }
    m->vertex_count = at;
    st = vtv_tangents(m->vertices, keys, at);
    free(keys);
    return st != 0 ? vt_error_set(err, st, "out of memory") : 0;
}

int vtv_mesh_quad(struct vtv_mesh *m, double width, double height, struct vts_error *err)
{
    memset(m, 0, sizeof(*m));
    m->vertices = calloc(6 * VTV_VERTEX_FLOATS, sizeof(float));
    m->groups = calloc(1, sizeof(*m->groups));
    m->layers[VTV_MAP_DIFFUSE] = strdup("");
    if (!m->vertices || !m->groups || !m->layers[VTV_MAP_DIFFUSE]) {
        vtv_mesh_free(m);
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    }
    const float w = (float)width, h = (float)height;
    const float corners[4][5] = {
        {0, 0, 0, 0, 0}, {w, 0, 0, 1, 0}, {w, h, 0, 1, 1}, {0, h, 0, 0, 1}};
    const int order[6] = {0, 1, 2, 0, 2, 3};
    for (int i = 0; i < 6; i++) {
        float *v = m->vertices + i * VTV_VERTEX_FLOATS;
        memcpy(v, corners[order[i]], 5 * sizeof(float));
        v[7] = 1.0f;  /* normal +z */
        v[8] = 1.0f;  /* tangent +x */
        v[11] = 1.0f; /* handedness */
    }
    m->vertex_count = 6;
    m->group_count = 1;
    m->groups[0].count = 6;
    m->groups[0].faces = 1;
    vtv_material_plain(&m->groups[0].mat);
    m->groups[0].features = vtv_material_features(&m->groups[0].mat);
    m->hi[0] = width;
    m->hi[1] = height;
    return 0;
}

static void ctx_release(struct obj_ctx *c)
{
    for (size_t i = 0; i < c->mtl_count; i++)
        free(c->mtls[i]);
    free(c->mtls);
    for (uint32_t i = 0; i < c->bucket_count; i++) {
        free(c->b[i].name);
        free(c->b[i].v);
        free(c->b[i].keys);
    }
    free(c->b);
}

int vtv_mesh_read_obj(struct vtv_mesh *m, const char *path, bool materials, struct vts_error *err)
{
    memset(m, 0, sizeof(*m));
    for (int k = 0; k < 3; k++) {
        m->lo[k] = 1e300;
        m->hi[k] = -1e300;
    }
    struct obj_ctx ctx = {.m = m, .path = path, .materials = materials, .cur = UINT32_MAX};
    struct vt_obj *obj = vt_obj_create(NULL, err);
    if (!obj)
        return err->status;
    struct vt_obj_callbacks cb = {.face = on_face, .mtllib = on_mtllib, .user = &ctx};
    int st = vt_obj_read(obj, path, &cb, err);
    vt_obj_destroy(obj);
    if (st == 0 && ctx.mtl_count)
        st = check_mtl(path, ctx.mtls[0], err);
    if (st == 0 && ctx.bucket_count == 0)
        st = vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': no faces", path);
    if (st == 0)
        st = build(&ctx, err);
    ctx_release(&ctx);
    if (st != 0)
        vtv_mesh_free(m);
    return st;
}

void vtv_mesh_free(struct vtv_mesh *m)
{
    free(m->vertices);
    free(m->indices);
    free(m->groups);
    for (int k = 0; k < VTV_MAP_COUNT; k++)
        free(m->layers[k]);
    for (uint32_t i = 0; i < m->wang_count; i++)
        free(m->wang_paths[i]);
    free(m->wang_paths);
    memset(m, 0, sizeof(*m));
}
