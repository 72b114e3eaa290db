/* A renderer's view of libvts: built against the installed headers and vts.pc only, as C and as
 * C++. Checks that the loaded library is the headers' version, prints the geometry and the number
 * of stored tiles, and reads every tile (CRC checked). */
#include <stdio.h>
#include <stdlib.h>
#include <vts.h>

int main(int argc, char **argv)
{
    if (argc != 2)
        return 2;
    if (vts_version() != VTS_VERSION_NUMBER) {
        fprintf(stderr, "consumer: libvts %s, headers %d.%d.%d\n", vts_version_string(),
                VTS_VERSION_MAJOR, VTS_VERSION_MINOR, VTS_VERSION_PATCH);
        return 1;
    }
    struct vts_error err;
    struct vts_store *s = vts_open(argv[1], &err);
    if (!s) {
        fprintf(stderr, "consumer: %s\n", err.message);
        return 1;
    }
    const struct vts_geometry *g = vts_store_geometry(s);
    unsigned char *buf = (unsigned char *)malloc(vts_store_max_payload(s) + 1);
    unsigned long stored = 0;
    int rc = 0;
    for (unsigned level = 0; level < g->level_count && rc == 0; level++) {
        struct vts_level L;
        rc = vts_store_level(s, level, &L);
        for (unsigned ty = 0; ty < L.tiles_y && rc == 0; ty++)
            for (unsigned tx = 0; tx < L.tiles_x && rc == 0; tx++) {
                size_t len;
                rc = vts_store_read(s, 0, level, tx, ty, buf, vts_store_max_payload(s), &len, 0,
                                    &err);
                stored += len > 0;
            }
    }
    if (rc == 0)
        printf("%ux%u levels=%u stored=%lu\n", g->width, g->height, g->level_count, stored);
    else
        fprintf(stderr, "consumer: %s\n", err.message);
    free(buf);
    vts_close(s);
    return rc ? 1 : 0;
}
