/* vt-synth-scene: writes a seeded test scene with the hard properties of real scenes (test utility
 * for tests/e2e/real_scenes, not installed; the kinds are described in
 * tests/e2e/real_scenes/README.md).
 *
 *   vt-synth-scene KIND OUTDIR [--seed N]
 *
 * KIND is strip, offset, roof, torus or mix; OUTDIR gets KIND.obj, its MTL and the textures (PNG).
 * On stdout one line of facts about the scene (faces, materials, what crosses integer UV lines).
 * Every face's texture coordinates are an affine function of its position (triangles, or planar
 * parallelograms with parallelogram UVs), so that any triangulation of any piece of it maps the
 * same point to the same UV: the checkers rely on it. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_synth_scene.h"

/* Writes an RGB noise texture at OUTDIR/rel. */
static void noise_png(struct vt_synth_scene *s, const char *rel, uint32_t w, uint32_t h)
{
    uint8_t *p = vt_synth_scene_noise8(s, w, h, 3);
    struct vt_synth_scene_png png = {w, h, 3, 8, p, NULL, NULL, 0};
    vt_synth_scene_write_png(s, rel, &png);
    free(p);
}

/* True when an integer line passes strictly between lo and hi. */
static bool crosses(double lo, double hi)
{
    return floor(lo) + 1 < hi;
}

/* A planar grid patch: corner o, edge vectors a (u direction) and b (v direction), nu x nv cells,
 * UV (u0..u1) x (v0..v1); quads, or two triangles per cell when tris. Positions and texcoords are
 * shared inside the patch. Returns the number of faces. */
struct patch {
    double o[3], a[3], b[3];
    uint32_t nu, nv;
    double u0, u1, v0, v1;
    bool tris;
};

static uint32_t write_patch(struct vt_synth_scene *s, const struct patch *p)
{
    uint32_t v0 = s->v_count + 1, t0 = s->vt_count + 1, faces = 0;
    for (uint32_t j = 0; j <= p->nv; j++)
        for (uint32_t i = 0; i <= p->nu; i++) {
            double fu = (double)i / p->nu, fv = (double)j / p->nv;
            vt_synth_scene_v(s, p->o[0] + fu * p->a[0] + fv * p->b[0],
                             p->o[1] + fu * p->a[1] + fv * p->b[1],
                             p->o[2] + fu * p->a[2] + fv * p->b[2]);
            vt_synth_scene_vt(s, p->u0 + fu * (p->u1 - p->u0), p->v0 + fv * (p->v1 - p->v0));
        }
    for (uint32_t j = 0; j < p->nv; j++)
        for (uint32_t i = 0; i < p->nu; i++) {
            uint32_t k = j * (p->nu + 1) + i, c[4] = {k, k + 1, k + p->nu + 2, k + p->nu + 1};
            uint32_t v[4], t[4];
            for (int q = 0; q < 4; q++)
                v[q] = v0 + c[q], t[q] = t0 + c[q];
            if (!p->tris) {
                vt_synth_scene_face(s, 4, v, t, NULL);
                faces++;
                continue;
            }
            uint32_t va[3] = {v[0], v[1], v[2]}, ta[3] = {t[0], t[1], t[2]};
            uint32_t vb[3] = {v[0], v[2], v[3]}, tb[3] = {t[0], t[2], t[3]};
            vt_synth_scene_face(s, 3, va, ta, NULL);
            vt_synth_scene_face(s, 3, vb, tb, NULL);
            faces += 2;
        }
    return faces;
}

/* ---- strip: a race track ---- */

#define STRIP_SECTIONS 10
#define STRIP_CELLS    60 /* per section; the first half straight, the second half a curve */

struct station {
    uint32_t lo, l, r, ro; /* position indices: outer left kerb edge, road edges, outer right */
};

/* Road faces of one cell between stations a and b; counts those crossing an integer u line. */
static void strip_road_cell(struct vt_synth_scene *s, const struct station *a,
                            const struct station *b, const uint32_t ta[2], const uint32_t tb[2],
                            bool curve, bool flip)
{
    /* ta/tb: vt of v = 0 (right edge) and v = 1 (left edge) at each station */
    if (!curve) {
        uint32_t v[4] = {a->r, b->r, b->l, a->l}, t[4] = {ta[0], tb[0], tb[1], ta[1]};
        vt_synth_scene_face(s, 4, v, t, NULL);
        return;
    }
    if (!flip) {
        uint32_t v1[3] = {a->r, b->r, b->l}, t1[3] = {ta[0], tb[0], tb[1]};
        uint32_t v2[3] = {a->r, b->l, a->l}, t2[3] = {ta[0], tb[1], ta[1]};
        vt_synth_scene_face(s, 3, v1, t1, NULL);
        vt_synth_scene_face(s, 3, v2, t2, NULL);
    } else {
        uint32_t v1[3] = {a->r, b->r, a->l}, t1[3] = {ta[0], tb[0], ta[1]};
        uint32_t v2[3] = {b->r, b->l, a->l}, t2[3] = {tb[0], tb[1], ta[1]};
        vt_synth_scene_face(s, 3, v1, t1, NULL);
        vt_synth_scene_face(s, 3, v2, t2, NULL);
    }
}

/* Kerb faces of one cell: inner edge i (road side, kerb v = 0), outer edge o (kerb v = 1). */
static void strip_kerb_cell(struct vt_synth_scene *s, uint32_t ia, uint32_t ib, uint32_t oa,
                            uint32_t ob, const uint32_t ka[2], const uint32_t kb[2], bool curve)
{
    if (!curve) {
        uint32_t v[4] = {ia, ib, ob, oa}, t[4] = {ka[0], kb[0], kb[1], ka[1]};
        vt_synth_scene_face(s, 4, v, t, NULL);
        return;
    }
    uint32_t v1[3] = {ia, ib, ob}, t1[3] = {ka[0], kb[0], kb[1]};
    uint32_t v2[3] = {ia, ob, oa}, t2[3] = {ka[0], kb[1], ka[1]};
    vt_synth_scene_face(s, 3, v1, t1, NULL);
    vt_synth_scene_face(s, 3, v2, t2, NULL);
}

static void kind_strip(struct vt_synth_scene *s)
{
    const double half = 4.0, kerb = 1.0, metres_per_u = 2.0;
    vt_synth_scene_mtl(s, "newmtl road\nKd 0.4 0.4 0.4\nmap_Kd tex/road.png\n\n"
                          "newmtl kerb\nKd 1 1 1\nmap_Kd tex/kerb.png\n");
    noise_png(s, "tex/road.png", 64, 32);
    uint8_t stripes[16 * 8 * 3];
    for (uint32_t i = 0; i < 16 * 8 * 3; i++)
        stripes[i] = (i / 3 % 16) / 2 % 2 ? 255 : 0; /* 2-texel black and white columns */
    struct vt_synth_scene_png kpng = {16, 8, 3, 8, stripes, NULL, NULL, 0};
    vt_synth_scene_write_png(s, "tex/kerb.png", &kpng);

    double cx = 0, cy = 0, heading = 0, arc = 0;
    struct station prev = {0};
    uint64_t road_faces = 0, road_crossing = 0, faces0 = s->face_count;
    for (int sec = 0; sec < STRIP_SECTIONS; sec++) {
        /* u of the section's stations: start, then start + 0.1 + 0.4 (i - 1): 2 cells in 5 cross
         * an integer line; the first section starts at -700, the last one ends at 2600 */
        double start = -700 + floor((double)sec * (3300.0 - 24.0) / (STRIP_SECTIONS - 1));
        uint32_t n = STRIP_CELLS + (sec == STRIP_SECTIONS - 1);
        double turn = (sec % 2 ? -1 : 1) * (0.03 + 0.02 * vt_synth_scene_rng_unit(&s->rng));
        double ku0 = (double)vt_synth_scene_rng_below(&s->rng, 7) - 3 + (sec % 3 == 1) * 0.5;
        struct station cur;
        uint32_t tprev[2] = {0, 0}, kprev[2] = {0, 0};
        double uprev = 0;
        vt_synth_scene_obj(s, "g section%d\n", sec);
        for (uint32_t i = 0; i <= n; i++) {
            double u = i == 0 ? start : start + 0.1 + 0.4 * (i - 1);
            if (sec == STRIP_SECTIONS - 1 && i == n)
                u = 2600;
            bool curve = i > STRIP_CELLS / 2;
            if (i > 0) { /* advance from the previous station along the cell's mid heading */
                double len = (u - uprev) * metres_per_u;
                double h1 = heading + (curve ? turn : 0);
                cx += len * cos(0.5 * (heading + h1));
                cy += len * sin(0.5 * (heading + h1));
                heading = h1;
                arc += len;
            }
            if (i > 0 || sec == 0) {
                double nx = -sin(heading), ny = cos(heading), z = 1.5 * sin(arc / 25.0);
                cur.lo = vt_synth_scene_v(s, cx + nx * (half + kerb), cy + ny * (half + kerb), z);
                cur.l = vt_synth_scene_v(s, cx + nx * half, cy + ny * half, z);
                cur.r = vt_synth_scene_v(s, cx - nx * half, cy - ny * half, z);
                cur.ro = vt_synth_scene_v(s, cx - nx * (half + kerb), cy - ny * (half + kerb), z);
            } else {
                cur = prev; /* the seam between sections: positions shared, texcoords not */
            }
            uint32_t t[2], k[2]; /* one statement each: the order of the lines is fixed */
            t[0] = vt_synth_scene_vt(s, u, 0);
            t[1] = vt_synth_scene_vt(s, u, 1);
            double ku = ku0 + 0.3 * i;
            k[0] = vt_synth_scene_vt(s, ku, 0);
            k[1] = vt_synth_scene_vt(s, ku, 1);
            if (i > 0) {
                uint64_t f0 = s->face_count;
                vt_synth_scene_obj(s, "usemtl road\n");
                strip_road_cell(s, &prev, &cur, tprev, t, curve, i % 2);
                road_faces += s->face_count - f0;
                if (crosses(uprev, u))
                    road_crossing += s->face_count - f0;
                vt_synth_scene_obj(s, "usemtl kerb\n");
                strip_kerb_cell(s, prev.l, cur.l, prev.lo, cur.lo, kprev, k, curve);
                strip_kerb_cell(s, cur.r, prev.r, cur.ro, prev.ro, k, kprev, curve);
            }
            prev = cur;
            memcpy(tprev, t, sizeof t);
            memcpy(kprev, k, sizeof k);
            uprev = u;
        }
    }
    printf("strip: %llu faces, %llu road faces (%llu crossing an integer u line, %.1f%%), "
           "road u -700..2600\n",
           (unsigned long long)(s->face_count - faces0), (unsigned long long)road_faces,
           (unsigned long long)road_crossing, 100.0 * (double)road_crossing / (double)road_faces);
}

/* ---- offset: charts offset by whole repeats, shared textures, half-used textures ---- */

static void kind_offset(struct vt_synth_scene *s)
{
    vt_synth_scene_mtl(s, "newmtl wood\nKd 0.6 0.4 0.2\nmap_Kd tex/wood.png\n\n"
                          "newmtl crate_a\nKd 1 0 0\nmap_Kd tex/crate.png\n\n"
                          "newmtl crate_b\nKd 0 1 0\nmap_Kd tex/crate.png\n\n"
                          "newmtl crate_c\nKd 0 0 1\nmap_Kd tex/crate.png\n\n"
                          "newmtl sign\nKd 1 1 1\nmap_Kd tex/sign.png\n");
    noise_png(s, "tex/wood.png", 40, 24);
    noise_png(s, "tex/crate.png", 48, 48);
    noise_png(s, "tex/sign.png", 64, 32);
    static const struct {
        const char *mtl;
        struct patch p;
    } charts[] = {
        {"wood", {{0, 0, 0}, {3, 0, 0}, {0, 0, 3}, 3, 3, 0, 1, -1, 0, false}},
        {"wood", {{5, 0, 0}, {2, 0.5, 0}, {0, 0, 2}, 2, 2, 3.2, 3.9, 0.1, 0.8, true}},
        {"wood", {{9, 0, 0}, {1, 0, 0}, {0, 1, 1.5}, 2, 3, -5.5, -5.1, 0.2, 0.9, false}},
        {"crate_a", {{0, 5, 0}, {2, 0, 0}, {0, 0, 2}, 2, 2, 0, 1, 0, 1, false}},
        {"crate_b", {{3, 5, 0}, {2, 0, 0}, {0, 0, 2}, 2, 2, 2, 3, 1, 2, false}},
        {"crate_c", {{6, 5, 0}, {2, 0, 0}, {0, 0.3, 2}, 1, 2, -1.75, -1.25, 5.25, 5.75, true}},
        {"crate_a", {{9, 5, 0}, {2, 0, 0}, {0, 0, 2}, 2, 2, -3, -2, 4, 5, false}},
        {"sign", {{0, 10, 0}, {4, 0, 0}, {0, 0, 2}, 4, 2, 0, 0.5, 0, 1, false}},
    };
    uint32_t faces = 0;
    for (size_t i = 0; i < sizeof charts / sizeof charts[0]; i++) {
        vt_synth_scene_obj(s, "o chart%zu\nusemtl %s\n", i, charts[i].mtl);
        faces += write_patch(s, &charts[i].p);
    }
    printf("offset: %u faces in %zu charts of 5 materials (3 sharing tex/crate.png; "
           "tex/sign.png used in its left half)\n",
           faces, sizeof charts / sizeof charts[0]);
}

/* ---- roof: houses whose walls and roofs tile 0..8 x 0..4 ---- */

/* One closed house at (ox, oy): walls (quads and 5-gon gables, brick, flat normals), a gable roof
 * (rooftile, vt with three components) and a floor without texcoords; every edge is shared by two
 * faces. du, dv: a whole-repeat offset of all its texcoords. */
static void roof_house(struct vt_synth_scene *s, int n, double ox, double oy, double du, double dv)
{
    static const double pos[15][3] = {
        {0, 0, 0}, {4, 0, 0}, {8, 0, 0}, {0, 4, 0}, {4, 4, 0}, {8, 4, 0}, /* b00 b40 b80 b04.. */
        {0, 0, 4}, {4, 0, 4}, {8, 0, 4}, {0, 4, 4}, {4, 4, 4}, {8, 4, 4}, /* t00 t40 t80 t04.. */
        {0, 2, 6}, {4, 2, 6}, {8, 2, 6},                                  /* r0 r4 r8 */
    };
    enum { B00, B40, B80, B04, B44, B84, T00, T40, T80, T04, T44, T84, R0, R4, R8 };
    uint32_t p[15];
    vt_synth_scene_obj(s, "o house%d\n", n);
    for (int i = 0; i < 15; i++)
        p[i] = vt_synth_scene_v(s, ox + pos[i][0], oy + pos[i][1], pos[i][2]);
    /* texcoords (u, v) = (i, j) for i 0..8, j 0..6 are written on demand */
    uint32_t grid[9][7] = {{0}};
    static const struct {
        int n, corner[5], uv[5][2], normal;
    } walls[] = {
        {4, {B00, B40, T40, T00}, {{0, 0}, {4, 0}, {4, 4}, {0, 4}}, 0},
        {4, {B40, B80, T80, T40}, {{4, 0}, {8, 0}, {8, 4}, {4, 4}}, 0},
        {4, {B84, B44, T44, T84}, {{0, 0}, {4, 0}, {4, 4}, {0, 4}}, 1},
        {4, {B44, B04, T04, T44}, {{4, 0}, {8, 0}, {8, 4}, {4, 4}}, 1},
        {5, {B04, B00, T00, R0, T04}, {{0, 0}, {4, 0}, {4, 4}, {2, 6}, {0, 4}}, 2},
        {5, {B80, B84, T84, R8, T80}, {{0, 0}, {4, 0}, {4, 4}, {2, 6}, {0, 4}}, 3},
    };
    static const struct {
        int corner[4], uv[4][2];
    } roofs[] = {
        {{T00, T40, R4, R0}, {{0, 0}, {4, 0}, {4, 4}, {0, 4}}},
        {{T40, T80, R8, R4}, {{4, 0}, {8, 0}, {8, 4}, {4, 4}}},
        {{T84, T44, R4, R8}, {{0, 0}, {4, 0}, {4, 4}, {0, 4}}},
        {{T44, T04, R0, R4}, {{4, 0}, {8, 0}, {8, 4}, {4, 4}}},
    };
    static const double normals[5][3] = {{0, -1, 0}, {0, 1, 0}, {-1, 0, 0}, {1, 0, 0}, {0, 0, -1}};
    uint32_t vn[5];
    for (int i = 0; i < 5; i++)
        vn[i] = vt_synth_scene_vn(s, normals[i][0], normals[i][1], normals[i][2]);
    vt_synth_scene_obj(s, "g house%d walls\nusemtl brick\n", n);
    for (size_t w = 0; w < sizeof walls / sizeof walls[0]; w++) {
        uint32_t v[5], t[5], nn[5];
        for (int c = 0; c < walls[w].n; c++) {
            int i = walls[w].uv[c][0], j = walls[w].uv[c][1];
            if (!grid[i][j])
                grid[i][j] = vt_synth_scene_vt(s, i + du, j + dv);
            v[c] = p[walls[w].corner[c]], t[c] = grid[i][j], nn[c] = vn[walls[w].normal];
        }
        vt_synth_scene_face(s, (uint32_t)walls[w].n, v, t, nn);
    }
    vt_synth_scene_obj(s, "g house%d floor\n", n); /* same object and material, no texcoords */
    uint32_t f1[4] = {p[B00], p[B04], p[B44], p[B40]}, f2[4] = {p[B40], p[B44], p[B84], p[B80]};
    uint32_t fn[4] = {vn[4], vn[4], vn[4], vn[4]};
    vt_synth_scene_face(s, 4, f1, NULL, fn);
    vt_synth_scene_face(s, 4, f2, NULL, fn);
    vt_synth_scene_obj(s, "g house%d roof\nusemtl rooftile\n", n);
    memset(grid, 0, sizeof grid);
    for (size_t r = 0; r < sizeof roofs / sizeof roofs[0]; r++) {
        uint32_t v[4], t[4];
        for (int c = 0; c < 4; c++) {
            int i = roofs[r].uv[c][0], j = roofs[r].uv[c][1];
            if (!grid[i][j])
                grid[i][j] = vt_synth_scene_vt3(s, i + du, j + dv, 0);
            v[c] = p[roofs[r].corner[c]], t[c] = grid[i][j];
        }
        vt_synth_scene_face(s, 4, v, t, NULL);
    }
}

static void kind_roof(struct vt_synth_scene *s)
{
    vt_synth_scene_mtl(s, "newmtl brick\nKd 0.7 0.3 0.2\nmap_Kd tex/brick.png\n\n"
                          "newmtl rooftile\nKd 0.5 0.1 0.1\nmap_Kd tex/rooftile.png\n");
    noise_png(s, "tex/brick.png", 32, 32);
    noise_png(s, "tex/rooftile.png", 32, 16);
    uint64_t f0 = s->face_count;
    for (int h = 0; h < 5; h++) {
        s->relative = h == 3; /* one house written with negative (relative) indices */
        double dy = 2.0 * vt_synth_scene_rng_unit(&s->rng);
        /* house 2's texcoords are offset by whole repeats (16, -4) */
        roof_house(s, h, 12.0 * h, dy, h == 2 ? 16 : 0, h == 2 ? -4 : 0);
    }
    s->relative = false;
    /* a garden wall of unit quads: corners on integer lines, no line strictly inside a face; its
     * shared texcoords (k, 0) and (k, 1) end one face's cell and start the next one's */
    vt_synth_scene_obj(s, "o garden_wall\ng garden_wall\nusemtl brick\n");
    struct patch wall = {{0, -6, 0}, {16, 0, 0}, {0, 0, 1}, 8, 1, 0, 8, 0, 1, false};
    write_patch(s, &wall);
    printf("roof: %llu faces: 5 closed houses (walls and gables 0..8 x 0..6 brick, roofs 0..8 x "
           "0..4 rooftile, floors without vt; house 2 offset by (16, -4), house 3 with relative "
           "indices) and a garden wall of 8 unit quads\n",
           (unsigned long long)(s->face_count - f0));
}

/* ---- torus: closed, watertight, tiling 0..6 x 0..3 ---- */

static void kind_torus(struct vt_synth_scene *s)
{
    enum { NU = 20, NV = 10 };
    const double R = 3, r = 1, pi = 3.14159265358979323846;
    vt_synth_scene_mtl(s, "newmtl donut\nKd 0.8 0.6 0.3\nmap_Kd tex/donut.png\n");
    noise_png(s, "tex/donut.png", 32, 32);
    vt_synth_scene_obj(s, "o torus\ng torus\nusemtl donut\n");
    uint32_t v0 = s->v_count + 1, n0 = s->vn_count + 1, t0 = s->vt_count + 1;
    for (int j = 0; j < NV; j++)
        for (int i = 0; i < NU; i++) {
            double th = 2 * pi * i / NU, ph = 2 * pi * j / NV;
            vt_synth_scene_v(s, (R + r * cos(ph)) * cos(th), (R + r * cos(ph)) * sin(th),
                             r * sin(ph));
            vt_synth_scene_vn(s, cos(ph) * cos(th), cos(ph) * sin(th), sin(ph));
        }
    for (int j = 0; j <= NV; j++) /* the seam: i = NU and j = NV get texcoords of their own */
        for (int i = 0; i <= NU; i++)
            vt_synth_scene_vt(s, 6.0 * i / NU, 3.0 * j / NV);
    for (int j = 0; j < NV; j++)
        for (int i = 0; i < NU; i++) {
            int ci[4] = {i, i + 1, i + 1, i}, cj[4] = {j, j, j + 1, j + 1};
            uint32_t v[4], t[4], n[4];
            for (int c = 0; c < 4; c++) {
                v[c] = v0 + (uint32_t)((cj[c] % NV) * NU + ci[c] % NU);
                n[c] = n0 + (v[c] - v0);
                t[c] = t0 + (uint32_t)(cj[c] * (NU + 1) + ci[c]);
            }
            int d = (i + j) % 2; /* alternate diagonals */
            uint32_t a[3] = {0, 1, 2}, b[3] = {0, 2, 3};
            if (d)
                a[2] = 3, b[0] = 1, b[1] = 2, b[2] = 3;
            uint32_t va[3], ta[3], na[3], vb[3], tb[3], nb[3];
            for (int c = 0; c < 3; c++) {
                va[c] = v[a[c]], ta[c] = t[a[c]], na[c] = n[a[c]];
                vb[c] = v[b[c]], tb[c] = t[b[c]], nb[c] = n[b[c]];
            }
            vt_synth_scene_face(s, 3, va, ta, na);
            vt_synth_scene_face(s, 3, vb, tb, nb);
        }
    printf("torus: %d triangles, %d positions, texcoords 0..6 x 0..3 in steps of 0.3\n",
           2 * NU * NV, NU * NV);
}

/* ---- mix: 600 materials over textures of every kind ---- */

#define MIX_MATERIALS 600

struct mix_texture {
    const char *path; /* relative to OUTDIR/tex; referenced from OUTDIR/mtl as ../tex/... */
    uint32_t w, h;
    int kind; /* 0 RGB, 1 palette 8-bit, 2 palette 4-bit + tRNS, 3 grey, 4 grey + alpha,
                 5 RGB 16-bit, 6 grey 16-bit, 7 RGBA cut-out */
};

static const struct mix_texture mix_textures[] = {
    {"rgb/r64.png", 64, 64, 0},      {"rgb/r300x17.png", 300, 17, 0},
    {"rgb/r2048x8.png", 2048, 8, 0}, {"rgb/r17x5.png", 17, 5, 0},
    {"pal/p8.png", 64, 32, 1},       {"pal/p4t.png", 30, 10, 2},
    {"grey/g48.png", 48, 48, 3},     {"grey/ga20.png", 20, 20, 4},
    {"deep/d40.png", 40, 40, 5},     {"deep/dg24.png", 24, 24, 6},
    {"alpha/cutout.png", 64, 64, 7}, {"rgb/sub/r96x40.png", 96, 40, 0},
};
#define MIX_TEXTURES (sizeof mix_textures / sizeof mix_textures[0])

static void mix_png(struct vt_synth_scene *s, const struct mix_texture *t)
{
    char rel[256];
    snprintf(rel, sizeof rel, "tex/%s", t->path);
    uint32_t n = t->w * t->h;
    struct vt_synth_scene_png png = {t->w, t->h, 3, 8, NULL, NULL, NULL, 0};
    uint8_t *p8 = NULL, pal[256 * 3], trns[256];
    uint16_t *p16 = NULL;
    switch (t->kind) {
    case 0:
        p8 = vt_synth_scene_noise8(s, t->w, t->h, 3);
        break;
    case 1:
    case 2:
        png.palette_size = t->kind == 1 ? 200 : 16;
        png.bits = t->kind == 1 ? 8 : 4;
        for (uint32_t i = 0; i < png.palette_size * 3; i++)
            pal[i] = (uint8_t)(vt_synth_scene_rng_next(&s->rng) >> 56);
        for (uint32_t i = 0; i < png.palette_size; i++)
            trns[i] = i % 3 == 0 ? 0 : i % 3 == 1 ? 128 : 255;
        p8 = malloc(n);
        for (uint32_t i = 0; i < n; i++)
            p8[i] = (uint8_t)vt_synth_scene_rng_below(&s->rng, png.palette_size);
        png.channels = 1;
        png.palette = pal;
        png.trns = t->kind == 2 ? trns : NULL;
        break;
    case 3:
    case 4:
        png.channels = (uint32_t)t->kind - 2;
        p8 = vt_synth_scene_noise8(s, t->w, t->h, png.channels);
        break;
    case 5:
    case 6:
        png.channels = t->kind == 5 ? 3 : 1;
        png.bits = 16;
        p16 = malloc((size_t)n * png.channels * sizeof *p16);
        for (uint32_t i = 0; i < n * png.channels; i++)
            p16[i] = (uint16_t)(vt_synth_scene_rng_next(&s->rng) >> 48);
        break;
    default: /* a cut-out: opaque inside a disc, fully transparent (but coloured) outside */
        png.channels = 4;
        p8 = vt_synth_scene_noise8(s, t->w, t->h, 4);
        for (uint32_t y = 0; y < t->h; y++)
            for (uint32_t x = 0; x < t->w; x++) {
                double dx = x + 0.5 - t->w / 2.0, dy = y + 0.5 - t->h / 2.0;
                p8[4 * (y * t->w + x) + 3] = dx * dx + dy * dy < 0.2 * t->w * t->h ? 255 : 0;
            }
        break;
    }
    if (!p8 && !p16)
        vt_synth_scene_die("out of memory");
    png.pixels = p8 ? (const void *)p8 : (const void *)p16;
    vt_synth_scene_write_png(s, rel, &png);
    free(p8);
    free(p16);
}

static void kind_mix(struct vt_synth_scene *s)
{
    for (size_t t = 0; t < MIX_TEXTURES; t++)
        mix_png(s, &mix_textures[t]);
    /* UV ranges of the charts: 0..1, repeating 0..3 x 0..1 and 0..3 x 0..3, offset by whole
     * repeats (2..3 x -1..0), a part (0.25..0.75 x 0.2..0.7) */
    static const double ranges[5][4] = {
        {0, 1, 0, 1}, {0, 3, 0, 1}, {0, 3, 0, 3}, {2, 3, -1, 0}, {0.25, 0.75, 0.2, 0.7}};
    uint32_t faces = 0, missing = 0, constant = 0;
    for (uint32_t i = 0; i < MIX_MATERIALS; i++) {
        struct vt_synth_scene_rng *r = &s->rng;
        double kd[3];
        for (int c = 0; c < 3; c++) /* one call each: argument order is unspecified */
            kd[c] = vt_synth_scene_rng_unit(r);
        vt_synth_scene_mtl(s, "\nnewmtl m%03u\nKd %.3f %.3f %.3f\n", i, kd[0], kd[1], kd[2]);
        if (i == 137 || i == 412) {
            vt_synth_scene_mtl(s, "map_Kd ../tex/%s\n",
                               i == 137 ? "gone/nothing.png" : "rgb/absent.png");
            missing++;
        } else if (i % 50 == 7) {
            constant++; /* Kd only */
        } else {
            vt_synth_scene_mtl(s, "map_Kd ../tex/%s\n", mix_textures[i % MIX_TEXTURES].path);
        }
        const double *q = ranges[i / MIX_TEXTURES % 5];
        double x = 3.0 * (i % 25), y = 3.0 * (i / 25), z = 0.25 * sin(0.7 * i);
        struct patch p = {{x, y, z}, {2, 0, 0.1}, {0, 1.5, 0}, 2,    1,
                          q[0],      q[1],        q[2],        q[3], i % 3 == 0};
        vt_synth_scene_obj(s, "usemtl m%03u\n", i);
        faces += write_patch(s, &p);
    }
    printf("mix: %u faces, %d materials over %zu textures (%u missing, %u constant)\n", faces,
           MIX_MATERIALS, MIX_TEXTURES, missing, constant);
}

static const struct {
    const char *name, *obj, *mtl;
    void (*write)(struct vt_synth_scene *s);
} kinds[] = {
    {"strip", "strip.obj", "strip.mtl", kind_strip},
    {"offset", "offset.obj", "offset.mtl", kind_offset},
    {"roof", "roof.obj", "roof.mtl", kind_roof},
    {"torus", "torus.obj", "torus.mtl", kind_torus},
    {"mix", "mix.obj", "mtl/mix.mtl", kind_mix},
};

static int usage(FILE *f, int rc)
{
    fprintf(f, "usage: vt-synth-scene strip|offset|roof|torus|mix OUTDIR [--seed N]\n");
    return rc;
}

int main(int argc, char **argv)
{
    static const struct option opts[] = {
        {"seed", required_argument, 0, 's'}, {"help", no_argument, 0, 'h'}, {0, 0, 0, 0}};
    unsigned long long seed = 1;
    int c;
    while ((c = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        char *end;
        switch (c) {
        case 's':
            seed = strtoull(optarg, &end, 10);
            if (*end || end == optarg)
                return usage(stderr, 2);
            break;
        case 'h':
            return usage(stdout, 0);
        default:
            return usage(stderr, 2);
        }
    }
    if (argc - optind != 2)
        return usage(stderr, 2);
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        if (strcmp(argv[optind], kinds[k].name) != 0)
            continue;
        struct vt_synth_scene s;
        vt_synth_scene_open(&s, argv[optind + 1], kinds[k].obj, kinds[k].mtl, kinds[k].name, seed);
        kinds[k].write(&s);
        vt_synth_scene_close(&s);
        return 0;
    }
    fprintf(stderr, "vt-synth-scene: unknown kind '%s'\n", argv[optind]);
    return usage(stderr, 2);
}
