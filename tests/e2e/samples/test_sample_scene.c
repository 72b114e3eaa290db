/* Checks the sample scene written by vt-sample-scene (samples/gen_scene.c): the OBJ and MTL parse
 * with lib/obj/vt_obj.h, 40+ textures of the promised sizes exist and load, alpha/normal/tiling
 * materials are what they claim, and the UV ranges are [0,1] except on the tiling ground (0..8).
 * Usage: test_sample_scene DIR (the generator's output directory). */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_image.h"
#include "vt_obj.h"
#include "vt_png_file.h"
#include "vt_test.h"

static const char *dir;

struct uv_range {
    char name[64];
    double umin, umax, vmin, vmax;
    unsigned faces;
};

struct scan {
    struct uv_range ranges[64];
    unsigned range_count;
    unsigned faces, quads, triangles, objects;
    char last_object[64];
    unsigned mtllibs;
};

static struct uv_range *range_for(struct scan *s, const char *name)
{
    for (unsigned i = 0; i < s->range_count; i++)
        if (strcmp(s->ranges[i].name, name) == 0)
            return &s->ranges[i];
    if (s->range_count == 64)
        return NULL;
    struct uv_range *r = &s->ranges[s->range_count++];
    snprintf(r->name, sizeof(r->name), "%s", name);
    r->umin = r->vmin = 1e30;
    r->umax = r->vmax = -1e30;
    return r;
}

static int on_mtllib(void *user, const struct vt_obj *obj, const char *path, uint64_t line,
                     struct vts_error *err)
{
    (void)obj, (void)line, (void)err;
    struct scan *s = user;
    s->mtllibs++;
    VT_CHECK_STR_CONTAINS(path, "scene.mtl");
    return 0;
}

static int on_face(void *user, const struct vt_obj *obj, const struct vt_obj_face *f,
                   struct vts_error *err)
{
    (void)err;
    struct scan *s = user;
    s->faces++;
    s->quads += f->corner_count == 4;
    s->triangles += f->corner_count == 3;
    if (strcmp(f->object, s->last_object) != 0) {
        s->objects++;
        snprintf(s->last_object, sizeof(s->last_object), "%s", f->object);
    }
    struct uv_range *r = range_for(s, f->material);
    if (!r)
        return -1;
    r->faces++;
    const double *vt = vt_obj_texcoords(obj);
    for (uint32_t i = 0; i < f->corner_count; i++) {
        VT_CHECK(f->corners[i].vt != VT_OBJ_NONE);
        VT_CHECK(f->corners[i].vn != VT_OBJ_NONE);
        if (f->corners[i].vt == VT_OBJ_NONE)
            continue;
        double u = vt[3 * f->corners[i].vt], v = vt[3 * f->corners[i].vt + 1];
        r->umin = fmin(r->umin, u);
        r->umax = fmax(r->umax, u);
        r->vmin = fmin(r->vmin, v);
        r->vmax = fmax(r->vmax, v);
    }
    return 0;
}

static char *slurp(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)n + 1);
    if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
        free(buf);
        buf = NULL;
    }
    if (buf)
        buf[n] = 0;
    fclose(f);
    *size = (size_t)n;
    return buf;
}

static bool is_pow2(uint32_t x)
{
    return x && !(x & (x - 1));
}

static void test_scene(void)
{
    char obj_path[4096], mtl_path[4096];
    snprintf(obj_path, sizeof(obj_path), "%s/scene.obj", dir);
    snprintf(mtl_path, sizeof(mtl_path), "%s/scene.mtl", dir);

    struct vts_error err = {0};
    struct vt_mtl mtl = {0};
    VT_CHECK_INT_EQ(vt_mtl_read(mtl_path, NULL, &mtl, &err), 0);
    if (err.status)
        fprintf(stderr, "%s\n", err.message);

    struct scan s = {0};
    struct vt_obj *obj = vt_obj_create(NULL, &err);
    struct vt_obj_callbacks cb = {on_mtllib, NULL, on_face, &s};
    VT_CHECK_INT_EQ(vt_obj_read(obj, obj_path, &cb, &err), 0);
    if (err.status)
        fprintf(stderr, "%s\n", err.message);
    struct vt_obj_stats st;
    vt_obj_stats(obj, &st);
    VT_CHECK_INT_EQ(st.unknown_statements, 0);
    VT_CHECK_INT_EQ(s.mtllibs, 1);
    VT_CHECK(s.objects >= 40);
    VT_CHECK(s.quads > 100);
    VT_CHECK(s.triangles > 0);
    fprintf(stderr, "%u objects, %u faces (%u quads, %u triangles), %u materials used\n", s.objects,
            s.faces, s.quads, s.triangles, s.range_count);

    /* Every material used is defined; only the ground leaves [0,1], and it spans 0..8. */
    for (unsigned i = 0; i < s.range_count; i++) {
        const struct uv_range *r = &s.ranges[i];
        VT_CHECK(vt_mtl_find(&mtl, r->name) != NULL);
        if (strcmp(r->name, "ground") == 0) {
            VT_CHECK(r->umin == 0 && r->vmin == 0 && r->umax == 8 && r->vmax == 8);
        } else {
            VT_CHECK(r->umin >= 0 && r->vmin >= 0 && r->umax <= 1 && r->vmax <= 1);
        }
    }
    VT_CHECK(range_for(&s, "ground")->faces == 4);

    /* Textures: every map file loads; 40+ distinct files; the promised sizes; one shared file. */
    static const uint32_t wanted[][2] = {{1024, 1024}, {512, 256}, {300, 200},
                                         {100, 60},    {64, 64},   {2000, 1000}};
    bool found[6] = {0};
    char seen[64][4096];
    unsigned distinct = 0, shared = 0, npot = 0, rgba = 0, normals = 0, masks = 0;
    for (size_t m = 0; m < mtl.material_count; m++) {
        const struct vt_mtl_material *mat = &mtl.materials[m];
        for (int k = 0; k < VT_MTL_MAP_COUNT; k++) {
            const struct vt_mtl_map *map = &mat->maps[k];
            if (!map->path)
                continue;
            bool dup = false;
            for (unsigned j = 0; j < distinct; j++)
                dup |= strcmp(seen[j], map->path) == 0;
            if (dup) {
                shared++;
                continue;
            }
            if (distinct < 64)
                snprintf(seen[distinct++], sizeof(seen[0]), "%s", map->path);
            struct vt_image im = {0};
            int rc = vt_png_file_read(map->path, &im, &err);
            VT_CHECK_INT_EQ(rc, 0);
            if (rc < 0) {
                fprintf(stderr, "%s\n", err.message);
                continue;
            }
            for (int w = 0; w < 6; w++)
                found[w] |= im.width == wanted[w][0] && im.height == wanted[w][1];
            npot += !is_pow2(im.width) || !is_pow2(im.height);
            if (k == VT_MTL_MAP_KD && im.channels == 4) {
                rgba++;
                /* a cut-out: the corner is transparent, the centre (label box) opaque */
                const uint8_t *p = im.pixels;
                VT_CHECK_INT_EQ(p[3], 0);
                const uint8_t *c = p + (size_t)(im.height / 2) * im.stride + (im.width / 2) * 4;
                VT_CHECK_INT_EQ(c[3], 255);
            }
            if (k == VT_MTL_MAP_D) {
                masks++;
                VT_CHECK_INT_EQ(im.channels, 1);
            }
            if (k == VT_MTL_MAP_NORM) {
                normals++;
                VT_CHECK_INT_EQ(im.channels, 3);
                /* every texel decodes to a unit vector facing out (z > 0) */
                double worst = 0;
                unsigned facing_in = 0;
                for (uint32_t y = 0; y < im.height; y++)
                    for (uint32_t x = 0; x < im.width; x++) {
                        const uint8_t *p = (const uint8_t *)im.pixels + y * im.stride + 3 * x;
                        double nx = p[0] / 127.5 - 1, ny = p[1] / 127.5 - 1, nz = p[2] / 127.5 - 1;
                        worst = fmax(worst, fabs(sqrt(nx * nx + ny * ny + nz * nz) - 1));
                        facing_in += nz <= 0;
                    }
                VT_CHECK_INT_EQ(facing_in, 0);
                VT_CHECK(worst < 0.02);
            }
            if (k == VT_MTL_MAP_KD && strstr(map->path, "t02.png")) {
                /* the label: dark box with white ink in the middle */
                unsigned white = 0, dark = 0;
                for (uint32_t y = im.height / 3; y < 2 * im.height / 3; y++)
                    for (uint32_t x = im.width / 4; x < 3 * im.width / 4; x++) {
                        const uint8_t *p =
                            (const uint8_t *)im.pixels + y * im.stride + x * im.channels;
                        white += p[0] == 255 && p[1] == 255 && p[2] == 255;
                        dark += p[0] == 20 && p[1] == 20 && p[2] == 20;
                    }
                VT_CHECK(white > 200 && dark > 200);
            }
            vt_image_release(&im);
        }
    }
    fprintf(stderr, "%u texture files, %u non-power-of-two, %u RGBA, %u shared\n", distinct, npot,
            rgba, shared);
    VT_CHECK(distinct >= 40);
    for (int w = 0; w < 6; w++)
        VT_CHECK(found[w]);
    VT_CHECK(npot >= 10);
    VT_CHECK(rgba >= 3);
    VT_CHECK_INT_EQ(normals, 1);
    VT_CHECK_INT_EQ(masks, 1);
    VT_CHECK_INT_EQ(shared, 1);
    const struct vt_mtl_material *kiosk = vt_mtl_find(&mtl, "kiosk");
    const struct vt_mtl_material *b10 = vt_mtl_find(&mtl, "bld_10");
    VT_CHECK(kiosk && b10 && strcmp(kiosk->maps[VT_MTL_MAP_KD].path, b10->maps[0].path) == 0);
    const struct vt_mtl_material *grey = vt_mtl_find(&mtl, "plain_grey");
    VT_CHECK(grey && !grey->maps[VT_MTL_MAP_KD].path && grey->kd[0] == 0.5);

    /* Text form: negative indices in the OBJ, CRLF line ends in the MTL. */
    size_t n;
    char *text = slurp(obj_path, &n);
    VT_CHECK(text && strstr(text, "\nf -"));
    free(text);
    text = slurp(mtl_path, &n);
    VT_CHECK(text && strstr(text, "\r\nnewmtl "));
    unsigned bare_lf = 0;
    for (size_t i = 0; text && i < n; i++)
        bare_lf += text[i] == '\n' && (i == 0 || text[i - 1] != '\r');
    VT_CHECK_INT_EQ(bare_lf, 0);
    free(text);

    vt_obj_destroy(obj);
    vt_mtl_release(&mtl);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: test_sample_scene DIR\n");
        return 2;
    }
    dir = argv[1];
    VT_RUN(test_scene);
    return vt_test_main_result();
}
