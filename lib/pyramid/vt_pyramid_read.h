/* Reading a pass's source for the mip pyramid (private to lib/): regions with clamped or wrapped
 * edges, and the band of full-width rows that stands in for a sequential source. */
#ifndef VT_PYRAMID_READ_H
#define VT_PYRAMID_READ_H

#include <stdint.h>

#include "vt_pyramid_pass.h"

/* Reads positions [x0, x0 + dst.width) x [y0, y0 + dst.height) of the pass source src into dst,
 * clamping (replicating the edge) or wrapping (o->wrap) positions outside the image. Uses s->xs,
 * s->ys. 0 or the source's status. */
int vt_pyramid_read_region(struct vt_pyramid_pass *p, struct vt_pyramid_pass_scratch *s,
                           struct vt_source *src, int64_t x0, int64_t y0, struct vt_image *dst,
                           struct vts_error *err);

/* Makes p->band hold source rows [a, b) (bands only move down): keeps the rows it already has,
 * reads the rest from p->sources[0] in one region read. 0 or a negative status (band invalid). */
int vt_pyramid_read_band_move(struct vt_pyramid_pass *p, int64_t a, int64_t b,
                              struct vts_error *err);

/* Sets p->band_source up as a source reading p->band, with info *in and name. */
void vt_pyramid_read_band_init(struct vt_pyramid_pass *p, const struct vt_source_info *in,
                               const char *name);

#endif
