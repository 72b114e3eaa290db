/* Writes the valid fixture stores (tests/robust/vts_fixture.c) into a directory: the seed corpus
 * of fuzz_vts_reader. Usage: make_vts_seeds DIR (created if missing) */
#include <errno.h>
#include <stdio.h>
#include <sys/stat.h>

#include "robust/vts_fixture.h"

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: make_vts_seeds DIR\n");
        return 2;
    }
    if (mkdir(argv[1], 0777) != 0 && errno != EEXIST) {
        perror(argv[1]);
        return 1;
    }
    static const char *const names[VTS_FIXTURE_COUNT] = {"small.vts", "medium.vts", "empty.vts"};
    for (int i = 0; i < VTS_FIXTURE_COUNT; i++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", argv[1], names[i]);
        struct vts_error err = {0};
        if (vts_fixture_write(path, (enum vts_fixture)i, &err) != 0) {
            fprintf(stderr, "make_vts_seeds: %s\n", err.message);
            return 1;
        }
    }
    return 0;
}
