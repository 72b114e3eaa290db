/* vt-atlas input scanning: OBJ faces -> used materials -> MTL maps -> texture headers. */
#include "vt_atlas_scene.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "vt_error.h"
#include "vt_image_input.h"
#include "vt_obj.h"
#include "vts.h"

#define UV_EPS 1e-6

/* ---- a string -> index hash table (open addressing, keys owned by the caller) ---- */

struct strmap {
    const char **keys;
    uint32_t *values;
    size_t capacity, count;
};

static uint64_t hash_str(const char *s)
{
    uint64_t h = 1469598103934665603ull;
    for (; *s; s++)
        h = (h ^ (unsigned char)*s) * 1099511628211ull;
    return h;
}

static int64_t strmap_get(const struct strmap *m, const char *key)
{
    if (!m->capacity)
        return -1;
    for (size_t i = hash_str(key) & (m->capacity - 1);; i = (i + 1) & (m->capacity - 1)) {
        if (!m->keys[i])
            return -1;
        if (strcmp(m->keys[i], key) == 0)
            return m->values[i];
    }
}

static int strmap_put(struct strmap *m, const char *key, uint32_t value)
{
    if ((m->count + 1) * 2 > m->capacity) {
        struct strmap n = {.capacity = m->capacity ? m->capacity * 2 : 64};
        n.keys = calloc(n.capacity, sizeof *n.keys);
        n.values = calloc(n.capacity, sizeof *n.values);
        if (!n.keys || !n.values) {
            free(n.keys);
            free(n.values);
            return VTS_ERR_NOMEM;
        }
        for (size_t i = 0; i < m->capacity; i++)
            if (m->keys[i])
                strmap_put(&n, m->keys[i], m->values[i]);
        free(m->keys);
        free(m->values);
        *m = n;
    }
    size_t i = hash_str(key) & (m->capacity - 1);
    while (m->keys[i])
        i = (i + 1) & (m->capacity - 1);
    m->keys[i] = key;
    m->values[i] = value;
    m->count++;
    return 0;
}

static void strmap_release(struct strmap *m)
{
    free(m->keys);
    free(m->values);
}

struct scene_index {
    struct strmap materials, textures, deps, files; /* files: texture id -> texture */
    size_t texture_capacity, dep_capacity;
};

/* ---- kinds ---- */

static const char *const kind_names[VT_ATLAS_KIND_COUNT] = {"diffuse", "normal",  "specular",
                                                            "alpha",   "ambient", "displacement"};
static const char *const kind_maps[VT_ATLAS_KIND_COUNT] = {"map_Kd", "norm",   "map_Ks",
                                                           "map_d",  "map_Ka", "disp"};

const char *vt_atlas_kind_name(unsigned kind)
{
    return kind < VT_ATLAS_KIND_COUNT ? kind_names[kind] : "?";
}

const char *vt_atlas_kind_map(unsigned kind)
{
    return kind < VT_ATLAS_KIND_COUNT ? kind_maps[kind] : "?";
}

uint32_t vt_atlas_kind_colour(unsigned kind)
{
    switch (kind) {
    case VT_ATLAS_NORMAL:
        return VTS_COLOUR_NORMAL;
    case VT_ATLAS_ALPHA:
    case VT_ATLAS_DISP:
        return VTS_COLOUR_DATA;
    default:
        return VTS_COLOUR_SRGB;
    }
}

/* ---- growing arrays ---- */

static int grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return 0;
    size_t n = *cap ? *cap * 2 : 16;
    while (n < need)
        n *= 2;
    void *q = realloc(*p, n * elem);
    if (!q)
        return VTS_ERR_NOMEM;
    *p = q;
    *cap = n;
    return 0;
}

static struct scene_index *index_of(struct vt_atlas_scene *s)
{
    if (!s->index)
        s->index = calloc(1, sizeof(struct scene_index));
    return s->index;
}

static int add_dep(struct vt_atlas_scene *s, const char *path, struct vts_error *err)
{
    struct scene_index *ix = index_of(s);
    if (!ix)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    if (strmap_get(&ix->deps, path) >= 0)
        return 0;
    char *copy = strdup(path);
    if (grow((void **)&s->deps, &ix->dep_capacity, s->dep_count + 1, sizeof *s->deps) || !copy ||
        strmap_put(&ix->deps, copy, (uint32_t)s->dep_count)) {
        free(copy);
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    }
    s->deps[s->dep_count++] = copy;
    return 0;
}

/* Finds or opens the texture at path (header only); -1 in *index when it is missing and
 * missing_skip. where ("'a.mtl':12: map_Kd") prefixes messages. */
static int add_texture(struct vt_atlas_scene *s, const char *path, const char *where,
                       const struct vt_atlas_scan_options *o, int32_t *index, struct vts_error *err)
{
    struct scene_index *ix = index_of(s);
    if (!ix)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    int64_t found = strmap_get(&ix->textures, path);
    if (found >= 0) {
        *index = (int32_t)found;
        return 0;
    }
    struct stat st;
    if (stat(path, &st) != 0) {
        int e = errno;
        char msg[VTS_ERROR_MESSAGE_MAX];
        snprintf(msg, sizeof msg, "%s '%s': %s", where, path, strerror(e));
        if (o->missing_skip && e == ENOENT) {
            if (o->warn) {
                strncat(msg, " (skipped)", sizeof msg - strlen(msg) - 1);
                o->warn(msg);
            }
            *index = -1;
            return 0;
        }
        return vt_error_set(err, VTS_ERR_IO, "%s", msg);
    }
    char id[64];
    snprintf(id, sizeof id, "%llu:%llu", (unsigned long long)st.st_dev,
             (unsigned long long)st.st_ino);
    found = strmap_get(&ix->files, id);
    if (found >= 0) { /* another path to a file already read */
        *index = (int32_t)found;
        return add_dep(s, path, err);
    }
    if (s->texture_count >= o->max_textures)
        return vt_error_set(err, VTS_ERR_LIMIT, "%s '%s': more than %u textures (--max-textures)",
                            where, path, o->max_textures);
    struct vt_input_limits limits = {.max_pixels = o->max_pixels};
    struct vt_source src;
    struct vts_error ie;
    int rc = vt_image_input_open(path, &limits, &src, &ie);
    if (rc)
        return vt_error_set(err, rc, "%s: %s", where, ie.message);
    struct vt_atlas_texture t = {
        .width = src.info.width, .height = src.info.height, .channels = src.info.channels};
    vt_source_close(&src);
    t.path = strdup(path);
    t.id = strdup(id);
    if (grow((void **)&s->textures, &ix->texture_capacity, (size_t)s->texture_count + 1,
             sizeof *s->textures) ||
        !t.path || !t.id || strmap_put(&ix->textures, t.path, s->texture_count) ||
        strmap_put(&ix->files, t.id, s->texture_count)) {
        free(t.path);
        free(t.id);
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    }
    *index = (int32_t)s->texture_count;
    s->textures[s->texture_count++] = t;
    return add_dep(s, path, err);
}

static int add_material(struct vt_atlas_scene *s, const char *name, uint32_t *index,
                        struct vts_error *err)
{
    struct scene_index *ix = index_of(s);
    if (!ix)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    int64_t found = strmap_get(&ix->materials, name);
    if (found >= 0) {
        *index = (uint32_t)found;
        return 0;
    }
    size_t cap = s->material_count;
    /* Amortised growth: capacity is the next power of two of the count. */
    if ((cap & (cap - 1)) == 0) {
        struct vt_atlas_material *n = realloc(s->materials, (cap ? cap * 2 : 1) * sizeof *n);
        if (!n)
            return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        s->materials = n;
    }
    struct vt_atlas_material *m = &s->materials[s->material_count];
    memset(m, 0, sizeof *m);
    m->name = strdup(name);
    if (!m->name || strmap_put(&ix->materials, m->name, s->material_count)) {
        free(m->name);
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    }
    for (unsigned k = 0; k < VT_ATLAS_KIND_COUNT; k++)
        m->texture[k] = -1;
    m->umin = m->vmin = INFINITY;
    m->umax = m->vmax = -INFINITY;
    *index = s->material_count++;
    return 0;
}

/* ---- OBJ ---- */

struct obj_ctx {
    struct vt_atlas_scene *scene;
    const struct vt_atlas_scan_options *o;
    const char *obj_path;
    struct vt_mtl *mtls;
    char **mtl_paths;
    size_t mtl_count;
    uint32_t last; /* material of the previous face */
    const char *last_name;
    bool have_last;
    uint32_t first_new; /* materials from here on were first used by this OBJ */
};

static int on_mtllib(void *user, const struct vt_obj *obj, const char *mtl_path, uint64_t line,
                     struct vts_error *err)
{
    (void)obj;
    struct obj_ctx *c = user;
    for (size_t i = 0; i < c->mtl_count; i++)
        if (strcmp(c->mtl_paths[i], mtl_path) == 0)
            return 0;
    struct vt_mtl *m = realloc(c->mtls, (c->mtl_count + 1) * sizeof *m);
    if (m)
        c->mtls = m;
    char **p = realloc(c->mtl_paths, (c->mtl_count + 1) * sizeof *p);
    if (p)
        c->mtl_paths = p;
    char *copy = strdup(mtl_path);
    if (!m || !p || !copy) {
        free(copy);
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    }
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
    return add_dep(c->scene, mtl_path, err);
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
        m->umin = fmin(m->umin, uv[3 * t]);
        m->umax = fmax(m->umax, uv[3 * t]);
        m->vmin = fmin(m->vmin, uv[3 * t + 1]);
        m->vmax = fmax(m->vmax, uv[3 * t + 1]);
    }
    if (!all_uv)
        return 0;
    for (uint32_t i = 1; i + 1 < f->corner_count; i++) {
        const struct vt_obj_corner *a = &f->corners[0], *b = &f->corners[i],
                                   *d = &f->corners[i + 1];
        m->world_area += tri_area3(pos + 3 * a->v, pos + 3 * b->v, pos + 3 * d->v);
        m->uv_area += tri_area2(uv + 3 * a->vt, uv + 3 * b->vt, uv + 3 * d->vt);
    }
    return 0;
}

/* The line of the last map statement of kind in the newmtl block at material_line (the reader
 * keeps the last one), or material_line when it cannot be found. */
static uint64_t map_line(const char *mtl_path, uint64_t material_line, unsigned mtl_kind)
{
    static const char *const names[VT_MTL_MAP_COUNT][3] = {
        {"map_Kd"}, {"map_Ka"}, {"map_Ks"}, {"map_d"}, {"map_Bump", "bump"}, {"norm"}, {"disp"}};
    FILE *f = fopen(mtl_path, "r");
    if (!f)
        return material_line;
    char buf[512];
    uint64_t line = 0, found = material_line;
    bool at_start = true;
    while (fgets(buf, sizeof buf, f)) {
        bool whole = strchr(buf, '\n') != NULL;
        if (at_start && ++line > material_line) {
            char word[32] = "";
            sscanf(buf, " %31s", word);
            if (strcmp(word, "newmtl") == 0)
                break;
            for (int k = 0; k < 3 && names[mtl_kind][k]; k++)
                if (strcasecmp(word, names[mtl_kind][k]) == 0)
                    found = line;
        }
        at_start = whole;
    }
    fclose(f);
    return found;
}

static void set_fill(double fill[4], const double rgb[3], double a)
{
    for (int i = 0; i < 3; i++)
        fill[i] = rgb[i] < 0 ? 0 : rgb[i] > 1 ? 1 : rgb[i];
    fill[3] = a < 0 ? 0 : a > 1 ? 1 : a;
}

static int resolve_material(struct obj_ctx *c, struct vt_atlas_material *m, struct vts_error *err)
{
    static const int kind_of[VT_MTL_MAP_COUNT] = {
        VT_ATLAS_DIFFUSE, VT_ATLAS_AMBIENT, VT_ATLAS_SPECULAR, VT_ATLAS_ALPHA,
        VT_ATLAS_NORMAL,  VT_ATLAS_NORMAL,  VT_ATLAS_DISP};
    const struct vt_mtl_material *mm = NULL;
    size_t mi = 0;
    for (size_t i = 0; i < c->mtl_count && !mm; i++)
        if ((mm = vt_mtl_find(&c->mtls[i], m->name)))
            mi = i;
    static const double grey[3] = {0.8, 0.8, 0.8}, black[3] = {0, 0, 0}, half[3] = {0.5, 0.5, 1};
    set_fill(m->fill[VT_ATLAS_DIFFUSE], mm && (mm->flags & VT_MTL_HAS_KD) ? mm->kd : grey, 1);
    set_fill(m->fill[VT_ATLAS_NORMAL], half, 1);
    set_fill(m->fill[VT_ATLAS_SPECULAR], mm && (mm->flags & VT_MTL_HAS_KS) ? mm->ks : black, 1);
    double d = mm && (mm->flags & VT_MTL_HAS_D) ? mm->d : 1;
    double dd[3] = {d, d, d};
    set_fill(m->fill[VT_ATLAS_ALPHA], dd, 1);
    set_fill(m->fill[VT_ATLAS_AMBIENT], mm && (mm->flags & VT_MTL_HAS_KA) ? mm->ka : black, 1);
    set_fill(m->fill[VT_ATLAS_DISP], black, 1);
    if (!mm) {
        if (c->o->warn) {
            char msg[VTS_ERROR_MESSAGE_MAX];
            snprintf(msg, sizeof msg,
                     "'%s':%llu: material '%s' is not defined in any mtllib: constant grey",
                     c->obj_path, (unsigned long long)m->first_line, m->name);
            c->o->warn(msg);
        }
        return 0;
    }
    m->defined = true;
    /* norm before bump, so that a material with both keeps its normal map. */
    static const unsigned order[VT_MTL_MAP_COUNT] = {
        VT_MTL_MAP_KD,   VT_MTL_MAP_KA,   VT_MTL_MAP_KS,  VT_MTL_MAP_D,
        VT_MTL_MAP_NORM, VT_MTL_MAP_BUMP, VT_MTL_MAP_DISP};
    for (unsigned j = 0; j < VT_MTL_MAP_COUNT; j++) {
        unsigned k = order[j];
        if (!mm->maps[k].path || m->texture[kind_of[k]] >= 0)
            continue;
        char where[VTS_ERROR_MESSAGE_MAX];
        static const char *const stmt[VT_MTL_MAP_COUNT] = {"map_Kd", "map_Ka", "map_Ks", "map_d",
                                                           "bump",   "norm",   "disp"};
        snprintf(where, sizeof where, "'%s':%llu: %s", c->mtl_paths[mi],
                 (unsigned long long)map_line(c->mtl_paths[mi], mm->line, k), stmt[k]);
        int rc = add_texture(c->scene, mm->maps[k].path, where, c->o, &m->texture[kind_of[k]], err);
        if (rc)
            return rc;
    }
    return 0;
}

int vt_atlas_scan_obj(struct vt_atlas_scene *scene, const char *obj_path,
                      const struct vt_atlas_scan_options *o, struct vts_error *err)
{
    struct obj_ctx c = {
        .scene = scene, .o = o, .obj_path = obj_path, .first_new = scene->material_count};
    struct vt_obj_limits limits;
    vt_obj_limits_default(&limits);
    limits.max_line_bytes = o->max_line_bytes;
    struct vt_obj *obj = vt_obj_create(&limits, err);
    if (!obj)
        return err ? err->status : VTS_ERR_NOMEM;
    struct vt_obj_callbacks cb = {.mtllib = on_mtllib, .face = on_face, .user = &c};
    int rc = add_dep(scene, obj_path, err);
    if (!rc)
        rc = vt_obj_read(obj, obj_path, &cb, err);
    for (uint32_t i = c.first_new; !rc && i < scene->material_count; i++)
        rc = resolve_material(&c, &scene->materials[i], err);
    vt_obj_destroy(obj);
    for (size_t i = 0; i < c.mtl_count; i++) {
        vt_mtl_release(&c.mtls[i]);
        free(c.mtl_paths[i]);
    }
    free(c.mtls);
    free(c.mtl_paths);
    return rc;
}

/* ---- texture lists ---- */

static int add_file_entry(struct vt_atlas_scene *s, const char *name, const char *path,
                          const char *where, const struct vt_atlas_scan_options *o,
                          struct vts_error *err)
{
    struct scene_index *ix = index_of(s);
    if (!ix)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    if (strmap_get(&ix->materials, name) >= 0)
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
    return 0;
}

int vt_atlas_scan_list(struct vt_atlas_scene *scene, const char *list_path,
                       const struct vt_atlas_scan_options *o, struct vts_error *err)
{
    FILE *f = fopen(list_path, "r");
    if (!f)
        return vt_error_set(err, VTS_ERR_IO, "cannot open '%s': %s", list_path, strerror(errno));
    int rc = add_dep(scene, list_path, err);
    char *line = NULL;
    size_t cap = 0;
    ssize_t len;
    uint64_t no = 0;
    while (!rc && (len = getline(&line, &cap, f)) >= 0) {
        no++;
        while (len > 0 && (line[len - 1] == '\n' || line[len - 1] == '\r' || line[len - 1] == ' ' ||
                           line[len - 1] == '\t'))
            line[--len] = 0;
        char *p = line;
        while (*p == ' ' || *p == '\t')
            p++;
        if (!*p || *p == '#')
            continue;
        if ((size_t)len > o->max_line_bytes) {
            rc = vt_error_set(err, VTS_ERR_LIMIT, "'%s':%llu: line longer than %zu bytes",
                              list_path, (unsigned long long)no, o->max_line_bytes);
            break;
        }
        char where[VTS_ERROR_MESSAGE_MAX];
        snprintf(where, sizeof where, "'%s':%llu:", list_path, (unsigned long long)no);
        char *path = vt_obj_resolve_path(list_path, p);
        if (!path) {
            rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
            break;
        }
        rc = add_file_entry(scene, p, path, where, o, err);
        free(path);
    }
    if (!rc && ferror(f))
        rc = vt_error_set(err, VTS_ERR_IO, "cannot read '%s': %s", list_path, strerror(errno));
    free(line);
    fclose(f);
    return rc;
}

int vt_atlas_scan_files(struct vt_atlas_scene *scene, char *const *paths, uint32_t count,
                        const struct vt_atlas_scan_options *o, struct vts_error *err)
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
    struct scene_index *ix = scene->index;
    if (ix) {
        strmap_release(&ix->materials);
        strmap_release(&ix->textures);
        strmap_release(&ix->deps);
        strmap_release(&ix->files);
    }
    free(ix);
    free(scene->materials);
    free(scene->textures);
    free(scene->deps);
    memset(scene, 0, sizeof *scene);
}
