/* A temporary image of float texels in an unlinked file: written by rectangles from many threads,
 * read back as a vt_source. It disappears when closed or when the process dies. The file holds the
 * image in square tiles (row-major within a tile, tiles row-major), so that a rectangle that is a
 * whole tile is one contiguous write: the pyramid's blocks each write one tile of the next pass's
 * level, and small writes scattered over a row-major file cost the kernel more than the copy
 * (partial file-system blocks zeroed, the inode lock taken per row). */
#ifndef VT_FLOAT_FILE_H
#define VT_FLOAT_FILE_H

#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_source.h"

struct vt_float_file;

/* Creates a width x height image of `channels` floats per texel in dir (NULL = "."), stored in
 * tiles of tile_px x tile_px texels (pick the edge of the rectangles that will be written). Returns
 * NULL and fills err on failure. Free with vt_float_file_destroy() (after closing its sources). */
struct vt_float_file *vt_float_file_create(const char *dir, uint32_t width, uint32_t height,
                                           uint32_t channels, uint32_t tile_px,
                                           struct vts_error *err);

/* Writes the width x height texels at (x, y) (inside the image by contract), whose rows start
 * `stride` floats apart in texels. Thread-safe for disjoint rectangles. */
int vt_float_file_write(struct vt_float_file *f, uint32_t x, uint32_t y, uint32_t width,
                        uint32_t height, const float *texels, size_t stride, struct vts_error *err);

/* Opens a random-access source over the file (sample VTS_SAMPLE_F32, colour as given). The source
 * must be closed before the file is destroyed. Thread-safe across sources. */
int vt_float_file_source(struct vt_float_file *f, uint32_t colour, bool has_alpha,
                         struct vt_source *out, struct vts_error *err);

void vt_float_file_destroy(struct vt_float_file *f);

#endif
