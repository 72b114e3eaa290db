/* Shared fixture of the vt-tiles --layout tests (test_atlas_build.c: one layout of several
 * entries and layers; test_atlas_build_cells.c: mixed coarse texels, groups, gutters): textures
 * written as PNG, the tool run with its stderr kept, stores read back texel by texel. */
#ifndef ATLAS_BUILD_FIXTURE_H
#define ATLAS_BUILD_FIXTURE_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_image.h"
#include "vts.h"

extern const char *abuild_tool;  /* vt-tiles */
extern const char *abuild_dir;   /* the work directory */
extern char abuild_stderr[8192]; /* stderr of the last abuild_run() */

/* A generated texture, written to abuild_dir/NAME.png. */
struct abuild_tex {
    const char *name;
    struct vt_image img;
    char path[512];
};

/* Smooth gradients plus noise (every texel distinct enough to catch offsets); ch 4 adds alpha. */
void abuild_texture(struct abuild_tex *t, const char *name, uint32_t w, uint32_t h, uint32_t ch,
                    uint32_t seed);

/* Runs "TOOL ARGS" keeping its stderr in abuild_stderr; returns its exit status. */
int abuild_run(const char *args);

/* One layer of a store read back tile by tile (the last tile decoded is kept). */
struct abuild_reader {
    struct vts_store *s;
    struct vts_geometry g;
    uint32_t layer, level, tx, ty;
    struct vt_image tile;
    bool valid, empty;
    unsigned char *buf;
};

bool abuild_reader_open(struct abuild_reader *r, const char *path, uint32_t layer);
void abuild_reader_close(struct abuild_reader *r);
/* The decoded payload of a tile (NULL when empty or unreadable). */
const struct vt_image *abuild_reader_tile(struct abuild_reader *r, uint32_t level, uint32_t tx,
                                          uint32_t ty);
/* Texel (X, Y) of a level, from the tile that owns it; NULL when that tile is empty. */
const uint8_t *abuild_reader_texel(struct abuild_reader *r, uint32_t level, uint32_t X, uint32_t Y);

/* malloc'ed copy of s (aborts when out of memory). */
char *abuild_strdup(const char *s);

/* An RGB texture reduced k times with the box filter in linear light, as 8-bit sRGB. */
void abuild_reduce(const struct vt_image *src, uint32_t k, struct vt_image *out);

#endif
