/* vt-obj2ply --check (see vt_obj2ply_check.h). */
#define _XOPEN_SOURCE 700 /* realpath */
#include "vt_obj2ply_check.h"

#include <inttypes.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_error.h"
#include "vt_obj2ply_path.h"

/* The resolved map_Kd path of material index i of m ("" when it has none), made absolute. */
static char *material_texture(const struct vt_obj2ply_mesh *m, uint32_t i)
{
    const struct vt_mtl_material *mat = vt_obj2ply_mesh_find_material(m, m->materials[i]);
    const char *path = mat ? mat->maps[VT_MTL_MAP_KD].path : NULL;
    if (!path)
        return strdup("");
    char *r = realpath(path, NULL);
    return r ? r : vt_obj2ply_path_absolute(path);
}

static void corner(const struct vt_obj2ply_mesh *m, const struct vt_obj2ply_mesh_tri *t, int k,
                   double out[5])
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

int vt_obj2ply_check_compare(const struct vt_obj2ply_mesh *a, const struct vt_obj2ply_mesh *b,
                             bool same_faces, double tol, struct vts_error *err)
{
    int rc = 0;
    char **ta = calloc(a->material_count + 1u, sizeof(char *));
    char **tb = calloc(b->material_count + 1u, sizeof(char *));
    if (!ta || !tb) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        goto cleanup;
    }
    for (uint32_t i = 0; i < a->material_count; i++)
        if (!(ta[i] = material_texture(a, i))) {
            rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
            goto cleanup;
        }
    for (uint32_t i = 0; i < b->material_count; i++) {
        if (!(tb[i] = material_texture(b, i))) {
            rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
            goto cleanup;
        }
        bool known = false;
        for (uint32_t j = 0; j < a->material_count && !known; j++)
            known = !strcmp(a->materials[j], b->materials[i]) && !strcmp(ta[j], tb[i]);
        if (!known) {
            rc = vt_error_set(
                err, VTS_ERR_BAD_INPUT,
                "'%s': material '%s' (texture '%s') is not a material of '%s' with that texture",
                b->path, b->materials[i], tb[i], a->path);
            goto cleanup;
        }
    }
    for (size_t i = 0; i < b->tri_count; i++) {
        const struct vt_obj2ply_mesh_tri *t = &b->tris[i];
        for (int k = 0; k < 3; k++)
            if (t->vt[k] == VT_OBJ_NONE) {
                rc = vt_error_set(err, VTS_ERR_BAD_INPUT,
                                  "'%s':%" PRIu64 ": a corner has no texture coordinate", b->path,
                                  t->line);
                goto cleanup;
            }
    }
    if (same_faces) {
        if (a->tri_count != b->tri_count) {
            rc = vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': %zu triangles, '%s' has %zu", b->path,
                              b->tri_count, a->path, a->tri_count);
            goto cleanup;
        }
        for (size_t i = 0; i < a->tri_count; i++) {
            const struct vt_obj2ply_mesh_tri *x = &a->tris[i], *y = &b->tris[i];
            if (strcmp(a->materials[x->material], b->materials[y->material])) {
                rc = vt_error_set(err, VTS_ERR_BAD_INPUT,
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
                    rc = vt_error_set(err, VTS_ERR_BAD_INPUT,
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
