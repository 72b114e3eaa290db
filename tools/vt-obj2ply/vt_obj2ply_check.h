/* vt-obj2ply --check IN.obj OUT.obj (tools/vt-obj2ply/vt-obj2ply.c): compares the materials,
 * textures and (with --same-faces) the triangles of two meshes. */
#ifndef VT_OBJ2PLY_CHECK_H
#define VT_OBJ2PLY_CHECK_H

#include <stdbool.h>

#include "vt_error.h"
#include "vt_obj2ply_mesh.h"

/* Checks b (with its MTL files read) against a; on success prints "vertices A -> B, faces C -> D,
 * materials E -> F" to stdout. Returns 0, or VTS_ERR_BAD_INPUT / VTS_ERR_NOMEM with err filled. */
int vt_obj2ply_check_compare(const struct vt_obj2ply_mesh *a, const struct vt_obj2ply_mesh *b,
                             bool same_faces, double tol, struct vts_error *err);

#endif
