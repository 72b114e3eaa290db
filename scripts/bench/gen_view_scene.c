/* The scene of scripts/bench/view-costs: a corridor (floor, two walls, a back wall) crossed by
 * three panels, every face with the one material under test, so that the frame time measures
 * what that material's features cost. Textures with detail at every scale (sums of sines over
 * several octaves), each surface its own texture at 256 texels per unit along both axes (floor
 * 512 x 2560, walls 2560 x 512, back and panels 512 x 512), so that the floor and the walls seen
 * down the corridor are anisotropic footprints.
 *
 * usage: gen_view_scene OUTDIR FEATURE    FEATURE: plain | alpha_test | blend | normal |
 *                                          specular | all
 * writes OUTDIR/scene.obj, OUTDIR/scene.mtl and OUTDIR/tex/NAME.png (OUTDIR/tex must exist).
 *   plain       map_Kd, lit
 *   alpha_test  map_Kd and map_d (a lattice of holes)
 *   blend       map_Kd, d 0.6
 *   normal      map_Kd and norm (bumps)
 *   specular    map_Kd and map_Ks (stripes), Ks 1, Ns 16
 *   all         all of the above in one material */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_png_file.h"

static const double pi = 3.14159265358979;

static unsigned char u8(double v)
{
    return (unsigned char)lround(fmin(fmax(v, 0.0), 1.0) * 255.0);
}

/* Per-texel noise in [-1, 1] (an integer hash): no two tiles alike, detail at the texel. */
static double noise(unsigned i, unsigned j, unsigned seed)
{
    unsigned h = i * 0x9E3779B1u ^ (j + 0x7F4A7C15u * seed) * 0x85EBCA77u;
    h ^= h >> 15;
    h *= 0x2C1B3C6Du;
    h ^= h >> 12;
    return (h & 0xFFFF) / 32767.5 - 1.0;
}

/* A height in [-1, 1] with detail from 1/2 of the texture down to 2 texels (frequencies not
 * multiples of one another: the texture does not repeat). */
static double height(unsigned n, double x, double y, unsigned seed)
{
    double h = 0, a = 0.5;
    for (double f = 2; f <= n / 2.0; f *= 2, a *= 0.6) {
        double p = seed * 1.7 + f * 0.37;
        double g = f * (1.13 + 0.1 * sin(p)) / n;
        h += a * sin(2 * pi * (g * x + 0.3 * sin(p))) * cos(2 * pi * (g * y + 0.7 * cos(p)));
    }
    return h;
}

/* A texture of w x h texels (frequencies scaled for 512 texels whatever the size); kind: 'd'
 * diffuse (RGB), 'n' normal map, 's' specular stripes, 'a' map_d lattice (grey). */
static int write_texture(const char *dir, const char *name, unsigned w, unsigned h, char kind,
                         unsigned seed)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/tex/%s.png", dir, name);
    unsigned ch = kind == 'a' ? 1 : 3;
    struct vts_error err;
    struct vt_png_file_writer *pw = vt_png_file_writer_create(path, w, h, ch, 8, &err);
    unsigned char *row = malloc((size_t)w * 3);
    const unsigned n = 512;
    int st = pw && row ? 0 : -1;
    for (unsigned j = 0; st == 0 && j < h; j++) {
        for (unsigned i = 0; i < w; i++) {
            unsigned char *p = row + (size_t)i * ch;
            double x = i + 0.5, y = j + 0.5;
            if (kind == 'd') {
                double z = height(n, x, y, seed) + 0.15 * noise(i, j, seed);
                p[0] = u8(0.5 + 0.35 * z + 0.1 * sin(seed));
                p[1] = u8(0.45 + 0.3 * height(n, y, x, seed + 1));
                p[2] = u8(0.4 - 0.3 * z);
            } else if (kind == 'n') {
                double e = 1.0, s = 3.0;
                double dx = (height(n, x + e, y, seed) - height(n, x - e, y, seed)) * s;
                double dy = (height(n, x, y + e, seed) - height(n, x, y - e, seed)) * s;
                double l = sqrt(dx * dx + dy * dy + 1);
                p[0] = u8(-dx / l * 0.5 + 0.5);
                p[1] = u8(dy / l * 0.5 + 0.5);
                p[2] = u8(1 / l * 0.5 + 0.5);
            } else if (kind == 's') {
                bool on = (i * 16 / n) % 2;
                p[0] = p[1] = p[2] = on ? 230 : 20;
            } else {
                unsigned c = n / 8;
                p[0] = (i % c < c / 3 || j % c < c / 3) ? 255 : 0;
            }
        }
        st = vt_png_file_writer_rows(pw, row, 1, 0, &err);
    }
    if (st == 0)
        st = vt_png_file_writer_finish(pw, &err);
    if (st != 0)
        fprintf(stderr, "gen_view_scene: %s: %s\n", path, pw ? err.message : "cannot create");
    vt_png_file_writer_destroy(pw);
    free(row);
    return st;
}

static unsigned vcount;

/* A quad with corners a, b, c, d (counter-clockwise seen from the front), UVs 0..1. */
static void quad(FILE *f, const char *mtl, const double q[4][3])
{
    static const int uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    fprintf(f, "usemtl %s\n", mtl);
    for (int k = 0; k < 4; k++)
        fprintf(f, "v %g %g %g\nvt %d %d\n", q[k][0], q[k][1], q[k][2], uv[k][0], uv[k][1]);
    fprintf(f, "f %u/%u %u/%u %u/%u %u/%u\n", vcount + 1, vcount + 1, vcount + 2, vcount + 2,
            vcount + 3, vcount + 3, vcount + 4, vcount + 4);
    vcount += 4;
}

int main(int argc, char **argv)
{
    static const char *const features[] = {"plain",  "alpha_test", "blend",
                                           "normal", "specular",   "all"};
    int feat = -1;
    for (int k = 0; argc == 3 && k < 6; k++)
        if (!strcmp(argv[2], features[k]))
            feat = k;
    if (feat < 0) {
        fprintf(stderr, "usage: gen_view_scene OUTDIR "
                        "plain|alpha_test|blend|normal|specular|all\n");
        return 2;
    }
    const char *dir = argv[1];
    bool alpha = feat == 1 || feat == 5, blend = feat == 2 || feat == 5;
    bool normal = feat == 3 || feat == 5, spec = feat == 4 || feat == 5;
    static const struct {
        const char *name;
        unsigned w, h;
        double q[4][3];
    } surf[] = {
        {"floor", 512, 2560, {{-1, 0, 2}, {1, 0, 2}, {1, 0, -8}, {-1, 0, -8}}},
        {"left", 2560, 512, {{-1, 0, -8}, {-1, 0, 2}, {-1, 2, 2}, {-1, 2, -8}}},
        {"right", 2560, 512, {{1, 0, 2}, {1, 0, -8}, {1, 2, -8}, {1, 2, 2}}},
        {"back", 512, 512, {{-1, 0, -8}, {1, 0, -8}, {1, 2, -8}, {-1, 2, -8}}},
        {"panel1", 512, 512, {{-1, 0, -1}, {0.2, 0, -1}, {0.2, 1.5, -1}, {-1, 1.5, -1}}},
        {"panel2", 512, 512, {{-0.2, 0, -3}, {1, 0, -3}, {1, 1.5, -3}, {-0.2, 1.5, -3}}},
        {"panel3", 512, 512, {{-0.6, 0.3, -5}, {0.6, 0.3, -5}, {0.6, 1.8, -5}, {-0.6, 1.8, -5}}},
    };
    char path[4096];
    snprintf(path, sizeof path, "%s/scene.mtl", dir);
    FILE *mtl = fopen(path, "w");
    snprintf(path, sizeof path, "%s/scene.obj", dir);
    FILE *obj = fopen(path, "w");
    if (!mtl || !obj) {
        fprintf(stderr, "gen_view_scene: cannot write in '%s'\n", dir);
        return 1;
    }
    fprintf(obj, "# generated by gen_view_scene (%s)\nmtllib scene.mtl\no corridor\n",
            features[feat]);
    vcount = 0;
    for (unsigned s = 0; s < sizeof surf / sizeof surf[0]; s++) {
        char name[64];
        const char *sn = surf[s].name;
        unsigned w = surf[s].w, h = surf[s].h;
        snprintf(name, sizeof name, "%s", sn);
        if (write_texture(dir, name, w, h, 'd', s) != 0)
            return 1;
        fprintf(mtl, "newmtl %s\nKd 1 1 1\nillum %d\nmap_Kd tex/%s.png\n", sn, spec ? 2 : 1, sn);
        if (alpha) {
            snprintf(name, sizeof name, "%s_d", sn);
            if (write_texture(dir, name, w, h, 'a', s) != 0)
                return 1;
            fprintf(mtl, "map_d tex/%s.png\n", name);
        }
        if (blend)
            fprintf(mtl, "d 0.6\n");
        if (normal) {
            snprintf(name, sizeof name, "%s_n", sn);
            if (write_texture(dir, name, w, h, 'n', s) != 0)
                return 1;
            fprintf(mtl, "norm tex/%s.png\n", name);
        }
        if (spec) {
            snprintf(name, sizeof name, "%s_s", sn);
            if (write_texture(dir, name, w, h, 's', s) != 0)
                return 1;
            fprintf(mtl, "Ks 1 1 1\nNs 16\nmap_Ks tex/%s.png\n", name);
        }
        fputc('\n', mtl);
        quad(obj, sn, surf[s].q);
    }
    if (fclose(mtl) != 0 || fclose(obj) != 0) {
        fprintf(stderr, "gen_view_scene: cannot write in '%s'\n", dir);
        return 1;
    }
    return 0;
}
