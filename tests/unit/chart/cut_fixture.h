/* Shared helpers of the lib/chart tests (test_vt_chart.c, test_vt_cut.c, test_vt_cut_alloc.c) and
 * of tests/fuzz/fuzz_cut.c: meshes built in memory, and checkers of a vt_cut() result that are
 * independent of the cut's own code (they recompute everything from the input mesh). The
 * checkers return their count of violations (0: the result is right) and print the first few
 * when verbose, so a test can also show that a corrupted result fails them. */
#ifndef CUT_FIXTURE_H
#define CUT_FIXTURE_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_chart.h"
#include "vt_cut.h"

/* A growing mesh: positions (x, y, z), texcoords, faces with a group and a wrap flag. */
struct tmesh {
    uint32_t face_count, position_count, texcoord_count;
    uint64_t corner_count;
    uint64_t *face_start;
    uint32_t *pos, *tex, *group;
    double *xyz, *uv;
    uint8_t *wrap;
    double *shift;   /* 2 per face; tmesh_shift_charts() fills it */
    uint64_t cap[8]; /* capacities of the arrays above */
};

void tmesh_init(struct tmesh *t);
void tmesh_release(struct tmesh *t);
uint32_t tmesh_pos(struct tmesh *t, double x, double y, double z);
uint32_t tmesh_tex(struct tmesh *t, double u, double v);
/* A face of n corners; tex NULL: no texcoords. Returns its index. Aborts when out of memory. */
uint32_t tmesh_face(struct tmesh *t, uint32_t group, uint32_t n, const uint32_t *pos,
                    const uint32_t *tex, bool wrap);
/* The vt_chart_mesh view of t (valid until t changes). */
struct vt_chart_mesh tmesh_view(const struct tmesh *t);
/* Labels the charts and sets every face's shift to its chart's move (0 for faces in none);
 * returns the chart count. */
uint32_t tmesh_shift_charts(struct tmesh *t);

/* The 3D position of output position index p (input or new). */
void cut_fixture_position(const struct tmesh *t, const struct vt_cut_result *r, uint32_t p,
                          double out[3]);

/* Watertightness by edge counts. Every output edge (two position indices, undirected, over kept
 * faces and output polygons) that lies on an input edge of its own face (both its ends on it: an
 * input position is on its edges, a new edge point on its edge) is used by exactly as many output
 * faces as input faces use that edge; any other edge of a face's polygons lies inside the face
 * and is used exactly twice by that face's polygons. closed: also no output edge used once. A
 * changed face without output polygons (it had no area: cut_fixture_check_pieces()) counts for
 * no input edge. */
int cut_fixture_check_watertight(const struct tmesh *t, const struct vt_cut_result *r, bool closed,
                                 bool verbose);

/* For every changed face: its output polygons' total signed area in UV equals the face's
 * (relative tolerance tol, of its UV box) and, for triangles, so do their total unsigned area and
 * their vector area in 3D, and every polygon of a wrap face has its texcoords in
 * [0, 1]^2, each the input's value at that point plus one integer vector per polygon. Kept wrap
 * faces: moved by face_shift into [0, 1]^2 (within tol). A face may lose all its polygons only if
 * it has zero area in UV and in 3D. */
int cut_fixture_check_pieces(const struct tmesh *t, const struct vt_cut_result *r, double tol,
                             bool verbose);

/* For changed triangles with texcoords: at random points of every output polygon, the 3D position
 * interpolated from its corners equals the input triangle's position at the input (unmoved)
 * texcoord there (relative tolerance tol, plus what rounding the texcoords at their magnitude
 * can cause through the triangle's conditioning). seed: the random points. */
int cut_fixture_check_points(const struct tmesh *t, const struct vt_cut_result *r, uint64_t seed,
                             int points_per_polygon, double tol, bool verbose);

/* A deep copy of a result of t (for corrupting it), with room for extra more corners and new
 * positions; release it with vt_cut_release(). Aborts when out of memory. */
void cut_fixture_copy(const struct tmesh *t, const struct vt_cut_result *r, uint64_t extra,
                      struct vt_cut_result *copy);

#endif
