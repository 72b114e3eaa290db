/* Cutting faces along the integer UV lines (libc only, pure computation): for vt-offset on the
 * materials whose atlas entry wraps (lib/layout/vt_layout.h "wrap"). See docs/real-scenes.md.
 *
 * Input: a mesh (vt_chart.h), a flag per face ("wrap": cut it) and a move per face (du, dv:
 * integers, the chart's move). A wrap face is one with the flag, a group and a texcoord at every
 * corner. For a wrap face, with its texcoords moved, every integer line u = k or v = k that passes
 * strictly between two of its corners' values cuts it: the face is clipped to each unit cell
 * [a, a+1] x [b, b+1] it covers, and each non-degenerate piece is moved by (-a, -b) so that it
 * lies in [0,1] x [0,1]. A wrap face that no line cuts lies in one cell [a, a+1] x [b, b+1]
 * (a = floor(umin), b = floor(vmin)) and is moved by (-a, -b) as a whole. The points where an
 * edge crosses its face's lines are at t from the edge's lower position index (the same bits for
 * every face with the same moved texcoords on the edge), with the crossing coordinate exactly k.
 *
 * No cracks: a point where a line cuts a mesh edge (two position indices) is a new position
 * shared by every face on that edge, so a face next to a cut face (any material, with or without
 * texcoords) gets the points of that edge as extra corners (it is "split", its shape unchanged).
 * Points inside a face (where two lines cross) are shared by the pieces of that face. Every edge
 * of the output is then shared by exactly the faces that shared the input edge it lies on: no
 * T-junction, no new boundary; an edge inside a face is shared by exactly two of its pieces. (For
 * faces with two corners at one position and for concave n-gons, the edges of zero-area slivers
 * or degenerate bridges can count more: still no T-junction.)
 *
 * Polygons with more than three corners are clipped as they are (convex ones exactly; a concave
 * n-gon gives pieces covering it, possibly with overlapping degenerate edges). A piece that lies
 * on one side line of its cell (the face only touches the cell along that line, or one of its
 * edges lies on it) is dropped, unless that line is the outer line of the face's cells (no cell
 * beyond holds that part: a face folded over itself in UV can have an area in 3D there): for a
 * convex face, exactly its pieces of zero area in UV. A face of zero area in UV (its signed area
 * exactly 0: collinear, or folded so that it encloses nothing) keeps its pieces that are more than
 * one point (it may have an area in 3D), and so may lose all only when it is degenerate in 3D
 * too. docs/real-scenes.md states the rules in full. */
#ifndef VT_CUT_H
#define VT_CUT_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_chart.h"
#include "vt_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One corner of an output polygon. */
struct vt_cut_corner {
    uint32_t pos;    /* position index: < position_count an input one, else the new position
                        vertices[pos - position_count] */
    bool has_uv;     /* the face has texcoords at every corner (else u = v = 0) */
    double u, v;     /* texcoord: for a wrap face, moved into [0,1] (its cell's move; a value
                        that rounding puts a hair outside is clamped); for a split face that
                        does not wrap, moved by the face's (du, dv) only. An input corner gets
                        texcoord + (move - cell), rounded once, as a kept face's corner */
    uint32_t src[3]; /* input face corners (0-based within the face) whose attributes (normals)
                        this corner interpolates; unused ones are VT_CHART_NONE */
    double w[3];     /* their weights (sum 1): an input corner is {i}, {1}; an edge point two
                        corners; a point inside the face three (barycentric in UV) */
};

/* A new position: sum of w[i] * position[pos[i]] over the used entries (unused ones are
 * VT_CHART_NONE with weight 0): an edge point {lo, hi, NONE} {1 - t, t, 0}; a point inside a face
 * three corners of one of its fan triangles, barycentric in UV. */
struct vt_cut_vertex {
    uint32_t pos[3];
    double w[3];
};

struct vt_cut_result {
    uint8_t *changed;     /* per input face: 0 kept (write it as it is, moved by face_shift),
                             1 replaced by its polygons below */
    double *face_shift;   /* per input face, 2: the move of a kept face (du, dv: the chart's,
                             plus the cell's for a wrap face that no line cuts; 0 for a face
                             without any texcoord), also set for changed faces */
    uint64_t *face_poly;  /* face_count + 1 offsets into the polygons (kept faces have none) */
    uint64_t *poly_start; /* poly_count + 1 offsets into corners */
    struct vt_cut_corner *corners;
    uint64_t poly_count, corner_count;
    struct vt_cut_vertex *vertices; /* new positions, in order of creation */
    uint32_t vertex_count;
    uint64_t faces_cut;   /* wrap faces that lines cut */
    uint64_t faces_split; /* other faces that got extra corners (neighbours of cuts) */
    uint64_t pieces;      /* polygons of the cut faces */
};

/* Computes the cut of m. wrap: per face, non-zero to cut it (faces in no chart are never cut);
 * shift: 2 per face (du, dv), ignored for faces without texcoords. *r is overwritten; release it
 * after success or failure (on failure it is already released: zeroed). Returns 0, VTS_ERR_NOMEM
 * or VTS_ERR_LIMIT (more than 2^32 - 1 - position_count new positions, a wrap face spanning more
 * than 2^20 cells, or a wrap face's moved texcoord that is not finite or beyond 2^52 in
 * magnitude), with err filled. Deterministic; thread-safe (no shared state). Time about
 * O(corners + new corners x log(cells per face)). Memory: the result (64 bytes per output corner,
 * 48 per new position) and, while it runs, 16 bytes per edge crossing and hash tables of the cut
 * edges and grid points. */
int vt_cut(const struct vt_chart_mesh *m, const uint8_t *wrap, const double *shift,
           struct vt_cut_result *r, struct vts_error *err);

/* Frees everything *r holds and zeroes it. Accepts NULL. */
void vt_cut_release(struct vt_cut_result *r);

#ifdef __cplusplus
}
#endif
#endif
