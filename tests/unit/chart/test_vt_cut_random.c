/* The fuzz target's checks (tests/fuzz/fuzz_cut.c, compiled in with VT_FUZZ_NO_ENTRY) in every
 * build, not only the fuzzer's: on its seeds and kept findings (tests/data/fuzz/fuzz_cut/) and on
 * pseudo-random inputs from a fixed seed. A violated invariant aborts the test.
 * Usage: test_vt_chart_cut_random [DIR] [COUNT] (defaults: the source tree's seeds, 1000
 * inputs). */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_test.h"

int fuzz_cut_one(const uint8_t *data, size_t size);

static int replay_dir(const char *dir)
{
    DIR *d = opendir(dir);
    VT_CHECK(d != NULL);
    if (!d)
        return 0;
    int files = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.')
            continue;
        char path[2048];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        FILE *f = fopen(path, "rb");
        VT_CHECK(f != NULL);
        if (!f)
            continue;
        uint8_t buf[4096];
        size_t n = fread(buf, 1, sizeof buf, f);
        fclose(f);
        uint8_t *exact = malloc(n ? n : 1); /* sanitizers see reads past the end */
        if (!exact)
            abort();
        memcpy(exact, buf, n);
        VT_CHECK_INT_EQ(fuzz_cut_one(exact, n), 0);
        free(exact);
        files++;
    }
    closedir(d);
    return files;
}

static uint64_t next_random(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : VT_CUT_SEEDS_DIR;
    long count = argc > 2 ? atol(argv[2]) : 1000;
    int files = replay_dir(dir);
    VT_CHECK(files >= 5);
    fprintf(stderr, "ok   %d seeds of %s\n", files, dir);
    uint64_t state = 2600;
    for (long i = 0; i < count; i++) {
        uint8_t buf[192];
        size_t n = 8 + next_random(&state) % (sizeof buf - 8);
        for (size_t k = 0; k < n; k++)
            buf[k] = (uint8_t)next_random(&state);
        /* half the inputs with exact quarter texcoords, where lines meet vertices and edges */
        if (i & 1)
            buf[0] |= 2;
        VT_CHECK_INT_EQ(fuzz_cut_one(buf, n), 0);
    }
    fprintf(stderr, "ok   %ld random meshes\n", count);
    return vt_test_main_result();
}
