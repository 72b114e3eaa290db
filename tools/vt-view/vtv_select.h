/* vt-view: whether a store's layers are sampled without filtering (docs/viewer.md, "Categorical
 * and min/max layers"). A store whose mip levels are selections (metadata filter=nearest, mode,
 * min or max: every texel of every level is a value of level 0) or whose layers are categorical
 * (colour=index) must not be interpolated: a filtered class map shows class IDs that are not in
 * the data. */
#ifndef VTV_SELECT_H
#define VTV_SELECT_H

#include <stddef.h>
#include <stdint.h>

#include "vts.h"
#include "vtv_display.h"

/* The metadata entry that makes s a selection store, written into why ("filter=mode",
 * "colour=index"; at most cap bytes, NUL-terminated): 1, or 0 (why empty) for a filtered store. */
int vtv_select_store(const struct vts_store *s, char *why, size_t cap);

/* The colour of class value v on the index display (--ramp index): h = (v + 1) * 0x9E3779B1,
 * h ^= h >> 16, h *= 0x85EBCA6B, h ^= h >> 13 (32-bit unsigned), then with b0, b1, b2 the bytes
 * 0, 1, 2 of h: R, G, B = 48 + (bk * 208 >> 8), in 48..255 (no class near the background's dark
 * grey). The shader computes the same (vtv_shaders.c, F_INDEX). The 256 values of a u8 layer get
 * 256 distinct colours (view_unit); u16 values may share one (2 pairs among 0..4095). */
void vtv_index_colour(uint32_t v, uint8_t rgb[3]);

/* The index display (VTV_F_INDEX, replacing range and ramp) for store layer `layer` when index
 * is 1 (--ramp index), or -1 (default) and the store is colour=index; only for a one-channel u8
 * or u16 layer (otherwise a warning, and d is left as it is). */
void vtv_select_display(const struct vts_store *s, uint32_t layer, int index,
                        struct vtv_display *d);

#endif
