/* vt-obj2ply's mesh (tools/vt-obj2ply/vt-obj2ply.c): an OBJ read whole with vt_obj, its faces
 * fanned into triangles, its materials in order of first use and its MTL files. */
#ifndef VT_OBJ2PLY_MESH_H
#define VT_OBJ2PLY_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_obj.h"

/* Material N of the PLY is named by the texture file name VT_OBJ2PLY_MESH_TOKEN_PREFIX "N". */
#define VT_OBJ2PLY_MESH_TOKEN_PREFIX "vt-material-"

/* A triangle of a fanned face: corner indices into the reader's arrays and a material index. */
struct vt_obj2ply_mesh_tri {
    uint32_t v[3];
    uint32_t vt[3]; /* VT_OBJ_NONE: (0, 0) */
    uint32_t material;
    uint64_t line;
};

/* One OBJ read whole: the reader (positions, texcoords), the triangles, the materials in order of
 * first use and the MTL files named by mtllib lines (resolved). */
struct vt_obj2ply_mesh {
    const char *path;
    struct vt_obj *obj;
    struct vt_obj2ply_mesh_tri *tris;
    size_t tri_count, tri_cap;
    char **materials;
    uint32_t material_count, material_cap;
    char **mtllibs;
    size_t mtllib_count, mtllib_cap;
    struct vt_mtl *mtls; /* one per mtllib, read by vt_obj2ply_mesh_read_mtls() */
};

/* Reads the OBJ at path into m (released with vt_obj2ply_mesh_release() even on failure; path must
 * outlive m). Returns 0 or a negative status with err filled. */
int vt_obj2ply_mesh_read(struct vt_obj2ply_mesh *m, const char *path, struct vts_error *err);

/* Reads the MTL files m's mtllib lines name (m->mtls). Returns 0 or a negative status. */
int vt_obj2ply_mesh_read_mtls(struct vt_obj2ply_mesh *m, struct vts_error *err);

/* Frees everything m holds; m is zeroed (a zeroed m may be released). */
void vt_obj2ply_mesh_release(struct vt_obj2ply_mesh *m);

/* The material named name in the mesh's MTL files (the last file that defines it), or NULL. */
const struct vt_mtl_material *vt_obj2ply_mesh_find_material(const struct vt_obj2ply_mesh *m,
                                                            const char *name);

#endif
