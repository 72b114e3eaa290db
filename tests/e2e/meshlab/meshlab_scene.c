/* Test scene and checker for scripts/mesh-clean (tests/e2e/meshlab/run.sh).
 *
 *   test_meshlab_scene gen DIR
 *       Writes DIR/scene.obj, DIR/scene.mtl and DIR/tex/{a,b,c}.png (placeholders: nothing reads
 *       the pixels): three boxes whose faces share no vertex (24 vertices per box, 8 after
 *       merging), every face a quad with its own UV rectangle, four materials (matA, matB, matC
 *       and matA2 sharing tex/a.png with another Kd), one pentagon (fanned by mesh-clean).
 *   test_meshlab_scene same ORIG.obj CLEAN.obj
 *       The no-simplify result: vertices EXPECTED_CLEAN_VERTICES (fewer than before), the same
 *       triangles in order (ORIG polygons fanned), each with the same material name, the same
 *       map_Kd file (resolved paths) and the same (position, uv) corner set within 1e-6.
 *   test_meshlab_scene simplified ORIG.obj CLEAN.obj
 *       The --simplify result: fewer faces, every face has a material of ORIG with the same texture
 *       and a texture coordinate on every corner. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "vt_error.h"
#include "vt_obj.h"
#include "vt_test.h"

#define BOXES                   3
#define PENTAGON_VERTICES       5
#define ORIG_VERTICES           (BOXES * 24 + PENTAGON_VERTICES)
#define EXPECTED_CLEAN_VERTICES (BOXES * 8 + PENTAGON_VERTICES)
#define ORIG_TRIANGLES          (BOXES * 12 + 3)
#define TOL                     1e-6

static int write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f || fputs(text, f) < 0 || fclose(f)) {
        fprintf(stderr, "cannot write %s: %s\n", path, strerror(errno));
        return 1;
    }
    return 0;
}

static int generate(const char *dir)
{
    char path[4096];
    snprintf(path, sizeof(path), "%s/tex", dir);
    if (mkdir(dir, 0777) && errno != EEXIST)
        return 1;
    if (mkdir(path, 0777) && errno != EEXIST)
        return 1;
    const char *texs[] = {"a", "b", "c"};
    for (int i = 0; i < 3; i++) {
        snprintf(path, sizeof(path), "%s/tex/%s.png", dir, texs[i]);
        if (write_text(path, "placeholder\n"))
            return 1;
    }
    snprintf(path, sizeof(path), "%s/scene.mtl", dir);
    if (write_text(path, "newmtl matA\nKd 0.8 0.7 0.6\nmap_Kd tex/a.png\n\n"
                         "newmtl matB\nKd 1 1 1\nmap_Kd -clamp on tex/b.png\n\n"
                         "newmtl matC\nKd 0.5 0.5 0.5\nmap_Kd tex/c.png\n\n"
                         "newmtl matA2\nKd 0.2 0.3 0.4\nmap_Kd tex/a.png\n"))
        return 1;
    snprintf(path, sizeof(path), "%s/scene.obj", dir);
    FILE *f = fopen(path, "w");
    if (!f)
        return 1;
    fprintf(f, "# mesh-clean test scene: boxes without shared vertices\nmtllib scene.mtl\n");
    /* unit cube corners; each face lists 4 of them counter-clockwise seen from outside */
    static const int cube[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                   {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    static const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                    {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
    static const char *box_mat[BOXES][2] = {{"matA", "matB"}, {"matC", "matA2"}, {"matB", "matC"}};
    int v = 0, vt = 0;
    for (int b = 0; b < BOXES; b++) {
        /* sizes and offsets with many decimals: float32 + "%f" must still be within 1e-6 */
        double size = 0.7312345 + 0.1318731 * b, ox = 1.9876543 * b, oy = 0.3141592 * b,
               oz = -0.2718281 * b;
        fprintf(f, "o box%d\n", b);
        for (int q = 0; q < 6; q++) {
            for (int k = 0; k < 4; k++) {
                const int *c = cube[faces[q][k]];
                fprintf(f, "v %.7f %.7f %.7f\n", ox + size * c[0], oy + size * c[1],
                        oz + size * c[2]);
            }
            /* a UV rectangle per face, cells of a 6x3 grid with a small inset */
            double u0 = (q + 0.0123457) / 6.0, u1 = (q + 0.9876543) / 6.0;
            double v0 = (b + 0.0234567) / 3.0, v1 = (b + 0.9765432) / 3.0;
            fprintf(f, "vt %.7f %.7f\nvt %.7f %.7f\nvt %.7f %.7f\nvt %.7f %.7f\n", u0, v0, u1, v0,
                    u1, v1, u0, v1);
            fprintf(f, "usemtl %s\n", box_mat[b][q % 2]);
            fprintf(f, "f %d/%d %d/%d %d/%d %d/%d\n", v + 1, vt + 1, v + 2, vt + 2, v + 3, vt + 3,
                    v + 4, vt + 4);
            v += 4;
            vt += 4;
        }
    }
    /* a pentagon with negative (relative) indices */
    fprintf(f, "o pentagon\nusemtl matA\n");
    for (int k = 0; k < PENTAGON_VERTICES; k++) {
        double a = 2 * 3.14159265358979 * k / PENTAGON_VERTICES;
        fprintf(f, "v %.7f %.7f 3.25\nvt %.7f %.7f\n", 5 + cos(a), -1 + sin(a), 0.5 + 0.4 * cos(a),
                0.5 + 0.4 * sin(a));
    }
    fprintf(f, "f -5/-5 -4/-4 -3/-3 -2/-2 -1/-1\n");
    if (fclose(f))
        return 1;
    return 0;
}

struct tri {
    uint32_t v[3], vt[3];
    char material[64];
};

struct scene {
    struct vt_obj *obj;
    struct tri tris[1024];
    size_t tri_count;
    char mtllib[4096];
    struct vt_mtl mtl;
};

static int on_face(void *user, const struct vt_obj *obj, const struct vt_obj_face *face,
                   struct vts_error *err)
{
    (void)obj;
    struct scene *s = user;
    for (uint32_t i = 1; i + 1 < face->corner_count; i++) {
        if (s->tri_count == sizeof(s->tris) / sizeof(s->tris[0]))
            return vt_error_set(err, VTS_ERR_LIMIT, "too many faces");
        struct tri *t = &s->tris[s->tri_count++];
        uint32_t idx[3] = {0, i, i + 1};
        for (int k = 0; k < 3; k++) {
            t->v[k] = face->corners[idx[k]].v;
            t->vt[k] = face->corners[idx[k]].vt;
        }
        snprintf(t->material, sizeof(t->material), "%s", face->material);
    }
    return 0;
}

static int on_mtllib(void *user, const struct vt_obj *obj, const char *path, uint64_t line,
                     struct vts_error *err)
{
    (void)obj;
    (void)line;
    (void)err;
    struct scene *s = user;
    snprintf(s->mtllib, sizeof(s->mtllib), "%s", path);
    return 0;
}

static bool load(struct scene *s, const char *path)
{
    memset(s, 0, sizeof(*s));
    struct vts_error err = {0};
    s->obj = vt_obj_create(NULL, &err);
    struct vt_obj_callbacks cb = {.mtllib = on_mtllib, .face = on_face, .user = s};
    if (!s->obj || vt_obj_read(s->obj, path, &cb, &err) || !s->mtllib[0] ||
        vt_mtl_read(s->mtllib, NULL, &s->mtl, &err)) {
        fprintf(stderr, "%s: %s (mtllib '%s')\n", path, err.message, s->mtllib);
        return false;
    }
    return true;
}

static void unload(struct scene *s)
{
    vt_obj_destroy(s->obj);
    vt_mtl_release(&s->mtl);
}

/* The real path of the map_Kd of material name in s, or "" (static buffer per slot). */
static const char *texture_of(const struct scene *s, const char *name, char buf[4096])
{
    const struct vt_mtl_material *m = vt_mtl_find(&s->mtl, name);
    buf[0] = '\0';
    if (m && m->maps[VT_MTL_MAP_KD].path) {
        char *r = realpath(m->maps[VT_MTL_MAP_KD].path, NULL);
        snprintf(buf, 4096, "%s", r ? r : "(missing)");
        free(r);
    }
    return buf;
}

static void get_corner(const struct scene *s, const struct tri *t, int k, double c[5])
{
    const double *p = vt_obj_positions(s->obj) + 3 * (size_t)t->v[k];
    memcpy(c, p, 3 * sizeof(double));
    c[3] = c[4] = -1;
    if (t->vt[k] != VT_OBJ_NONE) {
        const double *uv = vt_obj_texcoords(s->obj) + 3 * (size_t)t->vt[k];
        c[3] = uv[0];
        c[4] = uv[1];
    }
}

static void check(const char *mode, const char *orig_path, const char *clean_path)
{
    struct scene *a = calloc(1, sizeof(*a)), *b = calloc(1, sizeof(*b));
    VT_CHECK(a && b);
    if (!a || !b || !load(a, orig_path) || !load(b, clean_path)) {
        VT_CHECK(!"scenes load");
        goto done;
    }
    bool same = !strcmp(mode, "same");
    uint32_t va = vt_obj_position_count(a->obj), vb = vt_obj_position_count(b->obj);
    fprintf(stderr, "vertices %u -> %u, triangles %zu -> %zu\n", va, vb, a->tri_count,
            b->tri_count);
    VT_CHECK_INT_EQ(va, ORIG_VERTICES);
    VT_CHECK_INT_EQ(a->tri_count, ORIG_TRIANGLES);
    VT_CHECK(vb < va);
    if (same) {
        VT_CHECK_INT_EQ(vb, EXPECTED_CLEAN_VERTICES);
        VT_CHECK_INT_EQ(b->tri_count, a->tri_count);
    } else {
        VT_CHECK(b->tri_count < a->tri_count);
    }
    /* the cleaned scene uses the original MTL itself */
    char ra[4096], rb[4096];
    char *pa = realpath(a->mtllib, NULL), *pb = realpath(b->mtllib, NULL);
    VT_CHECK(pa && pb && !strcmp(pa, pb));
    free(pa);
    free(pb);
    size_t n = a->tri_count < b->tri_count ? a->tri_count : b->tri_count;
    int bad_faces = 0;
    for (size_t i = 0; i < b->tri_count; i++) {
        const struct tri *y = &b->tris[i];
        const char *tb = texture_of(b, y->material, rb);
        bool known = false;
        for (size_t j = 0; j < a->tri_count && !known; j++)
            known = !strcmp(a->tris[j].material, y->material) &&
                    !strcmp(texture_of(a, a->tris[j].material, ra), tb);
        VT_CHECK(known);
        VT_CHECK(tb[0] && strcmp(tb, "(missing)"));
        for (int k = 0; k < 3; k++)
            VT_CHECK(y->vt[k] != VT_OBJ_NONE);
        if (!same || i >= n)
            continue;
        const struct tri *x = &a->tris[i];
        bool ok = !strcmp(x->material, y->material) &&
                  !strcmp(texture_of(a, x->material, ra), texture_of(b, y->material, rb));
        bool used[3] = {false, false, false};
        for (int k = 0; k < 3 && ok; k++) {
            double ca[5], cb[5];
            get_corner(a, x, k, ca);
            bool found = false;
            for (int j = 0; j < 3 && !found; j++) {
                if (used[j])
                    continue;
                get_corner(b, y, j, cb);
                bool close = true;
                for (int c = 0; c < 5; c++)
                    close = close && fabs(ca[c] - cb[c]) <= TOL;
                if (close)
                    found = used[j] = true;
            }
            ok = found;
        }
        if (!ok && bad_faces++ < 5)
            fprintf(stderr, "triangle %zu differs (material %s / %s)\n", i, x->material,
                    y->material);
    }
    VT_CHECK_INT_EQ(bad_faces, 0);
done:
    if (a)
        unload(a);
    if (b)
        unload(b);
    free(a);
    free(b);
}

int main(int argc, char **argv)
{
    if (argc == 3 && !strcmp(argv[1], "gen"))
        return generate(argv[2]);
    if (argc == 4 && (!strcmp(argv[1], "same") || !strcmp(argv[1], "simplified"))) {
        check(argv[1], argv[2], argv[3]);
        return vt_test_main_result();
    }
    fprintf(stderr, "usage: test_meshlab_scene gen DIR | same|simplified ORIG.obj CLEAN.obj\n");
    return 2;
}
