/* A temporary image of float texels in an unlinked file: written by rows from many threads, read
 * back as a vt_source. It disappears when closed or when the process dies. */
#ifndef VT_FLOAT_FILE_H
#define VT_FLOAT_FILE_H

#include <stdint.h>

#include "vt_error.h"
#include "vt_source.h"

struct vt_float_file;

/* Creates a width x height image of `channels` floats per texel in dir (NULL = "."). Returns NULL
 * and fills err on failure. Free with vt_float_file_destroy() (after closing its sources). */
struct vt_float_file *vt_float_file_create(const char *dir, uint32_t width, uint32_t height,
                                           uint32_t channels, struct vts_error *err);

/* Writes `count` texels of row y starting at x. Thread-safe for disjoint rows/ranges. */
int vt_float_file_write(struct vt_float_file *f, uint32_t x, uint32_t y, const float *texels,
                        uint32_t count, struct vts_error *err);

/* Opens a random-access source over the file (sample VTS_SAMPLE_F32, colour as given). The source
 * must be closed before the file is destroyed. Thread-safe across sources. */
int vt_float_file_source(struct vt_float_file *f, uint32_t colour, bool has_alpha,
                         struct vt_source *out, struct vts_error *err);

void vt_float_file_destroy(struct vt_float_file *f);

#endif
