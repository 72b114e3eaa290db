/* vt-obj2ply's mesh (see vt_obj2ply_mesh.h). */
#include "vt_obj2ply_mesh.h"

#include <stdlib.h>
#include <string.h>

#include "vt_checked.h"
#include "vt_error.h"

static int push(void **arr, size_t *count, size_t *cap, size_t elem, struct vts_error *err)
{
    if (*count == *cap) {
        size_t ncap = *cap ? *cap * 2 : 64;
        size_t bytes;
        if (ncap < *cap || !vt_size_mul(ncap, elem, &bytes))
            return vt_error_set(err, VTS_ERR_LIMIT, "too many elements");
        void *n = realloc(*arr, bytes);
        if (!n)
            return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        *arr = n;
        *cap = ncap;
    }
    (*count)++;
    return 0;
}

static int mesh_mtllib(void *user, const struct vt_obj *obj, const char *mtl_path, uint64_t line,
                       struct vts_error *err)
{
    (void)obj;
    (void)line;
    struct vt_obj2ply_mesh *m = user;
    for (size_t i = 0; i < m->mtllib_count; i++)
        if (!strcmp(m->mtllibs[i], mtl_path))
            return 0;
    char *copy = strdup(mtl_path);
    if (!copy)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    int rc = push((void **)&m->mtllibs, &m->mtllib_count, &m->mtllib_cap, sizeof(char *), err);
    if (rc) {
        free(copy);
        return rc;
    }
    m->mtllibs[m->mtllib_count - 1] = copy;
    return 0;
}

static int mesh_material_index(struct vt_obj2ply_mesh *m, const char *name, uint32_t *out,
                               struct vts_error *err)
{
    for (uint32_t i = m->material_count; i-- > 0;)
        if (!strcmp(m->materials[i], name)) {
            *out = i;
            return 0;
        }
    char *copy = strdup(name);
    if (!copy)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    size_t count = m->material_count, cap = m->material_cap;
    int rc = push((void **)&m->materials, &count, &cap, sizeof(char *), err);
    if (rc || count > INT32_MAX) {
        free(copy);
        return rc ? rc : vt_error_set(err, VTS_ERR_LIMIT, "'%s': too many materials", m->path);
    }
    m->material_count = (uint32_t)count;
    m->material_cap = (uint32_t)cap;
    m->materials[count - 1] = copy;
    *out = (uint32_t)(count - 1);
    return 0;
}

static int mesh_face(void *user, const struct vt_obj *obj, const struct vt_obj_face *face,
                     struct vts_error *err)
{
    (void)obj;
    struct vt_obj2ply_mesh *m = user;
    uint32_t material = 0;
    int rc = mesh_material_index(m, face->material, &material, err);
    if (rc)
        return rc;
    for (uint32_t i = 1; i + 1 < face->corner_count; i++) {
        rc = push((void **)&m->tris, &m->tri_count, &m->tri_cap, sizeof(struct vt_obj2ply_mesh_tri),
                  err);
        if (rc)
            return rc;
        struct vt_obj2ply_mesh_tri *t = &m->tris[m->tri_count - 1];
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

void vt_obj2ply_mesh_release(struct vt_obj2ply_mesh *m)
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

int vt_obj2ply_mesh_read(struct vt_obj2ply_mesh *m, const char *path, struct vts_error *err)
{
    memset(m, 0, sizeof(*m));
    m->path = path;
    m->obj = vt_obj_create(NULL, err);
    if (!m->obj)
        return err->status;
    struct vt_obj_callbacks cb = {.mtllib = mesh_mtllib, .face = mesh_face, .user = m};
    return vt_obj_read(m->obj, path, &cb, err);
}

int vt_obj2ply_mesh_read_mtls(struct vt_obj2ply_mesh *m, struct vts_error *err)
{
    m->mtls = calloc(m->mtllib_count ? m->mtllib_count : 1, sizeof(*m->mtls));
    if (!m->mtls)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < m->mtllib_count; i++) {
        int rc = vt_mtl_read(m->mtllibs[i], NULL, &m->mtls[i], err);
        if (rc)
            return rc;
    }
    return 0;
}

/* The material named name in the mesh's MTL files (the last file that defines it), or NULL. */
const struct vt_mtl_material *vt_obj2ply_mesh_find_material(const struct vt_obj2ply_mesh *m,
                                                            const char *name)
{
    const struct vt_mtl_material *found = NULL;
    for (size_t i = 0; i < m->mtllib_count; i++) {
        const struct vt_mtl_material *mat = vt_mtl_find(&m->mtls[i], name);
        if (mat)
            found = mat;
    }
    return found;
}
