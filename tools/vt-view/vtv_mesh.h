/* vt-view geometry: the 2D quad over the virtual texture, or a .vt.obj scene read with the
 * streaming OBJ reader (polygons fanned into triangles; v flipped so that v = 0 is row 0). */
#ifndef VTV_MESH_H
#define VTV_MESH_H

#include <stdint.h>

#include "vt_error.h"

struct vtv_mesh {
    float *vertices; /* x y z u v */
    uint32_t vertex_count;
    uint32_t *indices;
    uint32_t index_count;
    double lo[3], hi[3]; /* bounding box */
};

int vtv_mesh_quad(struct vtv_mesh *m, double width, double height, struct vts_error *err);
int vtv_mesh_read_obj(struct vtv_mesh *m, const char *path, struct vts_error *err);
void vtv_mesh_free(struct vtv_mesh *m);

#endif
