/* vt-obj2ply IN.obj -o OUT.ply (tools/vt-obj2ply/vt-obj2ply.c): the binary PLY that meshlabserver
 * reads, with wedge texture coordinates and one "comment TextureFile" per material. */
#ifndef VT_OBJ2PLY_CONVERT_H
#define VT_OBJ2PLY_CONVERT_H

#include "vt_error.h"
#include "vt_obj2ply_mesh.h"

/* Writes m as a PLY to out_path (atomically). Returns 0 or a negative status with err filled. */
int vt_obj2ply_convert_write(const struct vt_obj2ply_mesh *m, const char *out_path,
                             struct vts_error *err);

#endif
