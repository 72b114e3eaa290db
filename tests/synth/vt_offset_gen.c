/* Inputs for vt-offset's tests and benchmark (built by tests/synth/CMakeLists.txt, not a test
 * itself):
 *
 *   vt-offset-gen layout OUT.json WIDTH HEIGHT NAME:X,Y,W,H[,RU,RV,OU,OV]...
 *       an atlas.json with one layer (diffuse, map_Kd) and one entry per argument with the
 *       texture NAME.png (a constant colour when NAME starts with "const"): rectangle X,Y,W,H in
 *       level-0 texels, optional repeats RU,RV and UV origin OU,OV
 *   vt-offset-gen bench DIR MB
 *       DIR/scene.obj of about MB megabytes (v, vt, vn and triangles of 8 materials, some vt
 *       shared between materials, a comment every block) and DIR/atlas.json (2^20 atlas)
 *   vt-offset-gen time SCENE.obj atlas.json [RUNS]
 *       runs the rewriter in this process into a sink that drops the text (no disk writes, no
 *       fsync) and prints the best of RUNS (default 3) in MB/s of input text
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "vt_layout.h"
#include "vt_offset.h"
#include "vts.h"

static int fail(const char *what)
{
    fprintf(stderr, "vt-offset-gen: %s\n", what);
    return 1;
}

/* Entries from "NAME:X,Y,W,H[,RU,RV,OU,OV]" arguments, written to path. */
static int write_layout(const char *path, uint32_t width, uint32_t height, int n, char **specs)
{
    struct vt_layout l;
    struct vts_error err = {0};
    if (vt_layout_alloc(&l, 1, (uint32_t)n, &err) < 0)
        return fail(err.message);
    l.width = width;
    l.height = height;
    l.tile_content = 256;
    l.border = 4;
    l.layers[0].name = strdup("diffuse");
    l.layers[0].map = strdup("map_Kd");
    l.layers[0].colour = VTS_COLOUR_SRGB;
    for (int i = 0; i < n; i++) {
        struct vt_layout_entry *e = &l.entries[i];
        char *colon = strchr(specs[i], ':');
        long v[8] = {0, 0, 1, 1, 1, 1, 0, 0};
        if (!colon) {
            vt_layout_release(&l);
            return fail("entry without ':'");
        }
        int got = sscanf(colon + 1, "%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld", &v[0], &v[1], &v[2], &v[3],
                         &v[4], &v[5], &v[6], &v[7]);
        if (got != 4 && got != 8) {
            vt_layout_release(&l);
            return fail("entry needs X,Y,W,H[,RU,RV,OU,OV]");
        }
        e->name = strndup(specs[i], (size_t)(colon - specs[i]));
        e->x = (uint32_t)v[0], e->y = (uint32_t)v[1];
        e->width = (uint32_t)v[2], e->height = (uint32_t)v[3];
        e->repeat_u = (uint32_t)v[4], e->repeat_v = (uint32_t)v[5];
        e->origin_u = (int32_t)v[6], e->origin_v = (int32_t)v[7];
        e->cell_width = e->width * e->repeat_u;
        e->cell_height = e->height * e->repeat_v;
        /* A texture named after the entry (never read by vt-offset); an entry whose name
         * starts with "const" is a material without textures (a constant cell). */
        if (strncmp(e->name, "const", 5) == 0) {
            e->textures[0].fill[0] = e->textures[0].fill[3] = 1;
        } else {
            char file[300];
            snprintf(file, sizeof file, "%s.png", e->name);
            e->textures[0].path = strdup(file);
            e->textures[0].width = e->width, e->textures[0].height = e->height;
        }
    }
    int rc = vt_layout_write(path, &l, &err);
    vt_layout_release(&l);
    return rc < 0 ? fail(err.message) : 0;
}

static uint64_t rng_state = 88172645463325252ULL;

static uint64_t rng(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return rng_state;
}

static double unit(void)
{
    return (double)(rng() >> 11) * (1.0 / 9007199254740992.0);
}

static int write_bench(const char *dir, double megabytes)
{
    char path[4096];
    char *specs[8];
    char spec_text[8][64];
    for (int i = 0; i < 8; i++) { /* 8 materials of 256K x 512K texels */
        snprintf(spec_text[i], sizeof spec_text[i], "mat%d:%d,%d,262144,524288", i,
                 (i % 4) * 262144, (i / 4) * 524288);
        specs[i] = spec_text[i];
    }
    snprintf(path, sizeof path, "%s/atlas.json", dir);
    if (write_layout(path, 1u << 20, 1u << 20, 8, specs) != 0)
        return 1;
    snprintf(path, sizeof path, "%s/scene.obj", dir);
    FILE *f = fopen(path, "wb");
    if (!f)
        return fail("cannot create scene.obj");
    fprintf(f, "# vt-offset benchmark scene\nmtllib scene.mtl\no bench\n");
    double target = megabytes * 1e6;
    long long bytes = 0, block = 0;
    while ((double)bytes < target) {
        /* a block: 300 v, 300 vt, 300 vn, 200 triangles of one material */
        long long base = block * 300;
        int n = 0;
        for (int i = 0; i < 300; i++)
            n += fprintf(f, "v %.6f %.6f %.6f\n", unit() * 100 - 50, unit() * 100 - 50,
                         unit() * 100 - 50);
        for (int i = 0; i < 300; i++)
            n += fprintf(f, "vt %.6f %.6f\n", unit(), unit());
        for (int i = 0; i < 300; i++)
            n += fprintf(f, "vn %.4f %.4f %.4f\n", unit() * 2 - 1, unit() * 2 - 1, unit() * 2 - 1);
        n += fprintf(f, "usemtl mat%lld\n# block %lld\n", block % 8, block);
        for (int i = 0; i < 200; i++) {
            long long a = base + (long long)(rng() % 300) + 1,
                      b = base + (long long)(rng() % 300) + 1,
                      c = base + (long long)(rng() % 300) + 1;
            n += fprintf(f, "f %lld/%lld/%lld %lld/%lld/%lld %lld/%lld/%lld\n", a, a, a, b, b, b, c,
                         c, c);
        }
        if (block > 0) { /* a few faces of another material sharing this block's vt */
            n += fprintf(f, "usemtl mat%lld\n", (block + 1) % 8);
            for (int i = 0; i < 4; i++)
                n += fprintf(f, "f -%d/-%d/-%d -%d/-%d/-%d -%d/-%d/-%d\n", i + 1, i + 1, i + 1,
                             i + 2, i + 2, i + 2, i + 3, i + 3, i + 3);
        }
        bytes += n;
        block++;
    }
    if (fclose(f) != 0)
        return fail("cannot write scene.obj");
    printf("%s: %lld bytes, %lld blocks\n", path, bytes, block);
    return 0;
}

static int drop(void *user, const void *data, size_t size, struct vts_error *err)
{
    (void)data, (void)err;
    *(unsigned long long *)user += size;
    return 0;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static double cpu_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static int time_rewrite(const char *obj, const char *layout_path, int runs)
{
    struct vt_layout l;
    struct vts_error err = {0};
    struct stat st;
    if (stat(obj, &st) != 0)
        return fail("cannot stat the scene");
    if (vt_layout_read(layout_path, NULL, &l, &err) < 0) {
        vt_layout_release(&l);
        return fail(err.message);
    }
    struct vt_offset_options opt;
    vt_offset_options_default(&opt);
    double best = 1e30, best_cpu = 1e30;
    unsigned long long written = 0;
    struct vt_offset_stats stats;
    for (int i = 0; i < runs; i++) {
        struct vt_offset_sink sink = {drop, &written};
        written = 0;
        double t0 = now_s(), c0 = cpu_s();
        int rc = vt_offset_rewrite(obj, &l, &opt, &sink, &stats, &err);
        double t = now_s() - t0, c = cpu_s() - c0;
        if (c < best_cpu)
            best_cpu = c;
        if (rc < 0) {
            vt_layout_release(&l);
            return fail(err.message);
        }
        if (t < best)
            best = t;
    }
    vt_layout_release(&l);
    printf(
        "%.1f MB in %.3f s: %.0f MB/s (CPU time %.3f s: %.0f MB/s); %llu bytes written, %llu vt, %llu faces renumbered\n",
        (double)st.st_size / 1e6, best, (double)st.st_size / 1e6 / best, best_cpu,
        (double)st.st_size / 1e6 / best_cpu, written, (unsigned long long)stats.vt_lines,
        (unsigned long long)stats.faces_rewritten);
    return 0;
}

int main(int argc, char **argv)
{
    if ((argc == 4 || argc == 5) && strcmp(argv[1], "time") == 0)
        return time_rewrite(argv[2], argv[3], argc == 5 ? atoi(argv[4]) : 3);
    if (argc >= 6 && strcmp(argv[1], "layout") == 0)
        return write_layout(argv[2], (uint32_t)strtoul(argv[3], NULL, 10),
                            (uint32_t)strtoul(argv[4], NULL, 10), argc - 5, argv + 5);
    if (argc == 4 && strcmp(argv[1], "bench") == 0)
        return write_bench(argv[2], atof(argv[3]));
    fputs("usage: vt-offset-gen layout OUT.json WIDTH HEIGHT NAME:X,Y,W,H[,RU,RV,OU,OV]...\n"
          "       vt-offset-gen bench DIR MB\n"
          "       vt-offset-gen time SCENE.obj atlas.json [RUNS]\n",
          stderr);
    return 2;
}
