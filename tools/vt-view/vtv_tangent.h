/* vt-view tangent frames for normal mapping, computed from the texture coordinates with
 * MikkTSpace-like rules (docs/viewer.md, "Tangents"): per triangle the tangent T and bitangent B
 * from the UV derivatives (T along +u, B along +v, v up as in the OBJ), normalised; summed over the
 * triangles that share a corner (the same OBJ v, vt and vn indices); at each vertex T made
 * orthogonal to the vertex normal (Gram-Schmidt) and normalised, and the handedness sign w = +1
 * when cross(N, T) points along B, else -1 (the shader's bitangent is w cross(N, T)). Both the
 * virtual-texture scene and the reference scene use it, so both shade with the same frames. */
#ifndef VTV_TANGENT_H
#define VTV_TANGENT_H

#include <stddef.h>
#include <stdint.h>

/* Floats per vertex of the scene buffers: x y z, u v (drawn: v = 0 is the first texel row),
 * nx ny nz (the OBJ's vn, or 0 0 0: the face normal is filled in), tx ty tz tw. */
#define VTV_VERTEX_FLOATS 12

/* Fills the normals that are 0 0 0 (with the triangle's normal) and the tangents of n vertices (3
 * per triangle, in order). keys: 3 uint32 per vertex, the OBJ v, vt and vn indices of its corner.
 * Returns 0 or VTS_ERR_NOMEM. */
int vtv_tangents(float *vertices, const uint32_t *keys, size_t n);

#endif
