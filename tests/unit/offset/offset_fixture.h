/* Shared helpers of the vt-offset unit tests (test_vt_offset.c: rewriting;
 * test_vt_offset_numerics.c: numerics, errors, random scenes): layouts built in memory and
 * rewrites of OBJ text in memory. */
#ifndef OFFSET_FIXTURE_H
#define OFFSET_FIXTURE_H

#include <stddef.h>
#include <stdint.h>

#include "vt_layout.h"
#include "vt_offset.h"

/* One entry: rectangle, repeats and UV origin; a name starting with "const" has no texture. */
struct spec {
    const char *name;
    uint32_t x, y, w, h, ru, rv;
    int32_t ou, ov;
};

/* A growing output buffer (NUL-terminated). */
struct membuf {
    char *data;
    size_t len, cap;
};

/* A vt_offset_sink write function appending to the struct membuf user. */
int offset_fixture_write(void *user, const void *data, size_t size, struct vts_error *err);

/* The u, v of the i-th (0-based) vt line of text; false when there is none. */
int offset_fixture_nth_vt(const char *text, int i, double *u, double *v);

/* Builds and indexes a one-layer layout of n entries (checks that it is valid). */
void offset_fixture_layout(struct vt_layout *l, uint32_t width, uint32_t height,
                           const struct spec *specs, uint32_t n);

/* Rewrites text ("s.obj", mtllib out.mtl, digits 0 = automatic) onto l into *out (free out->data);
 * returns the status with stats and err filled. */
int offset_fixture_rewrite(const char *text, const struct vt_layout *l, unsigned digits,
                           struct membuf *out, struct vt_offset_stats *stats,
                           struct vts_error *err);

/* True when the rewrite succeeds with exactly want (prints the difference otherwise). */
int offset_fixture_expect_output(const char *text, const struct vt_layout *l, unsigned digits,
                                 const char *want, struct vt_offset_stats *stats);

/* True when the rewrite fails with status and exactly message, writing nothing. */
int offset_fixture_expect_error(const char *text, const struct vt_layout *l, int status,
                                const char *message);

#endif
