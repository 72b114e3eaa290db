/* vt-view geometry: the 2D quad over the virtual texture, or a .vt.obj scene read with the
 * streaming OBJ reader (polygons fanned into triangles; v flipped so that v = 0 is row 0), its
 * faces grouped by material and the materials by feature set (vtv_material.h), with the maps of
 * its .vt.mtl (STORE#LAYER) naming the store layers to stream. */
#ifndef VTV_MESH_H
#define VTV_MESH_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"
#include "vtv_material.h"
#include "vtv_tangent.h"

/* The faces of one material: vertices first .. first + count - 1 of the buffer, or, in a mesh
 * with an index buffer, indices first .. first + count - 1 of it. */
struct vtv_mesh_group {
    uint32_t first, count;
    uint64_t faces; /* OBJ faces (before fanning) */
    struct vtv_material mat;
    unsigned features; /* vtv_material_features(&mat) */
};

struct vtv_mesh {
    float *vertices; /* VTV_VERTEX_FLOATS per vertex, 3 vertices per triangle (unindexed) */
    uint32_t vertex_count;
    /* Optional (the terrain grid): 3 indices per triangle into vertices, drawn with
     * glDrawElements; NULL: the vertices are the triangles (OBJ scenes, the 2D quad). */
    uint32_t *indices;
    uint32_t index_count;
    struct vtv_mesh_group *groups; /* ordered: opaque feature sets, then blended; by features */
    uint32_t group_count;
    /* The store layer each map kind is drawn from (by name; NULL: no material maps it; "": the
     * shown layer, for a map that names the store without a layer). */
    char *layers[VTV_MAP_COUNT];
    /* The Wang packs its materials name (vt_wang), each once (a material's wang is 1 + index). */
    char **wang_paths;
    uint32_t wang_count;
    double lo[3], hi[3]; /* bounding box */
};

int vtv_mesh_quad(struct vtv_mesh *m, double width, double height, struct vts_error *err);
/* Reads a .vt.obj scene. materials: group the faces by the materials of its MTL files (else every
 * face is drawn with the plain material: the shown layer, unlit). */
int vtv_mesh_read_obj(struct vtv_mesh *m, const char *path, bool materials, struct vts_error *err);
void vtv_mesh_free(struct vtv_mesh *m);

#endif
