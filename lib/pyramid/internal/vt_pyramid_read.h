/* Reading a pass's source for the mip pyramid (private to lib/pyramid, the bottom of its files;
 * see vt_pyramid_impl.h): regions with clamped or wrapped edges, and the band of full-width rows
 * that stands in for a sequential source. Knows sources and images only, not passes. */
#ifndef VT_PYRAMID_READ_H
#define VT_PYRAMID_READ_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_image.h"
#include "vt_source.h"

/* One stretch of a region along one axis: dst positions [dst, dst + len) read source positions
 * [src, src + len), or all repeat source position src when replicate (clamped edge). */
struct vt_pyramid_read_segment {
    int64_t dst;
    uint32_t src, len;
    bool replicate;
};

/* A worker's segment buffers, for regions up to cap - 4 texels along an axis. */
struct vt_pyramid_read_scratch {
    struct vt_pyramid_read_segment *xs, *ys;
    size_t cap;
};

/* Allocates s for regions of up to max_edge texels a side. 0 or VTS_ERR_NOMEM (then release s). */
int vt_pyramid_read_scratch_alloc(struct vt_pyramid_read_scratch *s, uint32_t max_edge);
void vt_pyramid_read_scratch_release(struct vt_pyramid_read_scratch *s);

/* Reads positions [x0, x0 + dst.width) x [y0, y0 + dst.height) of src, a width x height image,
 * into dst, clamping (replicating the edge) or, with wrap, wrapping positions outside the image.
 * 0 or the source's status. */
int vt_pyramid_read_region(struct vt_source *src, uint32_t width, uint32_t height, bool wrap,
                           struct vt_pyramid_read_scratch *s, int64_t x0, int64_t y0,
                           struct vt_image *dst, struct vts_error *err);

/* Full-width rows [y0, y0 + img.height) of a sequential source, and a source reading them. */
struct vt_pyramid_read_band {
    struct vt_image img;
    int64_t y0;
    bool valid;
    struct vt_source source; /* reads img; ctx points at this band, which must not move */
};

/* Sets b up, empty, with a source that has of's info and name. */
void vt_pyramid_read_band_init(struct vt_pyramid_read_band *b, const struct vt_source *of);

/* Makes b hold rows [a, end) of src (bands only move down): keeps the rows it already has, reads
 * the rest in one region read. 0 or a negative status (the band is then empty). */
int vt_pyramid_read_band_move(struct vt_pyramid_read_band *b, struct vt_source *src, int64_t a,
                              int64_t end, struct vts_error *err);

/* Frees the band's rows (it stays usable, empty). */
void vt_pyramid_read_band_release(struct vt_pyramid_read_band *b);

#endif
