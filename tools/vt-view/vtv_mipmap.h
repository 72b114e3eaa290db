/* vt-view: the mip chain of a reference texture made on the CPU the way vt-tiles makes the store's
 * (lib/compose/vt_mip_chain.c, docs/filters.md): each level from the finer one in the float working
 * space of lib/filter (linear light for sRGB, premultiplied alpha), kept in float from level to
 * level, each level encoded to 8 bits (correctly rounded sRGB). A 2:1 reduction of an even edge is
 * the box filter (1/2, 1/2: the store's arithmetic, in the same order); GL's level sizes are
 * floor(n / 2), so an odd edge n > 1 is reduced to floor(n / 2) texels by the area-weighted box
 * (texel i averages finer [i n / m, (i + 1) n / m), 3 or 4 taps), which reads nothing outside the
 * level: the chain is the same for clamped and repeating addressing. */
#ifndef VTV_MIPMAP_H
#define VTV_MIPMAP_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"

/* Uploads rgba (w x h RGBA8 texels, rows top first) as level 0 of the GL_TEXTURE_2D bound to the
 * current texture unit, with internal format GL_SRGB8_ALPHA8 (colour VTS_COLOUR_SRGB) or
 * GL_RGBA8, then every coarser level down to 1 x 1, and sets GL_TEXTURE_MAX_LEVEL. colour (enum
 * vts_colour): sRGB texels are filtered in linear light, normal maps in [-1, 1] and renormalised
 * at each level (as the store's), linear and data as they are; alpha: the fourth channel is alpha
 * (colour premultiplied while filtering), else it is filtered as data. Needs a current GL context.
 * Returns 0 or VTS_ERR_NOMEM (the message names path). */
int vtv_mipmap_upload(const uint8_t *rgba, uint32_t w, uint32_t h, uint32_t colour, bool alpha,
                      const char *path, struct vts_error *err);

#endif
