/* vt-obj2ply IN.obj -o OUT.ply (see vt_obj2ply_convert.h). */
#include "vt_obj2ply_convert.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_error.h"
#include "vt_obj2ply_out.h"

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

int vt_obj2ply_convert_write(const struct vt_obj2ply_mesh *m, const char *out_path,
                             struct vts_error *err)
{
    uint32_t nv = vt_obj_position_count(m->obj);
    if (nv > INT32_MAX || m->tri_count > INT32_MAX)
        return vt_error_set(err, VTS_ERR_LIMIT, "'%s': too large for a PLY with int indices",
                            m->path);
    struct vt_obj2ply_out *o = malloc(sizeof(*o));
    if (!o)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    o->offset = 0;
    o->used = 0;
    int rc = vt_atomic_file_create(&o->file, out_path, "tmp", VT_ATOMIC_FILE_SEQUENTIAL, err);
    if (rc) {
        free(o);
        return rc;
    }
    char line[128];
    rc = vt_obj2ply_out_str(
        o, "ply\nformat binary_little_endian 1.0\ncomment written by vt-obj2ply\n", err);
    for (uint32_t i = 0; !rc && i < m->material_count; i++) {
        snprintf(line, sizeof(line),
                 "comment TextureFile " VT_OBJ2PLY_MESH_TOKEN_PREFIX "%" PRIu32 "\n", i);
        rc = vt_obj2ply_out_str(o, line, err);
    }
    if (!rc) {
        snprintf(line, sizeof(line), "element vertex %" PRIu32 "\n", nv);
        rc = vt_obj2ply_out_str(o, line, err);
    }
    if (!rc)
        rc = vt_obj2ply_out_str(o, "property float x\nproperty float y\nproperty float z\n", err);
    if (!rc) {
        snprintf(line, sizeof(line), "element face %zu\n", m->tri_count);
        rc = vt_obj2ply_out_str(o, line, err);
    }
    if (!rc)
        rc = vt_obj2ply_out_str(o,
                                "property list uchar int vertex_indices\n"
                                "property list uchar float texcoord\n"
                                "property int texnumber\nend_header\n",
                                err);
    const double *pos = vt_obj_positions(m->obj);
    for (uint32_t i = 0; !rc && i < nv; i++) {
        unsigned char b[12];
        for (int k = 0; k < 3; k++)
            put_f32le(b + 4 * k, pos[3 * (size_t)i + (size_t)k]);
        rc = vt_obj2ply_out_write(o, b, sizeof(b), err);
    }
    const double *tex = vt_obj_texcoords(m->obj);
    for (size_t i = 0; !rc && i < m->tri_count; i++) {
        const struct vt_obj2ply_mesh_tri *t = &m->tris[i];
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
        rc = vt_obj2ply_out_write(o, b, sizeof(b), err);
    }
    if (!rc)
        rc = vt_obj2ply_out_flush(o, err);
    if (!rc)
        rc = vt_atomic_file_commit(&o->file, err);
    else
        vt_atomic_file_abort(&o->file);
    free(o);
    return rc;
}
