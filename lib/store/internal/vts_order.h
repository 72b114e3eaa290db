/* Space-filling-curve order of the tiles of one level (the on-disk data order of a .vts store). */
#ifndef VTS_ORDER_H
#define VTS_ORDER_H

#include <stdint.h>

#include "vt_error.h"

/* Position of tile (x, y) along the Hilbert curve that covers a 2^k x 2^k grid (k = order_bits). */
uint64_t vts_hilbert_index(uint32_t order_bits, uint32_t x, uint32_t y);

/* Fills out[0 .. tiles_x * tiles_y - 1] with the row-major tile numbers (ty * tiles_x + tx) of a
 * tiles_x x tiles_y grid, sorted along the Hilbert curve of the smallest power-of-two square that
 * covers it. Returns 0 or VTS_ERR_NOMEM. */
int vts_order_level(uint32_t tiles_x, uint32_t tiles_y, uint64_t *out, struct vts_error *err);

#endif
