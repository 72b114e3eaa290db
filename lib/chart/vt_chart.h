/* UV charts of a polygon mesh (libc only, pure computation): the connected groups of faces of one
 * material that share texture coordinates, and the whole-repeat move of each chart. Used by
 * vt-atlas (lib/atlas: which texels each material's charts use) and by vt-offset (lib/offset: the
 * move it applies, the same by construction). See docs/real-scenes.md.
 *
 * Connectivity. Two faces of the same group (material) are in one chart when they share a
 * texcoord index, or when they share an undirected edge (the same two position indices) whose two
 * ends carry bitwise-equal texcoord values on both faces (exporters that write one vt per face
 * corner). Faces of different groups never share a chart. A corner without texcoord
 * (VT_CHART_NONE) joins nothing; a face without any texcoord is in no chart.
 *
 * The move of a chart is the integer (du, dv) = (-floor(umin), -floor(vmin)) of its texcoord box
 * (+0.0, never -0.0): after it the box starts in [0,1). An axis whose range already lies in
 * [0,1], bounds included, is not moved (du = 0 for u 1..1: the right edge of one copy stays
 * there, which matters to a texture that clamps). u + du is rounded once in double
 * precision, and is exact whenever the result is not larger in magnitude than u (a chart in u >= 0
 * moved down: the far repeats of game scenes, u = 2600.3 -> 0.3 exactly), so such a move changes
 * no texel. A chart that straddles 0 and is moved up by a large du rounds its small values to the
 * precision of u + du (u = -0.3, du = 700: 699.7 to 2^-43), and a tiny negative umin can round to
 * a box starting at 1 (-1e-20 + 1 == 1). Non-finite texcoords give non-finite boxes and moves. */
#ifndef VT_CHART_H
#define VT_CHART_H

#include <stdint.h>

#include "vt_error.h"

#ifdef __cplusplus
extern "C" {
#endif

#define VT_CHART_NONE UINT32_MAX

/* A mesh as the OBJ reader gives it: faces as runs of corners. Every index is checked by the
 * caller (pos < position_count, tex < texcoord_count or VT_CHART_NONE). */
struct vt_chart_mesh {
    uint32_t face_count;
    const uint64_t *face_start; /* face_count + 1 offsets into the corner arrays; >= 3 corners */
    const uint32_t *pos;        /* per corner: position index */
    const uint32_t *tex;        /* per corner: texcoord index or VT_CHART_NONE */
    const uint32_t *nrm;        /* per corner: normal index or VT_CHART_NONE (may be NULL: none) */
    const uint32_t *group;      /* per face: material id; VT_CHART_NONE: the face is in no chart */
    const double *uv;           /* 2 per texcoord index: u, v */
    uint32_t position_count, texcoord_count;
};

/* Labels every face with its chart (chart[f], numbered 0.. in order of each chart's first face;
 * VT_CHART_NONE for faces in no chart) and sets *chart_count (0 on failure). Returns 0,
 * VTS_ERR_NOMEM or VTS_ERR_LIMIT (more than 2^32 - 2 charts), with err filled. Deterministic.
 * Memory (released before it returns): 4 bytes per face, and hash tables, 3/8 to 3/4 full, of
 * 16-byte slots for the distinct (texcoord, group) pairs and 56-byte slots for the distinct edges
 * with texcoords at both ends. Thread-safe (no shared state). */
int vt_chart_label(const struct vt_chart_mesh *m, uint32_t *chart, uint32_t *chart_count,
                   struct vts_error *err);

/* The texcoord box of a chart and its move. */
struct vt_chart_box {
    uint32_t group;                /* the material of its faces */
    uint32_t faces;                /* faces in the chart */
    double umin, umax, vmin, vmax; /* over its corners with texcoords, before the move */
    double du, dv;                 /* the move: integers, -floor(umin), -floor(vmin) (0 for an
                                      axis already inside [0,1]) */
};

/* Fills boxes[0 .. chart_count) from the labels of vt_chart_label() (boxes over the corners
 * that have texcoords). */
void vt_chart_boxes(const struct vt_chart_mesh *m, const uint32_t *chart, uint32_t chart_count,
                    struct vt_chart_box *boxes);

#ifdef __cplusplus
}
#endif
#endif
