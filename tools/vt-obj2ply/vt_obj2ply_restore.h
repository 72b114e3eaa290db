/* vt-obj2ply --restore IN.obj MESHLAB.obj -o OUT.obj (tools/vt-obj2ply/vt-obj2ply.c): gives the OBJ
 * meshlabserver wrote the original material names and MTL files back. */
#ifndef VT_OBJ2PLY_RESTORE_H
#define VT_OBJ2PLY_RESTORE_H

#include "vt_error.h"
#include "vt_obj2ply_mesh.h"

/* Rewrites meshlab_path (written from orig's PLY) into out_path (atomically) with orig's materials
 * and mtllib. Returns 0 or a negative status with err filled. */
int vt_obj2ply_restore_write(const struct vt_obj2ply_mesh *orig, const char *meshlab_path,
                             const char *out_path, struct vts_error *err);

#endif
