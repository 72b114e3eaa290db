/* libFuzzer target for the cut along the UV grid (lib/chart/vt_cut*.c) and the chart labels it is
 * given moves from (vt_chart.c): the input bytes describe a small mesh (decoded below), which is
 * labelled and cut; the result must pass the checkers of tests/unit/chart/cut_fixture.c: texcoords
 * of wrap faces in [0, 1]^2, each the input's plus an integer vector per polygon; areas kept; 3D
 * positions at random points of triangles; and, when every cut face is a triangle or convex in UV
 * and has distinct positions, watertightness by edge counts. A violation aborts.
 *
 * Bytes: [flags][positions][faces], then 3 per position (x, y, z: int8), 2 per position (u, v:
 * int8 / 4, plus a fraction byte / 1024 each unless flag 2), then per face a header byte (corners
 * 3 + (h & 3), or 3 with flag 1; group (h >> 2) & 3, 3: none; wrap h & 16 or flag 8; texcoords
 * (h >> 5): 0 the position's shared one, 1 none, 2 a copy per corner, 3 a copy moved by a byte
 * each) and its corners' position bytes. Flag 4 moves every texcoord by 2600.5 repeats. Missing
 * bytes read as 0; a face whose bytes run out is not made. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "unit/chart/cut_fixture.h"

int fuzz_cut_one(const uint8_t *data, size_t size);
/* The mesh of the bytes (t initialised here), with its charts' moves. */
void fuzz_cut_mesh(const uint8_t *data, size_t size, struct tmesh *t);
#ifndef VT_FUZZ_NO_ENTRY
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
#endif

struct reader {
    const uint8_t *p;
    size_t n, at;
};

static unsigned next_byte(struct reader *r)
{
    return r->at < r->n ? r->p[r->at++] : (r->at++, 0u);
}

/* Strictly convex and winding once in UV: the cut's exact case for n-gons. */
static bool convex_in_uv(const struct tmesh *t, uint32_t f)
{
    uint64_t c0 = t->face_start[f], n = t->face_start[f + 1] - c0;
    double turn = 0;
    int sign = 0;
    for (uint64_t i = 0; i < n; i++) {
        const double *a = t->uv + 2 * (size_t)t->tex[c0 + i];
        const double *b = t->uv + 2 * (size_t)t->tex[c0 + (i + 1) % n];
        const double *c = t->uv + 2 * (size_t)t->tex[c0 + (i + 2) % n];
        double x1 = b[0] - a[0], y1 = b[1] - a[1], x2 = c[0] - b[0], y2 = c[1] - b[1];
        double cross = x1 * y2 - y1 * x2;
        int s = cross > 0 ? 1 : cross < 0 ? -1 : 0;
        if (!s || (sign && s != sign))
            return false;
        sign = s;
        turn += atan2(cross, x1 * x2 + y1 * y2);
    }
    return fabs(fabs(turn) - 2 * 3.14159265358979323846) < 1e-6;
}

/* No two corners of the face at one position. A cut face with a repeated position (an edge of
 * zero length in 3D, its texcoords folded over it) gives pieces of zero area in 3D whose edges
 * count twice: no crack, but not the edge counts the watertightness check asks for. */
static bool distinct_positions(const struct tmesh *t, uint32_t f)
{
    for (uint64_t a = t->face_start[f]; a < t->face_start[f + 1]; a++)
        for (uint64_t b = a + 1; b < t->face_start[f + 1]; b++)
            if (t->pos[a] == t->pos[b])
                return false;
    return true;
}

/* The result's arrays are consistent: offsets in order and ending at the counts, kept faces
 * without polygons, polygons of 3 corners at least, positions that exist. */
static void check_structure(const struct tmesh *t, const struct vt_cut_result *r)
{
    if (r->face_poly[0] != 0 || r->face_poly[t->face_count] != r->poly_count ||
        r->poly_start[0] != 0 || r->poly_start[r->poly_count] != r->corner_count)
        abort();
    for (uint32_t f = 0; f < t->face_count; f++)
        if (r->face_poly[f] > r->face_poly[f + 1] ||
            (!r->changed[f] && r->face_poly[f] != r->face_poly[f + 1]))
            abort();
    for (uint64_t q = 0; q < r->poly_count; q++)
        if (r->poly_start[q + 1] < r->poly_start[q] + 3)
            abort();
    for (uint64_t c = 0; c < r->corner_count; c++)
        if (r->corners[c].pos >= t->position_count + r->vertex_count)
            abort();
    for (uint32_t v = 0; v < r->vertex_count; v++)
        if (r->vertices[v].pos[0] >= t->position_count)
            abort();
}

static void read_mesh(struct reader *in, struct tmesh *t, unsigned flags)
{
    unsigned positions = 3 + next_byte(in) % 14, faces = 1 + next_byte(in) % 24;
    double offset = flags & 4 ? 2600.5 : 0;
    for (unsigned i = 0; i < positions; i++) {
        double x = (int8_t)next_byte(in), y = (int8_t)next_byte(in), z = (int8_t)next_byte(in);
        tmesh_pos(t, x, y, z);
    }
    for (unsigned i = 0; i < positions; i++) {
        double uv[2];
        for (int a = 0; a < 2; a++) {
            uv[a] = (int8_t)next_byte(in) / 4.0 + offset;
            if (!(flags & 2))
                uv[a] += next_byte(in) / 1024.0;
        }
        tmesh_tex(t, uv[0], uv[1]); /* texcoord i: position i's */
    }
    for (unsigned f = 0; f < faces && in->at < in->n; f++) {
        unsigned h = next_byte(in), n = flags & 1 ? 3 : 3 + (h & 3), mode = h >> 5;
        uint32_t group = (h >> 2 & 3) == 3 ? VT_CHART_NONE : h >> 2 & 3, pos[6], tex[6];
        for (unsigned i = 0; i < n; i++) {
            pos[i] = next_byte(in) % positions;
            tex[i] = pos[i];
            if (mode >= 2) {
                double du = mode == 3 ? (int8_t)next_byte(in) / 8.0 : 0;
                tex[i] = tmesh_tex(t, t->uv[2 * pos[i]] + du, t->uv[2 * pos[i] + 1]);
            }
        }
        if (in->at <= in->n)
            tmesh_face(t, group, n, pos, mode == 1 ? NULL : tex, (h & 16) || (flags & 8));
    }
}

void fuzz_cut_mesh(const uint8_t *data, size_t size, struct tmesh *t)
{
    struct reader in = {data, size, 0};
    unsigned flags = next_byte(&in);
    tmesh_init(t);
    read_mesh(&in, t, flags);
    tmesh_shift_charts(t);
}

int fuzz_cut_one(const uint8_t *data, size_t size)
{
    struct tmesh t;
    fuzz_cut_mesh(data, size, &t);
    struct vt_chart_mesh m = tmesh_view(&t);
    struct vt_cut_result r;
    struct vts_error err = {0};
    if (vt_cut(&m, t.wrap, t.shift, &r, &err) != 0)
        abort(); /* the texcoords stay far below the limits */
    check_structure(&t, &r);
    if (cut_fixture_check_pieces(&t, &r, 1e-9, true))
        abort();
    bool exact = true;
    for (uint32_t f = 0; f < t.face_count && exact; f++)
        if (r.changed[f] && t.wrap[f] && t.group[f] != VT_CHART_NONE &&
            t.tex[t.face_start[f]] != VT_CHART_NONE)
            exact = distinct_positions(&t, f) &&
                    (t.face_start[f + 1] - t.face_start[f] == 3 || convex_in_uv(&t, f));
    if (exact && cut_fixture_check_watertight(&t, &r, false, true))
        abort();
    if (cut_fixture_check_points(&t, &r, size, 4, 1e-9, true))
        abort();
    vt_cut_release(&r);
    tmesh_release(&t);
    return 0;
}

#ifndef VT_FUZZ_NO_ENTRY
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz_cut_one(data, size);
}
#endif
