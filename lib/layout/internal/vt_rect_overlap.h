/* Overlap of axis-aligned rectangles on the integer grid (the cell check of vt_layout_check). Pure
 * computation, no layout types. */
#ifndef VT_RECT_OVERLAP_H
#define VT_RECT_OVERLAP_H

#include <stdint.h>

struct vt_rect {
    uint32_t x, y, w, h; /* texels [x, x + w) x [y, y + h) */
};

/* Looks for two overlapping rectangles among r[0 .. n) in O(n log n) (a sweep over x with the
 * rectangles that span the sweep line in a treap keyed by y). Returns 1 with *a and *b set to two
 * that overlap (*b the one the sweep met last), 0 when all are disjoint, -1 when out of memory. */
int vt_rect_overlap_find(const struct vt_rect *r, uint32_t n, uint32_t *a, uint32_t *b);

#endif
