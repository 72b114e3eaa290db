/* The effects scene of vt-view's materials test (tests/e2e/view/run_view_test.sh, case
 * scene_effects): every effect a material can call for, each on its own quad facing +z, in front
 * of a camera at (0, 0.75, 2.6) looking at (0, 0.75, 0):
 *   wall   a stone texture with a normal map of ridges and bumps (norm), lit by a grazing light;
 *   shiny  map_Ks stripes, Ks 1, Ns 8, illum 2 (Blinn-Phong);
 *   mask   map_Kd whose alpha is a binary team-colour mask, not transparency (vt_alpha none);
 *   fence  an opaque wood texture cut out by a lattice in map_d, in front of the wall;
 *   tree   map_Kd with a cut-out alpha (a disc and a trunk), found by vt-atlas's cut-out rule;
 *   glass  a constant pane, d 0.5 (blended);
 *   sign   a constant emissive strip (Ke).
 * All textures are 64 x 64 (powers of two: the reference's box mips are the store's).
 * tex/flat_n.png is a flat normal map of the same size (the negative control swaps it in).
 * opaque.obj holds the wall, shiny, mask and sign quads only (no alpha variant may be compiled).
 *
 * tilt (vtv_make_effects --tilt): the tangent frame's orientation against an independent
 * expectation: three grey quads facing +z with one normal map whose normal leans towards +u and
 * +v (0.5, 0.5, 0.7); the first has u along +x and v along +y, the second u mirrored (along -x),
 * the third v mirrored (along -y). Under a light from +x +y the first is lit the most; a tangent
 * or bitangent of the wrong sign would darken it.
 *
 * usage: vtv_make_effects OUTDIR          (writes OUTDIR/effects.obj, opaque.obj, effects.mtl,
 *                                          tex/NAME.png; OUTDIR/tex must exist)
 *        vtv_make_effects --tilt OUTDIR   (writes OUTDIR/tilt.obj, tilt.mtl, tex/grey.png,
 *                                          tex/tilt_n.png) */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_png_file.h"

#define N 64

static const double pi = 3.14159265358979;

static unsigned char u8(double v)
{
    return (unsigned char)lround(fmin(fmax(v, 0.0), 1.0) * 255.0);
}

/* Texel (i, j) (j from the top row) of texture t, channels c = 0..channels-1. */
static unsigned char texel(const char *t, unsigned i, unsigned j, int c)
{
    double u = (i + 0.5) / N, v = 1.0 - (j + 0.5) / N;
    if (!strcmp(t, "wood")) {
        static const double base[3] = {0.55, 0.35, 0.18};
        return u8(base[c] * (0.8 + 0.2 * sin(2 * pi * (6 * u + 0.7 * sin(2 * pi * v)))));
    }
    if (!strcmp(t, "fence_d")) /* bars 6 texels wide every 16: a lattice with 10 x 10 holes */
        return (i % 16 < 6 || j % 16 < 6) ? 255 : 0;
    if (!strcmp(t, "wall")) {
        static const double base[3] = {0.75, 0.72, 0.68};
        return u8(base[c] * (0.9 + 0.1 * sin(2 * pi * (3 * u + 2 * v))));
    }
    if (!strcmp(t, "wall_n") || !strcmp(t, "flat_n")) {
        /* height h = 0.06 sin(2 pi 4 u) + 0.04 cos(2 pi 3 v): n = (-dh/du, -dh/dv, 1) normalised
         * (u, v per texture: strong slopes) */
        double dx = 0, dy = 0;
        if (!strcmp(t, "wall_n")) {
            dx = 0.06 * 2 * pi * 4 * cos(2 * pi * 4 * u);
            dy = -0.04 * 2 * pi * 3 * sin(2 * pi * 3 * v);
        }
        double n[3] = {-dx, -dy, 1}, l = sqrt(n[0] * n[0] + n[1] * n[1] + 1);
        return u8(n[c] / l * 0.5 + 0.5);
    }
    if (!strcmp(t, "grey"))
        return 128;
    if (!strcmp(t, "tilt_n")) {
        const double n[3] = {0.5, 0.5, 0.7}, l = sqrt(0.25 + 0.25 + 0.49);
        return u8(n[c] / l * 0.5 + 0.5);
    }
    if (!strcmp(t, "shiny")) {
        static const double base[3] = {0.2, 0.3, 0.6};
        return u8(base[c] + 0.1 * sin(2 * pi * 2 * u));
    }
    if (!strcmp(t, "shiny_s")) /* stripes of specular colour, 8 texels wide */
        return (i / 8) % 2 ? u8(c == 2 ? 0.9 : 0.8) : 16;
    if (!strcmp(t, "tree")) {
        double dx = u - 0.5, dy = v - 0.62;
        bool canopy = dx * dx + dy * dy < 0.36 * 0.36;
        bool trunk = fabs(dx) < 0.07 && v < 0.35;
        if (c == 3)
            return canopy || trunk ? 255 : 0;
        static const double leaf[3] = {0.15, 0.55, 0.12}, bark[3] = {0.4, 0.25, 0.1};
        if (canopy)
            return u8(leaf[c] * (0.8 + 0.2 * sin(2 * pi * 5 * (u + v))));
        return u8(trunk ? bark[c] : 1.0 - 0.5 * c); /* a loud colour where it is cut out */
    }
    /* mask: a red/yellow checker; alpha a binary team-colour mask (stripes), not coverage */
    if (c == 3)
        return (i / 4) % 2 ? 255 : 0;
    static const double red[3] = {0.8, 0.15, 0.1}, yellow[3] = {0.9, 0.8, 0.2};
    return u8(((i / 8 + j / 8) % 2 ? red : yellow)[c]);
}

static int write_texture(const char *dir, const char *name, unsigned channels)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/tex/%s.png", dir, name);
    struct vts_error err;
    struct vt_png_file_writer *w = vt_png_file_writer_create(path, N, N, channels, 8, &err);
    unsigned char row[N * 4];
    int st = w ? 0 : -1;
    for (unsigned j = 0; st == 0 && j < N; j++) {
        for (unsigned i = 0; i < N; i++)
            for (unsigned c = 0; c < channels; c++)
                row[i * channels + c] = texel(name, i, j, (int)c);
        st = vt_png_file_writer_rows(w, row, 1, 0, &err);
    }
    if (st == 0)
        st = vt_png_file_writer_finish(w, &err);
    if (st != 0)
        fprintf(stderr, "vtv_make_effects: %s\n", w ? err.message : "cannot create a texture");
    vt_png_file_writer_destroy(w);
    return st;
}

static unsigned vcount;

/* A quad facing +z at depth z: x in [x0, x1], y in [y0, y1], UVs 0..1. */
static void quad(FILE *f, const char *mtl, double x0, double x1, double y0, double y1, double z)
{
    fprintf(f, "usemtl %s\n", mtl);
    fprintf(f, "v %g %g %g\nv %g %g %g\nv %g %g %g\nv %g %g %g\n", x0, y0, z, x1, y0, z, x1, y1, z,
            x0, y1, z);
    fprintf(f, "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n");
    fprintf(f, "f %u/%u %u/%u %u/%u %u/%u\n", vcount + 1, vcount + 1, vcount + 2, vcount + 2,
            vcount + 3, vcount + 3, vcount + 4, vcount + 4);
    vcount += 4;
}

static const char mtl_text[] = "newmtl wall\nKd 1 1 1\nillum 1\nmap_Kd tex/wall.png\n"
                               "norm tex/wall_n.png\n\n"
                               "newmtl shiny\nKd 1 1 1\nKs 1 1 1\nNs 8\nillum 2\n"
                               "map_Kd tex/shiny.png\nmap_Ks tex/shiny_s.png\n\n"
                               "newmtl mask\nKd 1 1 1\nillum 1\nvt_alpha none\n"
                               "map_Kd tex/mask.png\n\n"
                               "newmtl fence\nKd 1 1 1\nillum 1\nmap_Kd tex/wood.png\n"
                               "map_d tex/fence_d.png\n\n"
                               "newmtl tree\nKd 1 1 1\nillum 1\nmap_Kd tex/tree.png\n\n"
                               "newmtl glass\nKd 0.3 0.5 0.8\nd 0.5\nillum 1\n\n"
                               "newmtl sign\nKd 0.1 0.1 0.1\nKe 0.6 0.3 0.1\nillum 1\n";

static void geometry(FILE *f, bool opaque)
{
    vcount = 0;
    fprintf(f, "# generated by vtv_make_effects\nmtllib effects.mtl\no effects\n");
    quad(f, "wall", -1.2, 0, 0, 1.5, 0);
    quad(f, "shiny", 0, 1.2, 0, 0.75, 0);
    quad(f, "mask", 0, 1.2, 0.75, 1.5, 0);
    quad(f, "sign", -1.0, -0.4, 1.55, 1.8, 0);
    if (opaque)
        return;
    quad(f, "fence", -1.1, -0.1, -0.3, 0.7, 0.5);
    quad(f, "tree", 0.1, 0.9, -0.3, 0.7, 0.7);
    quad(f, "glass", 0.7, 1.15, 0.9, 1.35, 0.3);
}

/* The tilt scene (top of the file). */
static int make_tilt(const char *dir)
{
    if (write_texture(dir, "grey", 3) != 0 || write_texture(dir, "tilt_n", 3) != 0)
        return 1;
    char path[4096];
    snprintf(path, sizeof path, "%s/tilt.mtl", dir);
    FILE *mtl = fopen(path, "w");
    snprintf(path, sizeof path, "%s/tilt.obj", dir);
    FILE *obj = fopen(path, "w");
    if (!mtl || !obj) {
        fprintf(stderr, "vtv_make_effects: cannot write in '%s'\n", dir);
        return 1;
    }
    fputs("newmtl tilt\nKd 1 1 1\nillum 1\nmap_Kd tex/grey.png\nnorm tex/tilt_n.png\n", mtl);
    fputs("# generated by vtv_make_effects --tilt\nmtllib tilt.mtl\nusemtl tilt\n", obj);
    /* corner UVs: as laid, u mirrored, v mirrored */
    static const double uv[3][4][2] = {{{0, 0}, {1, 0}, {1, 1}, {0, 1}},
                                       {{1, 0}, {0, 0}, {0, 1}, {1, 1}},
                                       {{0, 1}, {1, 1}, {1, 0}, {0, 0}}};
    for (int q = 0; q < 3; q++) {
        double x0 = -0.9 + 0.65 * q, x1 = x0 + 0.5, y0 = 0.15, y1 = 0.65;
        fprintf(obj, "v %g %g 0\nv %g %g 0\nv %g %g 0\nv %g %g 0\n", x0, y0, x1, y0, x1, y1, x0,
                y1);
        for (int k = 0; k < 4; k++)
            fprintf(obj, "vt %g %g\n", uv[q][k][0], uv[q][k][1]);
        unsigned b = (unsigned)q * 4;
        fprintf(obj, "f %u/%u %u/%u %u/%u %u/%u\n", b + 1, b + 1, b + 2, b + 2, b + 3, b + 3, b + 4,
                b + 4);
    }
    if (fclose(mtl) != 0 || fclose(obj) != 0) {
        fprintf(stderr, "vtv_make_effects: cannot write in '%s'\n", dir);
        return 1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 3 && !strcmp(argv[1], "--tilt"))
        return make_tilt(argv[2]);
    if (argc != 2) {
        fprintf(stderr, "usage: vtv_make_effects [--tilt] OUTDIR\n");
        return 2;
    }
    const char *dir = argv[1];
    static const struct {
        const char *name;
        unsigned channels;
    } texs[] = {{"wood", 3},  {"fence_d", 1}, {"wall", 3}, {"wall_n", 3}, {"flat_n", 3},
                {"shiny", 3}, {"shiny_s", 3}, {"tree", 4}, {"mask", 4}};
    for (size_t t = 0; t < sizeof texs / sizeof texs[0]; t++)
        if (write_texture(dir, texs[t].name, texs[t].channels) != 0)
            return 1;
    char path[4096];
    const char *names[3] = {"effects.mtl", "effects.obj", "opaque.obj"};
    for (int k = 0; k < 3; k++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[k]);
        FILE *f = fopen(path, "w");
        if (!f) {
            fprintf(stderr, "vtv_make_effects: cannot write '%s'\n", path);
            return 1;
        }
        if (k == 0)
            fputs(mtl_text, f);
        else
            geometry(f, k == 2);
        if (fclose(f) != 0) {
            fprintf(stderr, "vtv_make_effects: cannot write '%s'\n", path);
            return 1;
        }
    }
    return 0;
}
