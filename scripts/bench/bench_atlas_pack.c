/* vt-bench-atlas-pack: packs N seeded textures of mixed sizes (each edge log-uniform in MIN..MAX)
 * with lib/vt_atlas_pack and prints the atlas area against the sum of the cells (textures rounded
 * up to whole tiles, sub-tile ones to their power-of-two cell) and the layout time.
 * usage: vt-bench-atlas-pack [--count N] [--seed S] [--tile-size T] [--min E] [--max E]
 *                            [--rounds R] [--gutter G] [--pow2 1]
 *        (defaults 1000, 1, 256, 16, 4096, 3, VT_ATLAS_DEFAULT_GUTTER, 0; --pow2 1 rounds every
 *        edge up to a power of two: the worst case for a gutter) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "vt_atlas_pack.h"

static uint64_t state;

static double uniform(void)
{
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(state >> 11) / 9007199254740992.0;
}

static uint32_t log_uniform(uint32_t lo, uint32_t hi)
{
    double v = exp(log((double)lo) + uniform() * (log((double)hi) - log((double)lo)));
    uint32_t e = (uint32_t)lround(v);
    return e < lo ? lo : e > hi ? hi : e;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

int main(int argc, char **argv)
{
    uint32_t count = 1000, seed = 1, tile = 256, lo = 16, hi = 4096, rounds = 3;
    uint32_t gutter = VT_ATLAS_DEFAULT_GUTTER, pow2 = 0;
    for (int i = 1; i + 1 < argc; i += 2) {
        uint32_t v = (uint32_t)strtoul(argv[i + 1], NULL, 10);
        if (!strcmp(argv[i], "--count"))
            count = v;
        else if (!strcmp(argv[i], "--seed"))
            seed = v;
        else if (!strcmp(argv[i], "--tile-size"))
            tile = v;
        else if (!strcmp(argv[i], "--min"))
            lo = v;
        else if (!strcmp(argv[i], "--max"))
            hi = v;
        else if (!strcmp(argv[i], "--rounds"))
            rounds = v;
        else if (!strcmp(argv[i], "--gutter"))
            gutter = v;
        else if (!strcmp(argv[i], "--pow2"))
            pow2 = v;
        else {
            fprintf(stderr, "vt-bench-atlas-pack: unknown option '%s'\n", argv[i]);
            return 2;
        }
    }
    if (!count || !rounds || !lo || lo > hi) {
        fprintf(stderr, "vt-bench-atlas-pack: bad arguments\n");
        return 2;
    }
    struct vt_atlas_rect *in = malloc(count * sizeof *in), *r = malloc(count * sizeof *r);
    if (!in || !r)
        return 1;
    state = seed;
    for (uint32_t i = 0; i < count; i++) {
        in[i] = (struct vt_atlas_rect){.width = log_uniform(lo, hi), .height = log_uniform(lo, hi)};
        if (pow2) { /* the worst case for a gutter: power-of-two textures */
            in[i].width = vt_atlas_next_pow2(in[i].width);
            in[i].height = vt_atlas_next_pow2(in[i].height);
        }
    }
    struct vt_atlas_pack_options o = {.tile_content = tile, .max_edge = 1u << 24, .gutter = gutter};
    struct vt_atlas_pack_stats s;
    struct vts_error err;
    double best = 1e30;
    for (uint32_t k = 0; k < rounds; k++) {
        memcpy(r, in, count * sizeof *r);
        double t0 = now_s();
        if (vt_atlas_pack(r, count, &o, &s, &err)) {
            fprintf(stderr, "vt-bench-atlas-pack: %s\n", err.message);
            return 1;
        }
        double t = now_s() - t0;
        if (t < best)
            best = t;
    }
    printf("textures %u (edges log-uniform %u..%u, seed %u), tile content %u, gutter %u\n", count,
           lo, hi, seed, tile, gutter);
    printf("atlas %ux%u texels (%ux%u tiles), tiles used %llu, empty %llu, sub-tile tiles %llu\n",
           s.width, s.height, s.tiles_x, s.tiles_y, (unsigned long long)s.tiles_used,
           (unsigned long long)s.tiles_empty, (unsigned long long)s.subtile_tiles);
    /* area/cells: against the cells without gutter (the packing target); area/gutter cells:
       against the cells actually placed (the packing loss alone). */
    printf("area/cells: %.4f\n", s.area_over_base);
    printf("area/gutter cells: %.4f\n", s.area_over_cells);
    printf("fill ratio: %.4f\n", s.fill_ratio);
    printf("layout time: %.4f s (best of %u)\n", best, rounds);
    free(in);
    free(r);
    return 0;
}
