/* Valid .vts stores for the robustness tests and the fuzz seed corpus, file helpers, and the
 * re-sealing of CRCs after a deliberate corruption (so that structural checks, not only checksums,
 * are reached). Layout knowledge comes from lib/store/vts_format.h. */
#ifndef VTS_FIXTURE_H
#define VTS_FIXTURE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "robust/vts_reseal.h"
#include "vts.h"

enum vts_fixture {
    /* 40x24, 16 px content + 2 px border, 2 levels, 2 layers (raw u8 RGBA sRGB, png u16 RGB
     * normal): 16 index entries, empty and shared tiles, 3 metadata pairs; about 1 KiB. */
    VTS_FIXTURE_SMALL,
    /* 300x200, 60 px content + 2 px border, 3 levels, 3 layers: 84 entries; about 5 KiB. */
    VTS_FIXTURE_MEDIUM,
    /* 1x1 texel, one level, one layer, no payload at all (the file ends with the metadata). */
    VTS_FIXTURE_EMPTY,
    VTS_FIXTURE_COUNT
};

const struct vts_geometry *vts_fixture_geometry(enum vts_fixture which);
const struct vts_layer *vts_fixture_layers(enum vts_fixture which);

/* Payload the fixture stores for a tile (0 = empty). buf holds VTS_FIXTURE_MAX_PAYLOAD bytes. */
#define VTS_FIXTURE_MAX_PAYLOAD 64u
size_t vts_fixture_payload(enum vts_fixture which, uint32_t layer, uint32_t level, uint32_t tx,
                           uint32_t ty, unsigned char *buf);

/* Writes the fixture store at path with vts_writer. Returns 0 or a status (err filled). */
int vts_fixture_write(const char *path, enum vts_fixture which, struct vts_error *err);

/* Writes the fixture into dir and returns its bytes (malloc'd, *size set), or NULL. */
unsigned char *vts_fixture_bytes(const char *dir, enum vts_fixture which, size_t *size);

/* Whole-file helpers. read returns a malloc'd buffer (at least 1 byte allocated) or NULL. */
unsigned char *vts_fixture_read_file(const char *path, size_t *size);
int vts_fixture_write_file(const char *path, const void *data, size_t size);

/* A fresh directory under $TMPDIR (or /tmp); removed with everything in it by rmdir_all. */
bool vts_fixture_mkdtemp(char *out, size_t cap, const char *prefix);
void vts_fixture_rmdir_all(const char *dir);

/* Opens a store image with vts_open_memory and, when it opens, reads every tile into a buffer of
 * exactly vts_store_max_payload() bytes and walks every accessor. Returns the open status; fills
 * *read_failures with the number of tile reads that failed with anything but VTS_ERR_CHECKSUM
 * (never expected for a store that opened). */
int vts_fixture_exercise(const unsigned char *data, size_t size, const char *name,
                         struct vts_error *err, unsigned *read_failures);

#endif
