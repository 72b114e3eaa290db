/* Test scenes for vt-view's --reference-scene (tests/e2e/view/CMakeLists.txt).
 *
 * scene (case scene_reference): a wall of textured quads, a floor whose material wraps (UVs in
 * [-1, 2], for vt-atlas --wrap replicate), a quad with its UVs turned by 90 degrees and one
 * material without a texture (Kd only, UVs inside [0.25, 0.75]). Every texture is a power of two
 * (so the reference's box mips equal vt-tiles' box mips) and holds a smooth pattern unique to it,
 * with a few sharp lines; the wrapped one tiles seamlessly.
 *
 * repeat (case scene_repeat): repeating materials as real scenes have them, with high-contrast
 * textures that do NOT tile seamlessly (so that a clamped seam shows): a floor strip x in [-20, 60]
 * (z in [0, 1]) whose material repeats u -20..60, v 0..1 (black and white stripes, then a checker:
 * its first column is white, its last alternates), cut into four quads at non-integer u; a floor
 * patch beside it repeating 0..3 x 0..2 (a coloured checker with a dark frame); and a wall facing
 * +z at z = -3 with u 2600..2602, v 0..1 (fine stripes), far from 0 where float32 has a step of
 * 1/4096 (256 texels per repeat). One world unit is one repeat along the strip. Where a surface
 * ends (the strip's and the wall's long edges, the patch's border) the opposite texture edges
 * are equal: there an engine repeats while vt-atlas clamps the outer edge of its copies, and the
 * test is about the seams inside. repeat_cut.obj is the same scene with the strip cut along
 * every integer u and each piece moved into [0, 1], as vt-offset cuts faces for a wrapping atlas
 * entry (vt-atlas then lays one copy with a clamped gutter: the seams show).
 *
 * usage: vtv_make_scene OUTDIR            (writes OUTDIR/scene.obj, scene.mtl, tex/NAME.png)
 *        vtv_make_scene --repeat OUTDIR   (writes OUTDIR/repeat.obj, repeat_cut.obj, repeat.mtl,
 *                                          tex/NAME.png) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_png_file.h"

struct tex {
    const char *name;
    unsigned w, h;
};

/* Materials in the order of the MTL; the last one has no texture. */
static const struct tex texs[] = {
    {"a", 128, 128}, {"b", 64, 64}, {"c", 64, 32}, {"d", 16, 16}, {"e", 256, 64}, {"wrap", 32, 32},
};
#define TEX_COUNT (sizeof texs / sizeof texs[0])

static unsigned char pattern(unsigned t, const struct tex *x, unsigned i, unsigned j, int c)
{
    const double pi = 3.14159265358979;
    double u = (i + 0.5) / x->w, v = (j + 0.5) / x->h, s;
    if (c == 0)
        s = 0.5 + 0.4 * sin(2 * pi * (u * (1 + t % 3) + 0.13 * t));
    else if (c == 1)
        s = 0.5 + 0.4 * cos(2 * pi * (v * (2 + t % 2) + u + 0.29 * t));
    else
        s = 0.3 + 0.1 * t + 0.25 * sin(2 * pi * (u + 2 * v));
    if (i % 16 == 5 || j % 16 == 11) /* sharp lines */
        s = c == (int)(t % 3) ? 0.95 : 0.05;
    return (unsigned char)lround(fmin(fmax(s, 0.0), 1.0) * 255.0);
}

typedef unsigned char (*pixel_fn)(unsigned t, const struct tex *x, unsigned i, unsigned j, int c);

static int write_texture(const char *dir, const struct tex *x, pixel_fn px, unsigned t)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/tex/%s.png", dir, x->name);
    struct vts_error err;
    struct vt_png_file_writer *w = vt_png_file_writer_create(path, x->w, x->h, 3, 8, &err);
    unsigned char *row = malloc((size_t)x->w * 3);
    int st = w && row ? 0 : -1;
    for (unsigned j = 0; st == 0 && j < x->h; j++) {
        for (unsigned i = 0; i < x->w; i++)
            for (int c = 0; c < 3; c++)
                row[i * 3 + c] = px(t, x, i, j, c);
        st = vt_png_file_writer_rows(w, row, 1, 0, &err);
    }
    if (st == 0)
        st = vt_png_file_writer_finish(w, &err);
    if (st != 0)
        fprintf(stderr, "vtv_make_scene: %s\n", w ? err.message : "cannot create");
    vt_png_file_writer_destroy(w);
    free(row);
    return st;
}

/* One quad: corners p0 + a*du + b*dv with UVs (u0 + a*su, v0 + b*sv), a, b in {0, 1}; turn: the
 * UVs rotated by 90 degrees. */
static unsigned vcount;
static void quad(FILE *f, const char *mtl, const double p0[3], const double du[3],
                 const double dv[3], double u0, double v0, double su, double sv, int turn)
{
    static const int ab[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    fprintf(f, "usemtl %s\n", mtl);
    for (int k = 0; k < 4; k++) {
        int a = ab[k][0], b = ab[k][1], ta = turn ? ab[(k + 1) % 4][0] : a;
        int tb = turn ? ab[(k + 1) % 4][1] : b;
        fprintf(f, "v %g %g %g\nvt %g %g\n", p0[0] + a * du[0] + b * dv[0],
                p0[1] + a * du[1] + b * dv[1], p0[2] + a * du[2] + b * dv[2], u0 + ta * su,
                v0 + tb * sv);
    }
    fprintf(f, "f %u/%u %u/%u %u/%u %u/%u\n", vcount + 1, vcount + 1, vcount + 2, vcount + 2,
            vcount + 3, vcount + 3, vcount + 4, vcount + 4);
    vcount += 4;
}

static int make_scene(const char *dir)
{
    char path[4096];
    for (unsigned t = 0; t < TEX_COUNT; t++)
        if (write_texture(dir, &texs[t], pattern, t) != 0)
            return 1;
    snprintf(path, sizeof path, "%s/scene.mtl", dir);
    FILE *mtl = fopen(path, "w");
    snprintf(path, sizeof path, "%s/scene.obj", dir);
    FILE *obj = fopen(path, "w");
    if (!mtl || !obj) {
        fprintf(stderr, "vtv_make_scene: cannot write in '%s'\n", dir);
        return 1;
    }
    for (unsigned t = 0; t < TEX_COUNT; t++)
        fprintf(mtl, "newmtl m_%s\nKd 1 1 1\nmap_Kd tex/%s.png\n\n", texs[t].name, texs[t].name);
    fprintf(mtl, "newmtl m_plain\nKd 0.2 0.6 0.3\n");
    fprintf(obj, "# generated by vtv_make_scene\nmtllib scene.mtl\no scene\n");
    /* the wall, z = 0, x in [-1.5, 1.5], y in [0, 1.5] */
    const double pa[3] = {-1.5, 0, 0}, pb[3] = {-0.5, 0, 0}, pc[3] = {0.5, 0, 0};
    const double pd[3] = {0.5, 0.5, 0}, pe[3] = {-1.5, 1, 0};
    const double w1[3] = {1, 0, 0}, h1[3] = {0, 1, 0}, h05[3] = {0, 0.5, 0}, w3[3] = {3, 0, 0};
    quad(obj, "m_a", pa, w1, h1, 0, 0, 1, 1, 0);
    quad(obj, "m_b", pb, w1, h1, 0, 0, 1, 1, 1); /* UVs turned */
    quad(obj, "m_c", pc, w1, h05, 0, 0, 1, 1, 0);
    quad(obj, "m_d", pd, w1, h05, 0, 0, 1, 1, 0);
    quad(obj, "m_e", pe, w3, h05, 0, 0, 1, 1, 0);
    const double pplain[3] = {-0.2, 1.5, 0}, wplain[3] = {0.4, 0, 0}, hplain[3] = {0, 0.2, 0};
    /* UVs inside the constant cell vt-atlas lays for it (4 x 4 texels): UVs 0..1 would reach its
     * edge, where bilinear filtering reads the neighbouring cells */
    quad(obj, "m_plain", pplain, wplain, hplain, 0.25, 0.25, 0.5, 0.5, 0);
    /* the floor, y = 0, z in [0, 1.5], UVs in [-1, 2] (3 x 3 copies of the wrapped texture) */
    const double pf[3] = {-1.5, 0, 1.5}, df[3] = {0, 0, -1.5};
    quad(obj, "m_wrap", pf, w3, df, -1, -1, 3, 3, 0);
    if (fclose(mtl) != 0 || fclose(obj) != 0) {
        fprintf(stderr, "vtv_make_scene: cannot write in '%s'\n", dir);
        return 1;
    }
    return 0;
}

/* The repeat scene's textures (see the top of this file). */
static const struct tex rtexs[] = {{"strip", 64, 64}, {"grid", 32, 32}, {"far", 256, 64}};

static unsigned char repeat_pattern(unsigned t, const struct tex *x, unsigned i, unsigned j, int c)
{
    (void)x;
    if (t == 0) { /* stripes 4 texels wide (white first), then a checker of 8-texel cells whose
                     rows are offset by 4, so that the first and last rows are equal: the strip
                     repeats only along u, and an engine's repeat along v (at the strip's long
                     edges) then reads what the atlas's clamp reads */
        unsigned on = i < 32 ? (i / 4) % 2 == 0 : (i / 8 + (j + 4) / 8) % 2;
        return on ? 255 : 0;
    }
    if (t == 1) { /* red/blue checker of 4-texel cells in a dark frame (on all four sides, so
                     that repeating it at the patch's outer edge reads what the atlas's clamp
                     reads there; inside the patch two copies meet in a line 2 texels wide) */
        static const unsigned char red[3] = {220, 40, 40}, blue[3] = {40, 60, 220};
        if (i == 0 || j == 0 || i == 31 || j == 31)
            return 20;
        return ((i / 4 + j / 4) % 2 ? red : blue)[c];
    }
    /* vertical stripes 2 texels wide, a dark line 2 texels high every 16 rows (not at the first
     * or last row, which are equal: the wall repeats only along u), a green tint */
    unsigned on = (i / 2) % 2 == 0 && j % 16 != 7 && j % 16 != 8;
    return (unsigned char)(on ? (c == 1 ? 255 : 200) : (c == 1 ? 40 : 0));
}

/* The repeat scene's geometry; cut: the strip as vt-offset cuts it for a wrapping entry (one quad
 * per unit of u, UVs 0..1), else as a modeller writes it (four quads cut at non-integer u). */
static void repeat_geometry(FILE *f, int cut)
{
    vcount = 0;
    fprintf(f, "# generated by vtv_make_scene --repeat%s\nmtllib repeat.mtl\no repeat\n",
            cut ? ": the strip cut along integer u, each piece moved into [0,1]" : "");
    /* the strip: u = x, v = 1 - z */
    static const double cuts[] = {-20, -7.5, 5.25, 30.5, 60};
    const double dz[3] = {0, 0, -1}, d1[3] = {1, 0, 0};
    for (unsigned k = 0; !cut && k + 1 < sizeof cuts / sizeof cuts[0]; k++) {
        const double p0[3] = {cuts[k], 0, 1}, du[3] = {cuts[k + 1] - cuts[k], 0, 0};
        quad(f, "m_strip", p0, du, dz, cuts[k], 0, cuts[k + 1] - cuts[k], 1, 0);
    }
    for (int x = -20; cut && x < 60; x++) {
        const double p0[3] = {x, 0, 1};
        quad(f, "m_strip", p0, d1, dz, 0, 0, 1, 1, 0);
    }
    /* the patch beside it: 3 x 2 repeats of one unit each; the wall with UVs far from 0 */
    const double pg[3] = {-19, 0, 3.2}, wg[3] = {3, 0, 0}, hg[3] = {0, 0, -2};
    const double pw[3] = {-20, 0, -3}, ww[3] = {2, 0, 0}, hw[3] = {0, 1, 0};
    quad(f, "m_grid", pg, wg, hg, 0, 0, 3, 2, 0);
    quad(f, "m_far", pw, ww, hw, 2600, 0, 2, 1, 0);
}

static int make_repeat(const char *dir)
{
    char path[4096];
    for (unsigned t = 0; t < sizeof rtexs / sizeof rtexs[0]; t++)
        if (write_texture(dir, &rtexs[t], repeat_pattern, t) != 0)
            return 1;
    snprintf(path, sizeof path, "%s/repeat.mtl", dir);
    FILE *mtl = fopen(path, "w");
    snprintf(path, sizeof path, "%s/repeat.obj", dir);
    FILE *obj = fopen(path, "w");
    snprintf(path, sizeof path, "%s/repeat_cut.obj", dir);
    FILE *cut = fopen(path, "w");
    if (!mtl || !obj || !cut) {
        fprintf(stderr, "vtv_make_scene: cannot write in '%s'\n", dir);
        return 1;
    }
    for (unsigned t = 0; t < sizeof rtexs / sizeof rtexs[0]; t++)
        fprintf(mtl, "newmtl m_%s\nKd 1 1 1\nmap_Kd tex/%s.png\n\n", rtexs[t].name, rtexs[t].name);
    repeat_geometry(obj, 0);
    repeat_geometry(cut, 1);
    if (fclose(mtl) != 0 || fclose(obj) != 0 || fclose(cut) != 0) {
        fprintf(stderr, "vtv_make_scene: cannot write in '%s'\n", dir);
        return 1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "--repeat") == 0)
        return make_repeat(argv[2]);
    if (argc != 2) {
        fprintf(stderr, "usage: vtv_make_scene [--repeat] OUTDIR\n");
        return 2;
    }
    return make_scene(argv[1]);
}
