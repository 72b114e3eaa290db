/* The scene scan: OBJ faces -> used materials -> MTL maps -> texture headers (vt_atlas_scene.h). */
#include "vt_atlas_scene.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "internal/vt_strmap.h"
#include "vt_chart.h"
#include "vt_checked.h"
#include "vt_error.h"
#include "vt_obj.h"

struct vt_atlas_scene_index {
    struct vt_strmap materials, textures, deps; /* name / path -> array index */
    struct vt_strmap files;                     /* texture id ("dev:ino") -> texture */
    size_t material_capacity, texture_capacity, dep_capacity;
};

/* ---- the scene's arrays ---- */

/* 0 or VTS_ERR_NOMEM: vt_array_grow() from 16 elements. */
static int grow(void **p, size_t *cap, size_t need, size_t elem)
{
    return vt_array_grow(p, cap, need, elem, 16) ? 0 : VTS_ERR_NOMEM;
}

static struct vt_atlas_scene_index *index_of(struct vt_atlas_scene *s, struct vts_error *err)
{
    if (!s->index)
        s->index = calloc(1, sizeof *s->index);
    if (!s->index)
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    return s->index;
}

/* Adds path to the deps (once); *copy (may be NULL) gets the scene's copy of it. */
static int add_dep(struct vt_atlas_scene *s, const char *path, const char **copy,
                   struct vts_error *err)
{
    struct vt_atlas_scene_index *ix = index_of(s, err);
    if (!ix)
        return VTS_ERR_NOMEM;
    int64_t found = vt_strmap_get(&ix->deps, path);
    if (found >= 0) {
        if (copy)
            *copy = s->deps[found];
        return 0;
    }
    char *dup = strdup(path);
    if (!dup || grow((void **)&s->deps, &ix->dep_capacity, s->dep_count + 1, sizeof *s->deps) ||
        vt_strmap_put(&ix->deps, dup, (uint32_t)s->dep_count))
        goto out_nomem;
    s->deps[s->dep_count++] = dup;
    if (copy)
        *copy = dup;
    return 0;
out_nomem:
    free(dup);
    return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
}

/* A missing texture (stat failed with errno e): an error, or with missing_skip a warning and no
 * texture (-1 in *index). */
static int missing_texture(const char *path, const char *where, int e,
                           const struct vt_atlas_scene_options *o, int32_t *index,
                           struct vts_error *err)
{
    char msg[VTS_ERROR_MESSAGE_MAX];
    snprintf(msg, sizeof msg, "%s '%s': %s", where, path, strerror(e));
    if (!o->missing_skip || e != ENOENT)
        return vt_error_set(err, VTS_ERR_IO, "%s", msg);
    if (o->warn) {
        strncat(msg, " (skipped: the material's constant)", sizeof msg - strlen(msg) - 1);
        o->warn(o->warn_user, msg);
    }
    *index = -1;
    return 0;
}

/* Reads the header of a new texture file through the open callback and appends it. */
static int open_texture(struct vt_atlas_scene *s, const char *path, const char *id,
                        const char *where, const struct vt_atlas_scene_options *o, int32_t *index,
                        struct vts_error *err)
{
    struct vt_atlas_scene_index *ix = s->index;
    if (s->texture_count >= o->max_textures)
        return vt_error_set(err, VTS_ERR_LIMIT, "%s '%s': more than %u textures (--max-textures)",
                            where, path, o->max_textures);
    struct vt_source src = {0};
    struct vts_error oe = {0};
    int rc = o->open(o->open_user, path, &src, &oe);
    if (rc)
        return vt_error_set(err, rc, "%s: %s", where, oe.message);
    struct vt_atlas_texture t = {.width = src.info.width,
                                 .height = src.info.height,
                                 .channels = src.info.channels,
                                 .has_alpha = src.info.has_alpha};
    vt_source_close(&src);
    t.path = strdup(path);
    t.id = strdup(id);
    if (!t.path || !t.id ||
        grow((void **)&s->textures, &ix->texture_capacity, (size_t)s->texture_count + 1,
             sizeof *s->textures))
        goto out_free;
    uint32_t ti = s->texture_count++;
    s->textures[ti] = t; /* the scene owns it from here on, also when a map fails below */
    if (vt_strmap_put(&ix->textures, t.path, ti) || vt_strmap_put(&ix->files, t.id, ti))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    *index = (int32_t)ti;
    return add_dep(s, path, NULL, err);
out_free:
    free(t.path);
    free(t.id);
    return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
}

/* Finds or opens the texture at path (header only); -1 in *index when it is missing and
 * missing_skip. where ("'a.mtl':12: map_Kd") prefixes messages. */
static int add_texture(struct vt_atlas_scene *s, const char *path, const char *where,
                       const struct vt_atlas_scene_options *o, int32_t *index,
                       struct vts_error *err)
{
    struct vt_atlas_scene_index *ix = index_of(s, err);
    if (!ix)
        return VTS_ERR_NOMEM;
    int64_t found = vt_strmap_get(&ix->textures, path);
    if (found >= 0) {
        *index = (int32_t)found;
        return 0;
    }
    struct stat st;
    if (stat(path, &st) != 0)
        return missing_texture(path, where, errno, o, index, err);
    char id[64];
    snprintf(id, sizeof id, "%llu:%llu", (unsigned long long)st.st_dev,
             (unsigned long long)st.st_ino);
    found = vt_strmap_get(&ix->files, id);
    if (found >= 0) { /* another path to a file already read */
        *index = (int32_t)found;
        return add_dep(s, path, NULL, err);
    }
    return open_texture(s, path, id, where, o, index, err);
}

static int add_material(struct vt_atlas_scene *s, const char *name, uint32_t *index,
                        struct vts_error *err)
{
    struct vt_atlas_scene_index *ix = index_of(s, err);
    if (!ix)
        return VTS_ERR_NOMEM;
    int64_t found = vt_strmap_get(&ix->materials, name);
    if (found >= 0) {
        *index = (uint32_t)found;
        return 0;
    }
    if (s->material_count == UINT32_MAX ||
        grow((void **)&s->materials, &ix->material_capacity, (size_t)s->material_count + 1,
             sizeof *s->materials))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    struct vt_atlas_material *m = &s->materials[s->material_count];
    memset(m, 0, sizeof *m);
    m->name = strdup(name);
    if (!m->name || vt_strmap_put(&ix->materials, m->name, s->material_count)) {
        free(m->name);
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    }
    for (unsigned k = 0; k < VT_ATLAS_KIND_COUNT; k++)
        m->texture[k] = -1;
    m->umin = m->vmin = m->raw_umin = m->raw_vmin = INFINITY;
    m->umax = m->vmax = m->raw_umax = m->raw_vmax = -INFINITY;
    *index = s->material_count++;
    return 0;
}

/* ---- OBJ ---- */

struct obj_ctx {
    struct vt_atlas_scene *scene;
    const struct vt_atlas_scene_options *o;
    const char *obj_path; /* the scene's copy (a dep) */
    struct vt_mtl *mtls;  /* the OBJ's mtllib files, read whole */
    char **mtl_paths;
    size_t mtl_count, mtls_capacity, paths_capacity;
    uint32_t last; /* material of the previous face */
    const char *last_name;
    bool have_last;
    uint32_t first_new; /* materials from here on were first used by this OBJ */
    /* the OBJ's faces with a material, for the charts (vt_chart.h) */
    uint64_t *face_start; /* face_count + 1 */
    uint32_t *corner_pos, *corner_tex, *face_group;
    uint32_t face_count;
    size_t face_cap, start_cap, corner_cap, tex_cap;
    uint64_t corner_count;
};

/* Keeps face f (material index mat) for the charts. */
static int keep_face(struct obj_ctx *c, const struct vt_obj_face *f, uint32_t mat,
                     struct vts_error *err)
{
    size_t corners;
    if (c->face_count == UINT32_MAX - 1 ||
        !vt_size_add((size_t)c->corner_count, f->corner_count, &corners))
        return vt_error_set(err, VTS_ERR_LIMIT, "'%s':%llu: too many faces", c->obj_path,
                            (unsigned long long)f->line);
    if (grow((void **)&c->face_group, &c->face_cap, (size_t)c->face_count + 1,
             sizeof *c->face_group) ||
        grow((void **)&c->face_start, &c->start_cap, (size_t)c->face_count + 2,
             sizeof *c->face_start) ||
        grow((void **)&c->corner_pos, &c->corner_cap, corners, sizeof *c->corner_pos) ||
        grow((void **)&c->corner_tex, &c->tex_cap, corners, sizeof *c->corner_tex))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the faces of '%s'", c->obj_path);
    if (c->face_count == 0)
        c->face_start[0] = 0;
    for (uint32_t i = 0; i < f->corner_count; i++) {
        c->corner_pos[c->corner_count + i] = f->corners[i].v;
        c->corner_tex[c->corner_count + i] =
            f->corners[i].vt == VT_OBJ_NONE ? VT_CHART_NONE : f->corners[i].vt;
    }
    c->corner_count = corners;
    c->face_group[c->face_count++] = mat;
    c->face_start[c->face_count] = c->corner_count;
    return 0;
}

/* The charts of the OBJ's faces: each material's box becomes the union of its charts' boxes,
 * each moved by whole repeats to start in [0,1). */
static int chart_faces(struct obj_ctx *c, const struct vt_obj *obj, struct vts_error *err)
{
    if (c->face_count == 0)
        return 0;
    uint32_t nt = vt_obj_texcoord_count(obj), nc = 0;
    const double *t3 = vt_obj_texcoords(obj);
    size_t uv_bytes;
    if (!vt_size_mul3(nt ? nt : 1, 2, sizeof(double), &uv_bytes))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the charts of '%s'",
                            c->obj_path);
    double *uv = malloc(uv_bytes);
    uint32_t *chart = malloc((size_t)c->face_count * sizeof *chart);
    struct vt_chart_box *boxes = NULL;
    int rc = 0;
    if (!uv || !chart) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the charts of '%s'", c->obj_path);
        goto out;
    }
    for (uint32_t i = 0; i < nt; i++) {
        uv[2 * (size_t)i] = t3[3 * (size_t)i];
        uv[2 * (size_t)i + 1] = t3[3 * (size_t)i + 1];
    }
    struct vt_chart_mesh m = {.face_count = c->face_count,
                              .face_start = c->face_start,
                              .pos = c->corner_pos,
                              .tex = c->corner_tex,
                              .group = c->face_group,
                              .uv = uv,
                              .position_count = vt_obj_position_count(obj),
                              .texcoord_count = nt};
    if ((rc = vt_chart_label(&m, chart, &nc, err)) != 0)
        goto out;
    boxes = malloc((nc ? nc : 1) * sizeof *boxes);
    if (!boxes) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the charts of '%s'", c->obj_path);
        goto out;
    }
    vt_chart_boxes(&m, chart, nc, boxes);
    for (uint32_t i = 0; i < nc; i++) {
        const struct vt_chart_box *b = &boxes[i];
        struct vt_atlas_material *mt = &c->scene->materials[b->group];
        mt->umin = fmin(mt->umin, b->umin + b->du);
        mt->umax = fmax(mt->umax, b->umax + b->du);
        mt->vmin = fmin(mt->vmin, b->vmin + b->dv);
        mt->vmax = fmax(mt->vmax, b->vmax + b->dv);
        mt->charts++;
        mt->moved_charts += b->du != 0 || b->dv != 0;
    }
out:
    free(uv);
    free(chart);
    free(boxes);
    return rc;
}

static int on_mtllib(void *user, const struct vt_obj *obj, const char *mtl_path, uint64_t line,
                     struct vts_error *err)
{
    (void)obj;
    struct obj_ctx *c = user;
    for (size_t i = 0; i < c->mtl_count; i++)
        if (strcmp(c->mtl_paths[i], mtl_path) == 0)
            return 0;
    if (grow((void **)&c->mtls, &c->mtls_capacity, c->mtl_count + 1, sizeof *c->mtls) ||
        grow((void **)&c->mtl_paths, &c->paths_capacity, c->mtl_count + 1, sizeof *c->mtl_paths))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    char *copy = strdup(mtl_path);
    if (!copy)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    struct vt_obj_limits limits;
    vt_obj_limits_default(&limits);
    limits.max_line_bytes = c->o->max_line_bytes;
    memset(&c->mtls[c->mtl_count], 0, sizeof c->mtls[0]);
    c->mtl_paths[c->mtl_count] = copy;
    int rc = vt_mtl_read(mtl_path, &limits, &c->mtls[c->mtl_count], err);
    c->mtl_count++;
    if (rc == VTS_ERR_IO && err) { /* name the mtllib statement too */
        char msg[VTS_ERROR_MESSAGE_MAX];
        snprintf(msg, sizeof msg, "%s", err->message);
        return vt_error_set(err, rc, "'%s':%llu: mtllib: %s", c->obj_path, (unsigned long long)line,
                            msg);
    }
    if (rc)
        return rc;
    return add_dep(c->scene, mtl_path, NULL, err);
}

static double tri_area3(const double *a, const double *b, const double *c)
{
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2],
           z = u[0] * v[1] - u[1] * v[0];
    return 0.5 * sqrt(x * x + y * y + z * z);
}

static double tri_area2(const double *a, const double *b, const double *c)
{
    return 0.5 * fabs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
}

static int on_face(void *user, const struct vt_obj *obj, const struct vt_obj_face *f,
                   struct vts_error *err)
{
    struct obj_ctx *c = user;
    if (!f->material[0])
        return 0; /* no material: nothing to place */
    if (!c->have_last || strcmp(c->last_name, f->material) != 0) {
        int rc = add_material(c->scene, f->material, &c->last, err);
        if (rc)
            return rc;
        c->have_last = true;
        c->last_name = c->scene->materials[c->last].name;
    }
    struct vt_atlas_material *m = &c->scene->materials[c->last];
    if (!m->obj) {
        m->obj = c->obj_path;
        m->first_line = f->line;
    }
    const double *pos = vt_obj_positions(obj), *uv = vt_obj_texcoords(obj);
    bool all_uv = true;
    for (uint32_t i = 0; i < f->corner_count; i++) {
        uint32_t t = f->corners[i].vt;
        if (t == VT_OBJ_NONE) {
            all_uv = false;
            continue;
        }
        m->has_uv = true;
        m->raw_umin = fmin(m->raw_umin, uv[3 * t]);
        m->raw_umax = fmax(m->raw_umax, uv[3 * t]);
        m->raw_vmin = fmin(m->raw_vmin, uv[3 * t + 1]);
        m->raw_vmax = fmax(m->raw_vmax, uv[3 * t + 1]);
    }
    int rc = keep_face(c, f, c->last, err);
    if (rc || !all_uv)
        return rc;
    for (uint32_t i = 1; i + 1 < f->corner_count; i++) {
        const struct vt_obj_corner *a = &f->corners[0], *b = &f->corners[i],
                                   *d = &f->corners[i + 1];
        m->world_area += tri_area3(pos + 3 * a->v, pos + 3 * b->v, pos + 3 * d->v);
        m->uv_area += tri_area2(uv + 3 * a->vt, uv + 3 * b->vt, uv + 3 * d->vt);
    }
    return 0;
}

static void set_fill(double fill[4], const double rgb[3], double a)
{
    for (int i = 0; i < 3; i++)
        fill[i] = rgb[i] < 0 ? 0 : rgb[i] > 1 ? 1 : rgb[i];
    fill[3] = a < 0 ? 0 : a > 1 ? 1 : a;
}

/* Each layer's constant: Kd (grey without), a flat normal, Ks, d, Ka, no displacement. */
static void set_fills(struct vt_atlas_material *m, const struct vt_mtl_material *mm)
{
    static const double grey[3] = {0.8, 0.8, 0.8}, black[3] = {0, 0, 0}, half[3] = {0.5, 0.5, 1};
    set_fill(m->fill[VT_ATLAS_DIFFUSE], mm && (mm->flags & VT_MTL_HAS_KD) ? mm->kd : grey, 1);
    set_fill(m->fill[VT_ATLAS_NORMAL], half, 1);
    set_fill(m->fill[VT_ATLAS_SPECULAR], mm && (mm->flags & VT_MTL_HAS_KS) ? mm->ks : black, 1);
    double d = mm && (mm->flags & VT_MTL_HAS_D) ? mm->d : 1;
    double dd[3] = {d, d, d};
    set_fill(m->fill[VT_ATLAS_ALPHA], dd, 1);
    set_fill(m->fill[VT_ATLAS_AMBIENT], mm && (mm->flags & VT_MTL_HAS_KA) ? mm->ka : black, 1);
    set_fill(m->fill[VT_ATLAS_DISP], black, 1);
}

/* Opens the texture of every map of mm (from the MTL file mtl_path) into m's layers. */
static int add_maps(struct obj_ctx *c, struct vt_atlas_material *m,
                    const struct vt_mtl_material *mm, const char *mtl_path, struct vts_error *err)
{
    static const int kind_of[VT_MTL_MAP_COUNT] = {
        VT_ATLAS_DIFFUSE, VT_ATLAS_AMBIENT, VT_ATLAS_SPECULAR, VT_ATLAS_ALPHA,
        VT_ATLAS_NORMAL,  VT_ATLAS_NORMAL,  VT_ATLAS_DISP};
    static const char *const stmt[VT_MTL_MAP_COUNT] = {"map_Kd", "map_Ka", "map_Ks", "map_d",
                                                       "bump",   "norm",   "disp"};
    /* norm before bump, so that a material with both keeps its normal map. */
    static const unsigned order[VT_MTL_MAP_COUNT] = {
        VT_MTL_MAP_KD,   VT_MTL_MAP_KA,   VT_MTL_MAP_KS,  VT_MTL_MAP_D,
        VT_MTL_MAP_NORM, VT_MTL_MAP_BUMP, VT_MTL_MAP_DISP};
    for (unsigned j = 0; j < VT_MTL_MAP_COUNT; j++) {
        unsigned k = order[j];
        const struct vt_mtl_map *map = &mm->maps[k];
        if (!map->path || m->texture[kind_of[k]] >= 0)
            continue;
        m->clamp |= map->clamp;
        char where[VTS_ERROR_MESSAGE_MAX];
        snprintf(where, sizeof where, "'%s':%llu: %s", mtl_path, (unsigned long long)map->line,
                 stmt[k]);
        int rc = add_texture(c->scene, map->path, where, c->o, &m->texture[kind_of[k]], err);
        if (rc)
            return rc;
    }
    return 0;
}

/* Reads the alpha of texture ti once (a map_Kd with an alpha channel): is it a cut-out? */
static int scan_alpha(struct obj_ctx *c, int32_t ti, const char *where, bool *cutout,
                      struct vts_error *err)
{
    struct vt_atlas_texture *t = &c->scene->textures[ti];
    *cutout = false;
    if (!t->has_alpha)
        return 0;
    if (!t->alpha_scanned) {
        struct vt_source src = {0};
        struct vts_error oe = {0};
        int rc = c->o->open(c->o->open_user, t->path, &src, &oe);
        if (!rc)
            rc = vt_atlas_alpha_scan(&src, &t->alpha, &oe);
        vt_source_close(&src);
        if (rc)
            return vt_error_set(err, rc, "%s: %s", where, oe.message);
        t->alpha_scanned = true;
    }
    *cutout = vt_atlas_alpha_is_cutout(&t->alpha);
    return 0;
}

static void clamp_colour(double dst[3], const double src[3], bool given, double dflt)
{
    for (int k = 0; k < 3; k++)
        dst[k] = !given ? dflt : src[k] > 0 ? src[k] : 0;
}

/* m's constants from its MTL definition mm (NULL: not defined), with the defaults of
 * docs/atlas-format.md: Kd 1 with a map_Kd else 0.8, Ka Ks Ke 0, Ns 0, d from d (else from Tr
 * strictly between 0 and 1, else 1), illum 2 with a non-zero Ks else 1. */
static void set_constants(struct vt_atlas_material *m, const struct vt_mtl_material *mm)
{
    static const double none[3] = {0, 0, 0};
    struct vt_layout_material *f = &m->features;
    unsigned flags = mm ? mm->flags : 0;
    clamp_colour(f->kd, mm ? mm->kd : none, flags & VT_MTL_HAS_KD,
                 m->texture[VT_ATLAS_DIFFUSE] >= 0 ? 1 : 0.8);
    clamp_colour(f->ka, mm ? mm->ka : none, flags & VT_MTL_HAS_KA, 0);
    clamp_colour(f->ks, mm ? mm->ks : none, flags & VT_MTL_HAS_KS, 0);
    clamp_colour(f->ke, mm ? mm->ke : none, flags & VT_MTL_HAS_KE, 0);
    f->ns = (flags & VT_MTL_HAS_NS) && mm->ns > 0 ? mm->ns : 0;
    double d = 1;
    if (flags & VT_MTL_HAS_D)
        d = mm->d;
    else if ((flags & VT_MTL_HAS_TR) && mm->tr > 0 && mm->tr < 1)
        d = 1 - mm->tr; /* Tr 1 alone is MeshLab's opaque (docs/obj-reader.md) */
    f->d = d < 0 ? 0 : d > 1 ? 1 : d;
    bool specular = f->ks[0] > 0 || f->ks[1] > 0 || f->ks[2] > 0;
    f->illum = (flags & VT_MTL_HAS_ILLUM) ? (uint32_t)mm->illum : specular ? 2 : 1;
    f->alpha = VT_LAYOUT_ALPHA_NONE;
    m->alpha_reason = VT_ATLAS_ALPHA_BY_DEFAULT;
}

/* m's alpha mode: the MTL's vt_alpha; else blend when d < 1; else test with a map_d, or with a
 * map_Kd whose alpha is a cut-out (vt_atlas_alpha.h); else none. */
static int set_alpha(struct obj_ctx *c, struct vt_atlas_material *m,
                     const struct vt_mtl_material *mm, const char *mtl_path, struct vts_error *err)
{
    struct vt_layout_material *f = &m->features;
    bool cutout = false;
    if (mm->alpha != VT_MTL_ALPHA_AUTO) {
        f->alpha = mm->alpha - VT_MTL_ALPHA_NONE + VT_LAYOUT_ALPHA_NONE;
        m->alpha_reason = VT_ATLAS_ALPHA_BY_MTL;
    } else if (f->d < 1) {
        f->alpha = VT_LAYOUT_ALPHA_BLEND;
        m->alpha_reason = VT_ATLAS_ALPHA_BY_D;
    } else if (m->texture[VT_ATLAS_ALPHA] >= 0) {
        f->alpha = VT_LAYOUT_ALPHA_TEST;
        m->alpha_reason = VT_ATLAS_ALPHA_BY_MAP_D;
    } else if (m->texture[VT_ATLAS_DIFFUSE] >= 0) {
        char where[VTS_ERROR_MESSAGE_MAX];
        snprintf(where, sizeof where, "'%s':%llu: map_Kd alpha", mtl_path,
                 (unsigned long long)mm->maps[VT_MTL_MAP_KD].line);
        int rc = scan_alpha(c, m->texture[VT_ATLAS_DIFFUSE], where, &cutout, err);
        if (rc)
            return rc;
        f->alpha = cutout ? VT_LAYOUT_ALPHA_TEST : VT_LAYOUT_ALPHA_NONE;
        m->alpha_reason = c->scene->textures[m->texture[VT_ATLAS_DIFFUSE]].has_alpha
                              ? VT_ATLAS_ALPHA_BY_TEXELS
                              : VT_ATLAS_ALPHA_BY_DEFAULT;
    }
    return 0;
}

/* Gives m its constants and textures from the first of the OBJ's MTL files that defines it. */
static int resolve_material(struct obj_ctx *c, struct vt_atlas_material *m, struct vts_error *err)
{
    const struct vt_mtl_material *mm = NULL;
    size_t mi = 0;
    for (size_t i = 0; i < c->mtl_count && !mm; i++)
        if ((mm = vt_mtl_find(&c->mtls[i], m->name)))
            mi = i;
    set_fills(m, mm);
    if (!mm) {
        set_constants(m, NULL);
        if (c->o->warn) {
            char msg[VTS_ERROR_MESSAGE_MAX];
            snprintf(msg, sizeof msg,
                     "'%s':%llu: material '%s' is not defined in any mtllib: constant grey",
                     c->obj_path, (unsigned long long)m->first_line, m->name);
            c->o->warn(c->o->warn_user, msg);
        }
        return 0;
    }
    m->defined = true;
    if (mm->wang_path) {
        /* A pack material: no maps (its faces keep texture coordinates the pack's output is
         * addressed by, which no atlas map could use), Kd 1 unless given (docs/wang.md). */
        m->wang_scale = mm->wang_scale;
        int rc = add_dep(c->scene, mm->wang_path, &m->wang, err);
        if (rc)
            return rc;
        set_constants(m, mm);
        if (!(mm->flags & VT_MTL_HAS_KD))
            m->features.kd[0] = m->features.kd[1] = m->features.kd[2] = 1;
        return set_alpha(c, m, mm, c->mtl_paths[mi], err);
    }
    int rc = add_maps(c, m, mm, c->mtl_paths[mi], err);
    if (rc)
        return rc;
    set_constants(m, mm);
    return set_alpha(c, m, mm, c->mtl_paths[mi], err);
}

int vt_atlas_scene_scan_obj(struct vt_atlas_scene *scene, const char *obj_path,
                            const struct vt_atlas_scene_options *o, struct vts_error *err)
{
    struct obj_ctx c = {.scene = scene, .o = o, .first_new = scene->material_count};
    struct vt_obj_limits limits;
    vt_obj_limits_default(&limits);
    limits.max_line_bytes = o->max_line_bytes;
    struct vt_obj *obj = vt_obj_create(&limits, err);
    if (!obj)
        return err ? err->status : VTS_ERR_NOMEM;
    struct vt_obj_callbacks cb = {.mtllib = on_mtllib, .face = on_face, .user = &c};
    int rc = add_dep(scene, obj_path, &c.obj_path, err);
    if (!rc)
        rc = vt_obj_read(obj, obj_path, &cb, err);
    if (!rc)
        rc = chart_faces(&c, obj, err);
    for (uint32_t i = c.first_new; !rc && i < scene->material_count; i++)
        rc = resolve_material(&c, &scene->materials[i], err);
    vt_obj_destroy(obj);
    for (size_t i = 0; i < c.mtl_count; i++) {
        vt_mtl_release(&c.mtls[i]);
        free(c.mtl_paths[i]);
    }
    free(c.mtls);
    free(c.mtl_paths);
    free(c.face_start);
    free(c.corner_pos);
    free(c.corner_tex);
    free(c.face_group);
    return rc;
}

/* ---- texture lists ---- */

static int add_file_entry(struct vt_atlas_scene *s, const char *name, const char *path,
                          const char *where, const struct vt_atlas_scene_options *o,
                          struct vts_error *err)
{
    struct vt_atlas_scene_index *ix = index_of(s, err);
    if (!ix)
        return VTS_ERR_NOMEM;
    if (vt_strmap_get(&ix->materials, name) >= 0)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "%s '%s' is listed twice", where, name);
    int32_t ti;
    int rc = add_texture(s, path, where, o, &ti, err);
    if (rc || ti < 0)
        return rc; /* a skipped missing file gives no entry */
    uint32_t mi;
    rc = add_material(s, name, &mi, err);
    if (rc)
        return rc;
    struct vt_atlas_material *m = &s->materials[mi];
    m->defined = true;
    m->texture[VT_ATLAS_DIFFUSE] = ti;
    set_constants(m, NULL); /* a listed texture: Kd 1, opaque (its alpha is not read) */
    return 0;
}

/* Strips the line end and trailing blanks of line (*len bytes, updated); returns its first
 * non-blank. */
static char *trim_line(char *line, ssize_t *len)
{
    ssize_t n = *len;
    while (n > 0 && (line[n - 1] == '\n' || line[n - 1] == '\r' || line[n - 1] == ' ' ||
                     line[n - 1] == '\t'))
        line[--n] = 0;
    *len = n;
    while (*line == ' ' || *line == '\t')
        line++;
    return line;
}

/* One non-blank, non-comment line (entry) of the list file, line number no. */
static int list_entry(struct vt_atlas_scene *scene, const char *list_path, uint64_t no,
                      const char *entry, const struct vt_atlas_scene_options *o,
                      struct vts_error *err)
{
    char where[VTS_ERROR_MESSAGE_MAX];
    snprintf(where, sizeof where, "'%s':%llu:", list_path, (unsigned long long)no);
    char *path = vt_obj_resolve_path(list_path, entry);
    if (!path)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    int rc = add_file_entry(scene, entry, path, where, o, err);
    free(path);
    return rc;
}

int vt_atlas_scene_scan_list(struct vt_atlas_scene *scene, const char *list_path,
                             const struct vt_atlas_scene_options *o, struct vts_error *err)
{
    FILE *f = fopen(list_path, "r");
    if (!f)
        return vt_error_set(err, VTS_ERR_IO, "cannot open '%s': %s", list_path, strerror(errno));
    int rc = add_dep(scene, list_path, NULL, err);
    char *line = NULL;
    size_t cap = 0;
    ssize_t len;
    uint64_t no = 0;
    while (!rc && (len = getline(&line, &cap, f)) >= 0) {
        no++;
        char *entry = trim_line(line, &len);
        if (!*entry || *entry == '#')
            continue;
        if ((size_t)len > o->max_line_bytes)
            rc = vt_error_set(err, VTS_ERR_LIMIT, "'%s':%llu: line longer than %zu bytes",
                              list_path, (unsigned long long)no, o->max_line_bytes);
        else
            rc = list_entry(scene, list_path, no, entry, o, err);
    }
    if (!rc && ferror(f))
        rc = vt_error_set(err, VTS_ERR_IO, "cannot read '%s': %s", list_path, strerror(errno));
    free(line);
    fclose(f);
    return rc;
}

int vt_atlas_scene_scan_files(struct vt_atlas_scene *scene, char *const *paths, uint32_t count,
                              const struct vt_atlas_scene_options *o, struct vts_error *err)
{
    for (uint32_t i = 0; i < count; i++) {
        int rc = add_file_entry(scene, paths[i], paths[i], "texture", o, err);
        if (rc)
            return rc;
    }
    return 0;
}

void vt_atlas_scene_release(struct vt_atlas_scene *scene)
{
    if (!scene)
        return;
    for (uint32_t i = 0; i < scene->material_count; i++)
        free(scene->materials[i].name);
    for (uint32_t i = 0; i < scene->texture_count; i++) {
        free(scene->textures[i].path);
        free(scene->textures[i].id);
    }
    for (size_t i = 0; i < scene->dep_count; i++)
        free(scene->deps[i]);
    struct vt_atlas_scene_index *ix = scene->index;
    if (ix) {
        vt_strmap_release(&ix->materials);
        vt_strmap_release(&ix->textures);
        vt_strmap_release(&ix->deps);
        vt_strmap_release(&ix->files);
    }
    free(ix);
    free(scene->materials);
    free(scene->textures);
    free(scene->deps);
    memset(scene, 0, sizeof *scene);
}
