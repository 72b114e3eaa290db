/* End to end with shared entries: materials that use the same texture share one atlas cell (one
 * entry with aliases) and still read their own texels. Two textures with a unique pattern per
 * texel; m_a and m_b use s.png (m_b through another path to it, with UVs in [1, 3]: its charts
 * are moved to [0, 2], so the shared entry replicates the texture over the union [0, 2]), m_c and
 * m_d use t.png; one vt is used by
 * faces of both m_a and m_b. vt-atlas -> vt-offset -> vt-tiles --layout (png tiles) -> vt-info
 * --extract 0: every face corner of every material must land in its entry's cell, on a texel
 * centre, and read the original texel exactly.
 *
 * usage: test_atlas_shared WORK_DIR VT_ATLAS VT_OFFSET VT_TILES VT_INFO */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_layout.h"
#include "vt_png_file.h"
#include "vt_test.h"
#include "vt_test_corners.h"

struct tex {
    const char *file;
    uint32_t w, h;
};
static const struct tex texs[2] = {{"tex/s.png", 64, 48}, {"tex/t.png", 40, 40}};

struct mat {
    const char *name, *map; /* map_Kd as written in the MTL */
    uint32_t tex;
    int u_from, u_copies; /* corners in copies u_from .. u_from + u_copies - 1 */
};
static const struct mat mats[4] = {{"m_a", "tex/s.png", 0, 0, 1},
                                   {"m_b", "./tex/../tex/s.png", 0, 1, 2},
                                   {"m_c", "tex/t.png", 1, 0, 1},
                                   {"m_d", "tex/t.png", 1, 0, 1}};
#define MAT_COUNT 4

static const char *work;

static const char *path(const char *name)
{
    static char buf[4][1024];
    static int k;
    k = (k + 1) % 4;
    snprintf(buf[k], sizeof buf[k], "%s/%s", work, name);
    return buf[k];
}

static uint8_t pattern(uint32_t t, uint32_t i, uint32_t j, uint32_t c)
{
    uint32_t v = c == 0 ? i * 3 + t * 101 : c == 1 ? j * 5 + t * 37 : (i ^ j) * 7 + t * 59;
    return (uint8_t)(v & 255);
}

static void write_texture(uint32_t t)
{
    const struct tex *x = &texs[t];
    struct vts_error err;
    struct vt_png_file_writer *w = vt_png_file_writer_create(path(x->file), x->w, x->h, 3, 8, &err);
    VT_CHECK(w != NULL);
    uint8_t *row = malloc((size_t)x->w * 3);
    for (uint32_t j = 0; w && j < x->h; j++) {
        for (uint32_t i = 0; i < x->w; i++)
            for (uint32_t c = 0; c < 3; c++)
                row[i * 3 + c] = pattern(t, i, j, c);
        VT_CHECK_INT_EQ(vt_png_file_writer_rows(w, row, 1, 0, &err), 0);
    }
    VT_CHECK_INT_EQ(vt_png_file_writer_finish(w, &err), 0);
    vt_png_file_writer_destroy(w);
    free(row);
}

static uint32_t rnd_state = 4242;
static uint32_t rnd(uint32_t n)
{
    rnd_state = rnd_state * 1103515245u + 12345u;
    return (rnd_state >> 8) % n;
}

static void write_scene(void)
{
    FILE *mtl = fopen(path("scene.mtl"), "w");
    for (uint32_t m = 0; m < MAT_COUNT; m++)
        fprintf(mtl, "newmtl %s\nmap_Kd %s\n\n", mats[m].name, mats[m].map);
    fclose(mtl);
    FILE *obj = fopen(path("scene.obj"), "w");
    fprintf(obj, "mtllib scene.mtl\n");
    uint32_t n = 0;
    for (uint32_t m = 0; m < MAT_COUNT; m++) {
        const struct tex *x = &texs[mats[m].tex];
        fprintf(obj, "usemtl %s\n", mats[m].name);
        for (int f = 0; f < 30; f++) {
            for (int c = 0; c < 3; c++) {
                double u = mats[m].u_from + (int)rnd((uint32_t)mats[m].u_copies) +
                           (rnd(x->w) + 0.5) / x->w;
                double v = 1 - (rnd(x->h) + 0.5) / x->h;
                fprintf(obj, "v %d %d 0\nvt %.17g %.17g\n", (int)rnd(50), (int)rnd(50), u, v);
            }
            n += 3;
            fprintf(obj, "f %u/%u %u/%u %u/%u\n", n - 2, n - 2, n - 1, n - 1, n, n);
        }
    }
    /* One vt (a texel centre of s.png) used by a face of m_a and a face of m_b. */
    fprintf(obj, "v 0 0 0\nvt %.17g %.17g\n", 10.5 / 64, 1 - 20.5 / 48);
    n++;
    fprintf(obj, "usemtl m_a\nf %u/%u 1/%u 2/%u\n", n, n, n, n);
    fprintf(obj, "usemtl m_b\nf %u/%u 2/%u 3/%u\n", n, n, n, n);
    fclose(obj);
}

/* The layout: two entries, each shared by two materials, each found by both names. */
static void check_layout(struct vt_layout *l)
{
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_layout_read(path("atlas.json"), NULL, l, &err), 0);
    VT_CHECK_INT_EQ(l->entry_count, 2);
    if (l->entry_count != 2)
        return;
    const struct vt_layout_entry *a = &l->entries[0], *c = &l->entries[1];
    VT_CHECK(strcmp(a->name, "m_a") == 0 && a->alias_count == 1 &&
             strcmp(a->aliases[0], "m_b") == 0);
    VT_CHECK(strcmp(c->name, "m_c") == 0 && c->alias_count == 1 &&
             strcmp(c->aliases[0], "m_d") == 0);
    VT_CHECK(vt_layout_find(l, "m_b") == a && vt_layout_find(l, "m_d") == c);
    /* the union of m_a's [0, 1] and m_b's [1, 3] along u, m_b's charts moved down one repeat
     * to [0, 2] (docs/real-scenes.md): two copies */
    VT_CHECK(a->origin_u == 0 && a->repeat_u == 2 && a->repeat_v == 1);
    /* m_c and m_d hold the whole of t.png in one copy: it wraps as the texture repeats */
    VT_CHECK(!a->wrap && c->wrap);
    VT_CHECK(c->origin_u == 0 && c->repeat_u == 1 && c->repeat_v == 1);
}

int main(int argc, char **argv)
{
    if (argc != 6) {
        fprintf(stderr, "usage: test_atlas_shared WORK_DIR VT_ATLAS VT_OFFSET VT_TILES VT_INFO\n");
        return 2;
    }
    work = argv[1];
    char cmd[8192];
    snprintf(cmd, sizeof cmd, "rm -rf '%s' && mkdir -p '%s/tex'", work, work);
    VT_CHECK(vt_test_run(cmd) == 0);
    for (uint32_t t = 0; t < 2; t++)
        write_texture(t);
    write_scene();
    snprintf(
        cmd, sizeof cmd,
        "cd '%s' && '%s' scene.obj -o atlas.json --wrap replicate && '%s' scene.obj atlas.json -o scene.vt.obj -q && '%s' --layout atlas.json -o scene.vts --codec png -q && '%s' --extract 0 -o level0.png scene.vts",
        work, argv[2], argv[3], argv[4], argv[5]);
    VT_CHECK(vt_test_run(cmd) == 0);
    struct vt_layout l = {0};
    check_layout(&l);

    const char *names[MAT_COUNT];
    for (int m = 0; m < MAT_COUNT; m++)
        names[m] = mats[m].name;
    struct vt_test_corners a, b;
    struct vts_error rerr;
    VT_CHECK_INT_EQ(vt_test_corners_read(path("scene.obj"), names, MAT_COUNT, &a, &rerr), 0);
    VT_CHECK_INT_EQ(vt_test_corners_read(path("scene.vt.obj"), NULL, 0, &b, &rerr), 0);
    VT_CHECK_INT_EQ(a.count, 3 * 30 * MAT_COUNT + 6);
    VT_CHECK_INT_EQ(b.count, a.count);
    struct vt_image atlas = {0};
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_png_file_read(path("level0.png"), &atlas, &err), 0);
    uint32_t equal = 0, in_cell = 0, per_mat[MAT_COUNT] = {0};
    for (uint32_t k = 0; k < a.count && k < b.count && atlas.pixels && l.entry_count == 2; k++) {
        int m = a.material[k];
        VT_CHECK(m >= 0);
        if (m < 0)
            continue;
        const struct tex *x = &texs[mats[m].tex];
        const struct vt_layout_entry *e = vt_layout_find(&l, mats[m].name);
        double u = a.uv[2 * k], v = a.uv[2 * k + 1];
        uint32_t i = (uint32_t)((u - floor(u)) * x->w), j = (uint32_t)((1 - (v - floor(v))) * x->h);
        double px = b.uv[2 * k] * atlas.width, py = (1 - b.uv[2 * k + 1]) * atlas.height;
        VT_CHECK(fabs(px - floor(px) - 0.5) < 1e-3 && fabs(py - floor(py) - 0.5) < 1e-3);
        bool inside = e && px >= e->x && px < (double)e->x + e->cell_width && py >= e->y &&
                      py < (double)e->y + e->cell_height;
        in_cell += inside;
        if (!inside || px >= atlas.width || py >= atlas.height)
            continue;
        const uint8_t *p = vt_image_at(&atlas, (uint32_t)px, (uint32_t)py);
        bool same = true;
        for (uint32_t c = 0; c < 3; c++)
            same &= p[c] == pattern(mats[m].tex, i, j, c);
        equal += same;
        per_mat[m] += same;
        if (!same)
            fprintf(stderr, "corner %u of %s: texel (%u,%u) -> atlas (%u,%u) differs\n", k,
                    mats[m].name, i, j, (uint32_t)px, (uint32_t)py);
    }
    fprintf(stderr, "%u of %u corners in their cell, %u equal (m_a %u, m_b %u, m_c %u, m_d %u)\n",
            in_cell, a.count, equal, per_mat[0], per_mat[1], per_mat[2], per_mat[3]);
    VT_CHECK_INT_EQ(in_cell, a.count);
    VT_CHECK_INT_EQ(equal, a.count);
    VT_CHECK(per_mat[0] == 93 && per_mat[1] == 93 && per_mat[2] == 90 && per_mat[3] == 90);
    vt_image_release(&atlas);
    vt_layout_release(&l);
    vt_test_corners_release(&a);
    vt_test_corners_release(&b);
    return vt_test_main_result();
}
