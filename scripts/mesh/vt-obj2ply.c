/* vt-obj2ply: the OBJ side of the optional MeshLab stage (scripts/mesh-clean, docs/mesh-clean.md).
 *
 *   vt-obj2ply IN.obj -o OUT.ply
 *       Writes IN.obj as a binary PLY that meshlabserver 2020.09 reads (it aborts on every OBJ):
 *       float x y z per vertex; per face (polygons fanned into triangles) the vertex indices, the
 *       six wedge texture coordinates and a texnumber. Each material used becomes one
 *       "comment TextureFile vt-material-N" line (N in order of first use), so that the material
 *       MeshLab writes for a face names the original material, whatever its textures are.
 *   vt-obj2ply --restore IN.obj MESHLAB.obj -o OUT.obj
 *       Rewrites the OBJ that meshlabserver wrote from that PLY: every "usemtl material_K" gets the
 *       original material name back (looked up through MeshLab's MTL: map_Kd vt-material-N), and
 *       mtllib names IN.obj's own MTL files (relative to OUT.obj), so materials keep their colours,
 *       options and every map, not MeshLab's copies (Kd 1 1 1, Tr 1).
 *   vt-obj2ply --check IN.obj OUT.obj [--same-faces] [--tolerance T]
 *       Compares: every face of OUT.obj has a material whose map_Kd is the same file as in IN.obj
 *       (resolved paths); with --same-faces, face I of OUT.obj has the material of triangle I of
 *       IN.obj and the same (position, uv) corners as a set, within T (positions: T * max(1, |x|),
 *       texcoords: T; default 1e-6). Prints "vertices A -> B, faces C -> D".
 * Exit status 0 ok, 1 bad input or check failed, 2 usage. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <errno.h>
#include <inttypes.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tool_common.h"
#include "vt_atomic_file.h"
#include "vt_checked.h"
#include "vt_error.h"
#include "vt_obj.h"

#define TOKEN_PREFIX "vt-material-"

/* A triangle of a fanned face: corner indices into the reader's arrays and a material index. */
struct tri {
    uint32_t v[3];
    uint32_t vt[3]; /* VT_OBJ_NONE: (0, 0) */
    uint32_t material;
    uint64_t line;
};

/* One OBJ read whole: the reader (positions, texcoords), the triangles, the materials in order of
 * first use and the MTL files named by mtllib lines (resolved). */
struct mesh {
    const char *path;
    struct vt_obj *obj;
    struct tri *tris;
    size_t tri_count, tri_cap;
    char **materials;
    uint32_t material_count, material_cap;
    char **mtllibs;
    size_t mtllib_count, mtllib_cap;
    struct vt_mtl *mtls; /* one per mtllib, read by mesh_read_mtls() */
};

static int push(void **arr, size_t *count, size_t *cap, size_t elem, struct vt_error *err)
{
    if (*count == *cap) {
        size_t ncap = *cap ? *cap * 2 : 64;
        size_t bytes;
        if (ncap < *cap || !vt_size_mul(ncap, elem, &bytes))
            return vt_error_set(err, VT_ERR_LIMIT, "too many elements");
        void *n = realloc(*arr, bytes);
        if (!n)
            return vt_error_set(err, VT_ERR_NOMEM, "out of memory");
        *arr = n;
        *cap = ncap;
    }
    (*count)++;
    return 0;
}

static int mesh_mtllib(void *user, const struct vt_obj *obj, const char *mtl_path, uint64_t line,
                       struct vt_error *err)
{
    (void)obj;
    (void)line;
    struct mesh *m = user;
    for (size_t i = 0; i < m->mtllib_count; i++)
        if (!strcmp(m->mtllibs[i], mtl_path))
            return 0;
    char *copy = strdup(mtl_path);
    if (!copy)
        return vt_error_set(err, VT_ERR_NOMEM, "out of memory");
    int rc = push((void **)&m->mtllibs, &m->mtllib_count, &m->mtllib_cap, sizeof(char *), err);
    if (rc) {
        free(copy);
        return rc;
    }
    m->mtllibs[m->mtllib_count - 1] = copy;
    return 0;
}

static int mesh_material_index(struct mesh *m, const char *name, uint32_t *out,
                               struct vt_error *err)
{
    for (uint32_t i = m->material_count; i-- > 0;)
        if (!strcmp(m->materials[i], name)) {
            *out = i;
            return 0;
        }
    char *copy = strdup(name);
    if (!copy)
        return vt_error_set(err, VT_ERR_NOMEM, "out of memory");
    size_t count = m->material_count, cap = m->material_cap;
    int rc = push((void **)&m->materials, &count, &cap, sizeof(char *), err);
    if (rc || count > INT32_MAX) {
        free(copy);
        return rc ? rc : vt_error_set(err, VT_ERR_LIMIT, "'%s': too many materials", m->path);
    }
    m->material_count = (uint32_t)count;
    m->material_cap = (uint32_t)cap;
    m->materials[count - 1] = copy;
    *out = (uint32_t)(count - 1);
    return 0;
}

static int mesh_face(void *user, const struct vt_obj *obj, const struct vt_obj_face *face,
                     struct vt_error *err)
{
    (void)obj;
    struct mesh *m = user;
    uint32_t material = 0;
    int rc = mesh_material_index(m, face->material, &material, err);
    if (rc)
        return rc;
    for (uint32_t i = 1; i + 1 < face->corner_count; i++) {
        rc = push((void **)&m->tris, &m->tri_count, &m->tri_cap, sizeof(struct tri), err);
        if (rc)
            return rc;
        struct tri *t = &m->tris[m->tri_count - 1];
        const struct vt_obj_corner *c[3] = {&face->corners[0], &face->corners[i],
                                            &face->corners[i + 1]};
        for (int k = 0; k < 3; k++) {
            t->v[k] = c[k]->v;
            t->vt[k] = c[k]->vt;
        }
        t->material = material;
        t->line = face->line;
    }
    return 0;
}

static void mesh_release(struct mesh *m)
{
    vt_obj_destroy(m->obj);
    free(m->tris);
    for (uint32_t i = 0; i < m->material_count; i++)
        free(m->materials[i]);
    free(m->materials);
    for (size_t i = 0; i < m->mtllib_count; i++) {
        free(m->mtllibs[i]);
        if (m->mtls)
            vt_mtl_release(&m->mtls[i]);
    }
    free(m->mtllibs);
    free(m->mtls);
    memset(m, 0, sizeof(*m));
}

static int mesh_read(struct mesh *m, const char *path, struct vt_error *err)
{
    memset(m, 0, sizeof(*m));
    m->path = path;
    m->obj = vt_obj_create(NULL, err);
    if (!m->obj)
        return err->status;
    struct vt_obj_callbacks cb = {.mtllib = mesh_mtllib, .face = mesh_face, .user = m};
    return vt_obj_read(m->obj, path, &cb, err);
}

static int mesh_read_mtls(struct mesh *m, struct vt_error *err)
{
    m->mtls = calloc(m->mtllib_count ? m->mtllib_count : 1, sizeof(*m->mtls));
    if (!m->mtls)
        return vt_error_set(err, VT_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < m->mtllib_count; i++) {
        int rc = vt_mtl_read(m->mtllibs[i], NULL, &m->mtls[i], err);
        if (rc)
            return rc;
    }
    return 0;
}

/* The material named name in the mesh's MTL files (the last file that defines it), or NULL. */
static const struct vt_mtl_material *mesh_find_material(const struct mesh *m, const char *name)
{
    const struct vt_mtl_material *found = NULL;
    for (size_t i = 0; i < m->mtllib_count; i++) {
        const struct vt_mtl_material *mat = vt_mtl_find(&m->mtls[i], name);
        if (mat)
            found = mat;
    }
    return found;
}

/* ---- PLY writer ---- */

struct out_buf {
    struct vt_atomic_file file;
    unsigned long long offset;
    size_t used;
    unsigned char data[1 << 16];
};

static int out_flush(struct out_buf *o, struct vt_error *err)
{
    int rc = vt_atomic_file_pwrite(&o->file, o->data, o->used, o->offset, err);
    o->offset += o->used;
    o->used = 0;
    return rc;
}

static int out_write(struct out_buf *o, const void *p, size_t n, struct vt_error *err)
{
    const unsigned char *b = p;
    while (n) {
        if (o->used == sizeof(o->data)) {
            int rc = out_flush(o, err);
            if (rc)
                return rc;
        }
        size_t k = sizeof(o->data) - o->used;
        if (k > n)
            k = n;
        memcpy(o->data + o->used, b, k);
        o->used += k;
        b += k;
        n -= k;
    }
    return 0;
}

static int out_str(struct out_buf *o, const char *s, struct vt_error *err)
{
    return out_write(o, s, strlen(s), err);
}

static void put_u32le(unsigned char *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (unsigned char)(v >> (8 * i));
}

static void put_f32le(unsigned char *p, double d)
{
    float f = (float)d;
    uint32_t u;
    memcpy(&u, &f, 4);
    put_u32le(p, u);
}

static int write_ply(const struct mesh *m, const char *out_path, struct vt_error *err)
{
    uint32_t nv = vt_obj_position_count(m->obj);
    if (nv > INT32_MAX || m->tri_count > INT32_MAX)
        return vt_error_set(err, VT_ERR_LIMIT, "'%s': too large for a PLY with int indices",
                            m->path);
    struct out_buf *o = malloc(sizeof(*o));
    if (!o)
        return vt_error_set(err, VT_ERR_NOMEM, "out of memory");
    o->offset = 0;
    o->used = 0;
    int rc = vt_atomic_file_create(&o->file, out_path, "tmp", err);
    if (rc) {
        free(o);
        return rc;
    }
    char line[128];
    rc = out_str(o, "ply\nformat binary_little_endian 1.0\ncomment written by vt-obj2ply\n", err);
    for (uint32_t i = 0; !rc && i < m->material_count; i++) {
        snprintf(line, sizeof(line), "comment TextureFile " TOKEN_PREFIX "%" PRIu32 "\n", i);
        rc = out_str(o, line, err);
    }
    if (!rc) {
        snprintf(line, sizeof(line), "element vertex %" PRIu32 "\n", nv);
        rc = out_str(o, line, err);
    }
    if (!rc)
        rc = out_str(o, "property float x\nproperty float y\nproperty float z\n", err);
    if (!rc) {
        snprintf(line, sizeof(line), "element face %zu\n", m->tri_count);
        rc = out_str(o, line, err);
    }
    if (!rc)
        rc = out_str(o,
                     "property list uchar int vertex_indices\n"
                     "property list uchar float texcoord\n"
                     "property int texnumber\nend_header\n",
                     err);
    const double *pos = vt_obj_positions(m->obj);
    for (uint32_t i = 0; !rc && i < nv; i++) {
        unsigned char b[12];
        for (int k = 0; k < 3; k++)
            put_f32le(b + 4 * k, pos[3 * (size_t)i + (size_t)k]);
        rc = out_write(o, b, sizeof(b), err);
    }
    const double *tex = vt_obj_texcoords(m->obj);
    for (size_t i = 0; !rc && i < m->tri_count; i++) {
        const struct tri *t = &m->tris[i];
        unsigned char b[1 + 12 + 1 + 24 + 4];
        b[0] = 3;
        for (int k = 0; k < 3; k++)
            put_u32le(b + 1 + 4 * k, t->v[k]);
        b[13] = 6;
        for (int k = 0; k < 3; k++) {
            double u = 0, v = 0;
            if (t->vt[k] != VT_OBJ_NONE) {
                u = tex[3 * (size_t)t->vt[k]];
                v = tex[3 * (size_t)t->vt[k] + 1];
            }
            put_f32le(b + 14 + 8 * k, u);
            put_f32le(b + 18 + 8 * k, v);
        }
        put_u32le(b + 38, t->material);
        rc = out_write(o, b, sizeof(b), err);
    }
    if (!rc)
        rc = out_flush(o, err);
    if (!rc)
        rc = vt_atomic_file_commit(&o->file, err);
    else
        vt_atomic_file_abort(&o->file);
    free(o);
    return rc;
}

/* ---- restore ---- */

/* Absolute, normalised form of path (realpath of its directory + its name). malloc'ed or NULL. */
static char *absolute_path(const char *path)
{
    char *copy = strdup(path);
    if (!copy)
        return NULL;
    char *slash = strrchr(copy, '/');
    const char *dir = ".", *name = copy;
    if (slash == copy) {
        dir = "/";
        name = copy + 1;
    } else if (slash) {
        *slash = '\0';
        dir = copy;
        name = slash + 1;
    }
    char *rdir = realpath(dir, NULL);
    char *res = NULL;
    if (rdir) {
        size_t n = strlen(rdir) + strlen(name) + 2;
        res = malloc(n);
        if (res)
            snprintf(res, n, "%s%s%s", rdir, strcmp(rdir, "/") ? "/" : "", name);
    }
    free(rdir);
    free(copy);
    return res;
}

/* target relative to directory dir (both absolute). malloc'ed or NULL. */
static char *relative_path(const char *dir, const char *target)
{
    size_t dir_len = strlen(dir), common = 0, i = 0;
    while (dir[i] && dir[i] == target[i]) {
        i++;
        if (dir[i - 1] == '/')
            common = i;
    }
    if (!dir[i] && target[i] == '/')
        common = i + 1; /* target is inside dir */
    const char *rest = common <= dir_len ? dir + common : "";
    size_t ups = 0;
    for (const char *p = rest; *p; p++)
        if (*p != '/' && (p == rest || p[-1] == '/'))
            ups++;
    size_t n = 3 * ups + strlen(target + common) + 1;
    char *res = malloc(n);
    if (!res)
        return NULL;
    res[0] = '\0';
    for (size_t k = 0; k < ups; k++)
        strcat(res, "../");
    strcat(res, target + common);
    return res;
}

static int restore(const struct mesh *orig, const char *meshlab_path, const char *out_path,
                   struct vt_error *err)
{
    struct mesh ml;
    int rc = mesh_read(&ml, meshlab_path, err);
    if (!rc)
        rc = mesh_read_mtls(&ml, err);
    FILE *in = NULL;
    char *buf = NULL, *mtllib_line = NULL, *out_dir = NULL;
    size_t cap = 0;
    struct out_buf *o = NULL;
    bool created = false;
    if (rc)
        goto cleanup;
    /* the mtllib line: IN.obj's MTL files relative to OUT.obj's directory */
    out_dir = absolute_path(out_path);
    if (!out_dir) {
        rc = vt_error_set(err, VT_ERR_IO, "'%s': cannot resolve the directory: %s", out_path,
                          strerror(errno));
        goto cleanup;
    }
    char *last = strrchr(out_dir, '/');
    if (last)
        last[last == out_dir ? 1 : 0] = '\0';
    size_t len = strlen("mtllib") + 2;
    mtllib_line = malloc(len);
    if (!mtllib_line) {
        rc = vt_error_set(err, VT_ERR_NOMEM, "out of memory");
        goto cleanup;
    }
    strcpy(mtllib_line, "mtllib");
    for (size_t i = 0; i < orig->mtllib_count; i++) {
        char *abs = absolute_path(orig->mtllibs[i]);
        char *rel = abs ? relative_path(out_dir, abs) : NULL;
        free(abs);
        if (!rel) {
            rc = vt_error_set(err, VT_ERR_IO, "'%s': cannot resolve the path", orig->mtllibs[i]);
            goto cleanup;
        }
        len += strlen(rel) + 1;
        char *n = realloc(mtllib_line, len);
        if (!n) {
            free(rel);
            rc = vt_error_set(err, VT_ERR_NOMEM, "out of memory");
            goto cleanup;
        }
        mtllib_line = n;
        strcat(mtllib_line, " ");
        strcat(mtllib_line, rel);
        free(rel);
    }
    strcat(mtllib_line, "\n");

    in = fopen(meshlab_path, "r");
    if (!in) {
        rc = vt_error_set(err, VT_ERR_IO, "'%s': %s", meshlab_path, strerror(errno));
        goto cleanup;
    }
    o = malloc(sizeof(*o));
    if (!o) {
        rc = vt_error_set(err, VT_ERR_NOMEM, "out of memory");
        goto cleanup;
    }
    o->offset = 0;
    o->used = 0;
    rc = vt_atomic_file_create(&o->file, out_path, "tmp", err);
    if (rc)
        goto cleanup;
    created = true;
    rc = out_str(o, "# vt-obj2ply --restore: MeshLab output with the original materials\n", err);
    bool mtllib_done = false, material_seen = false;
    uint64_t lineno = 0;
    ssize_t n;
    while (!rc && (n = getline(&buf, &cap, in)) >= 0) {
        lineno++;
        const char *p = buf;
        while (*p == ' ' || *p == '\t')
            p++;
        if (!strncmp(p, "mtllib", 6) && (p[6] == ' ' || p[6] == '\t')) {
            if (!mtllib_done && orig->mtllib_count)
                rc = out_str(o, mtllib_line, err);
            mtllib_done = true;
            continue;
        }
        if (!strncmp(p, "usemtl", 6) && (p[6] == ' ' || p[6] == '\t')) {
            char name[256];
            if (sscanf(p + 6, " %255s", name) != 1) {
                rc = vt_error_set(err, VT_ERR_BAD_INPUT, "'%s':%" PRIu64 ": bad usemtl",
                                  meshlab_path, lineno);
                break;
            }
            const struct vt_mtl_material *mat = mesh_find_material(&ml, name);
            const char *file = mat ? mat->maps[VT_MTL_MAP_KD].file : NULL;
            uint32_t index;
            if (!file || strncmp(file, TOKEN_PREFIX, strlen(TOKEN_PREFIX)) ||
                vt_parse_u32(file + strlen(TOKEN_PREFIX), 0, UINT32_MAX, &index) ||
                index >= orig->material_count) {
                rc = vt_error_set(err, VT_ERR_BAD_INPUT,
                                  "'%s':%" PRIu64 ": material '%s' does not name one of '%s'"
                                  " (map_Kd '%s')",
                                  meshlab_path, lineno, name, orig->path, file ? file : "");
                break;
            }
            const char *orig_name = orig->materials[index];
            if (!orig_name[0]) {
                /* faces before any usemtl: expressible only before the first material */
                if (material_seen) {
                    rc = vt_error_set(err, VT_ERR_BAD_INPUT,
                                      "'%s':%" PRIu64 ": faces without a material come after"
                                      " faces with one; OBJ cannot say that",
                                      meshlab_path, lineno);
                    break;
                }
                continue;
            }
            material_seen = true;
            rc = out_str(o, "usemtl ", err);
            if (!rc)
                rc = out_str(o, orig_name, err);
            if (!rc)
                rc = out_str(o, "\n", err);
            continue;
        }
        rc = out_write(o, buf, (size_t)n, err);
    }
    if (!rc && ferror(in))
        rc = vt_error_set(err, VT_ERR_IO, "'%s': read error", meshlab_path);
    if (!rc)
        rc = out_flush(o, err);
    if (!rc) {
        rc = vt_atomic_file_commit(&o->file, err);
        created = false;
    }
cleanup:
    if (created)
        vt_atomic_file_abort(&o->file);
    free(o);
    if (in)
        fclose(in);
    free(buf);
    free(mtllib_line);
    free(out_dir);
    mesh_release(&ml);
    return rc;
}

/* ---- check ---- */

/* The resolved map_Kd path of material index i of m ("" when it has none), made absolute. */
static char *material_texture(const struct mesh *m, uint32_t i)
{
    const struct vt_mtl_material *mat = mesh_find_material(m, m->materials[i]);
    const char *path = mat ? mat->maps[VT_MTL_MAP_KD].path : NULL;
    if (!path)
        return strdup("");
    char *r = realpath(path, NULL);
    return r ? r : absolute_path(path);
}

static void corner(const struct mesh *m, const struct tri *t, int k, double out[5])
{
    const double *p = vt_obj_positions(m->obj) + 3 * (size_t)t->v[k];
    out[0] = p[0];
    out[1] = p[1];
    out[2] = p[2];
    out[3] = out[4] = 0;
    if (t->vt[k] != VT_OBJ_NONE) {
        const double *uv = vt_obj_texcoords(m->obj) + 3 * (size_t)t->vt[k];
        out[3] = uv[0];
        out[4] = uv[1];
    }
}

static bool corner_close(const double a[5], const double b[5], double tol)
{
    for (int i = 0; i < 5; i++) {
        double scale = i < 3 ? fmax(1.0, fabs(a[i])) : 1.0;
        if (!(fabs(a[i] - b[i]) <= tol * scale))
            return false;
    }
    return true;
}

static int check(const struct mesh *a, const struct mesh *b, bool same_faces, double tol,
                 struct vt_error *err)
{
    int rc = 0;
    char **ta = calloc(a->material_count + 1u, sizeof(char *));
    char **tb = calloc(b->material_count + 1u, sizeof(char *));
    if (!ta || !tb) {
        rc = vt_error_set(err, VT_ERR_NOMEM, "out of memory");
        goto cleanup;
    }
    for (uint32_t i = 0; i < a->material_count; i++)
        if (!(ta[i] = material_texture(a, i))) {
            rc = vt_error_set(err, VT_ERR_NOMEM, "out of memory");
            goto cleanup;
        }
    for (uint32_t i = 0; i < b->material_count; i++) {
        if (!(tb[i] = material_texture(b, i))) {
            rc = vt_error_set(err, VT_ERR_NOMEM, "out of memory");
            goto cleanup;
        }
        bool known = false;
        for (uint32_t j = 0; j < a->material_count && !known; j++)
            known = !strcmp(a->materials[j], b->materials[i]) && !strcmp(ta[j], tb[i]);
        if (!known) {
            rc = vt_error_set(err, VT_ERR_BAD_INPUT,
                              "'%s': material '%s' (texture '%s') is not a material of '%s' with"
                              " that texture",
                              b->path, b->materials[i], tb[i], a->path);
            goto cleanup;
        }
    }
    for (size_t i = 0; i < b->tri_count; i++) {
        const struct tri *t = &b->tris[i];
        for (int k = 0; k < 3; k++)
            if (t->vt[k] == VT_OBJ_NONE) {
                rc = vt_error_set(err, VT_ERR_BAD_INPUT,
                                  "'%s':%" PRIu64 ": a corner has no texture coordinate", b->path,
                                  t->line);
                goto cleanup;
            }
    }
    if (same_faces) {
        if (a->tri_count != b->tri_count) {
            rc = vt_error_set(err, VT_ERR_BAD_INPUT, "'%s': %zu triangles, '%s' has %zu", b->path,
                              b->tri_count, a->path, a->tri_count);
            goto cleanup;
        }
        for (size_t i = 0; i < a->tri_count; i++) {
            const struct tri *x = &a->tris[i], *y = &b->tris[i];
            if (strcmp(a->materials[x->material], b->materials[y->material])) {
                rc = vt_error_set(err, VT_ERR_BAD_INPUT,
                                  "'%s':%" PRIu64 ": material '%s', was '%s' ('%s':%" PRIu64 ")",
                                  b->path, y->line, b->materials[y->material],
                                  a->materials[x->material], a->path, x->line);
                goto cleanup;
            }
            bool used[3] = {false, false, false};
            for (int k = 0; k < 3; k++) {
                double ca[5], cb[5];
                corner(a, x, k, ca);
                bool found = false;
                for (int j = 0; j < 3 && !found; j++) {
                    if (used[j])
                        continue;
                    corner(b, y, j, cb);
                    if (corner_close(ca, cb, tol))
                        found = used[j] = true;
                }
                if (!found) {
                    rc = vt_error_set(err, VT_ERR_BAD_INPUT,
                                      "'%s':%" PRIu64 ": corner (%g %g %g / %g %g) of '%s':%" PRIu64
                                      " is missing",
                                      b->path, y->line, ca[0], ca[1], ca[2], ca[3], ca[4], a->path,
                                      x->line);
                    goto cleanup;
                }
            }
        }
    }
    printf("vertices %" PRIu32 " -> %" PRIu32 ", faces %zu -> %zu, materials %" PRIu32
           " -> %" PRIu32 "\n",
           vt_obj_position_count(a->obj), vt_obj_position_count(b->obj), a->tri_count, b->tri_count,
           a->material_count, b->material_count);
cleanup:
    for (uint32_t i = 0; ta && i < a->material_count; i++)
        free(ta[i]);
    for (uint32_t i = 0; tb && i < b->material_count; i++)
        free(tb[i]);
    free(ta);
    free(tb);
    return rc;
}

static void usage(FILE *f)
{
    fprintf(f, "usage: vt-obj2ply IN.obj -o OUT.ply\n"
               "       vt-obj2ply --restore IN.obj MESHLAB.obj -o OUT.obj\n"
               "       vt-obj2ply --check IN.obj OUT.obj [--same-faces] [--tolerance T]\n"
               "The OBJ side of scripts/mesh-clean (MeshLab reads PLY only): converts an OBJ to a\n"
               "PLY with wedge texture coordinates, restores the original materials in the OBJ\n"
               "meshlabserver wrote, and checks the result against the input.\n"
               "  -o, --output FILE  the file to write\n"
               "  --same-faces       --check: face I must have the corners of input triangle I\n"
               "  --tolerance T      --check: largest difference (default 1e-6)\n"
               "  -q, --quiet        errors only\n"
               "  -h, --help         this help\n"
               "  --version          version\n");
}

int main(int argc, char **argv)
{
    vt_tool_init("vt-obj2ply");
    vt_atomic_file_cleanup_on_signals();
    enum { OPT_RESTORE = 256, OPT_CHECK, OPT_SAME, OPT_TOL, OPT_VERSION };
    static const struct option longopts[] = {{"output", required_argument, NULL, 'o'},
                                             {"restore", no_argument, NULL, OPT_RESTORE},
                                             {"check", no_argument, NULL, OPT_CHECK},
                                             {"same-faces", no_argument, NULL, OPT_SAME},
                                             {"tolerance", required_argument, NULL, OPT_TOL},
                                             {"quiet", no_argument, NULL, 'q'},
                                             {"help", no_argument, NULL, 'h'},
                                             {"version", no_argument, NULL, OPT_VERSION},
                                             {NULL, 0, NULL, 0}};
    const char *output = NULL;
    bool do_restore = false, do_check = false, same_faces = false;
    double tol = 1e-6;
    opterr = 0;
    int c;
    while ((c = vt_getopt_long(argc, argv, ":o:qh", longopts)) != -1) {
        switch (c) {
        case 'o':
            output = optarg;
            break;
        case OPT_RESTORE:
            do_restore = true;
            break;
        case OPT_CHECK:
            do_check = true;
            break;
        case OPT_SAME:
            same_faces = true;
            break;
        case OPT_TOL: {
            char *end;
            errno = 0;
            tol = strtod(optarg, &end);
            if (errno || end == optarg || *end || !(tol >= 0) || !isfinite(tol))
                return vt_usage_error("bad --tolerance '%s'", optarg);
            break;
        }
        case 'q':
            vt_log_set_level(VT_LOG_ERROR);
            break;
        case 'h':
            usage(stdout);
            return VT_EXIT_OK;
        case OPT_VERSION:
            vt_print_version(stdout);
            return VT_EXIT_OK;
        default:
            return vt_usage_getopt_error(c, argv);
        }
    }
    int nargs = argc - optind;
    if (do_restore && do_check)
        return vt_usage_error("--restore and --check exclude each other");
    if ((do_restore || do_check) ? nargs != 2 : nargs != 1)
        return vt_usage_error("wrong number of files");
    if (!do_check && !output)
        return vt_usage_error("no output: give -o FILE");
    if (do_check && output)
        return vt_usage_error("--check writes nothing: no -o");
    if (!do_check && same_faces)
        return vt_usage_error("--same-faces needs --check");

    struct vt_error err = {0};
    struct mesh a, b;
    memset(&b, 0, sizeof(b));
    int rc = mesh_read(&a, argv[optind], &err);
    if (!rc && do_restore)
        rc = restore(&a, argv[optind + 1], output, &err);
    else if (!rc && do_check) {
        rc = mesh_read_mtls(&a, &err);
        if (!rc)
            rc = mesh_read(&b, argv[optind + 1], &err);
        if (!rc)
            rc = mesh_read_mtls(&b, &err);
        if (!rc)
            rc = check(&a, &b, same_faces, tol, &err);
    } else if (!rc) {
        rc = write_ply(&a, output, &err);
    }
    mesh_release(&a);
    mesh_release(&b);
    if (rc) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        return VT_EXIT_BAD_INPUT;
    }
    return VT_EXIT_OK;
}
