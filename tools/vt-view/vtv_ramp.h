/* vt-view colour ramps for single-channel layers (docs/viewer.md, "Ranges and ramps"): a value
 * mapped to [0,1] by --range is shown as the colour of the ramp at that position. A ramp is
 * VTV_RAMP_POINTS colours (sRGB-encoded, 0..1) at positions 0, 1/8, ..., 1, interpolated
 * linearly between them; values outside [0,1] take the end colours. The shader reads the same
 * table (uniform u_ramp), so vtv_ramp_at() is the CPU reference of what the GPU draws. */
#ifndef VTV_RAMP_H
#define VTV_RAMP_H

#include <stdbool.h>

#define VTV_RAMP_POINTS 9

enum vtv_ramp_kind {
    VTV_RAMP_NONE, /* no ramp: the channel shown as grey */
    VTV_RAMP_DUSK, /* dark violet -> blue -> teal -> green -> yellow, lightness rising */
    VTV_RAMP_HEAT, /* black -> red -> orange -> yellow -> white */
    VTV_RAMP_GREY, /* black -> white (the same as none, through the ramp path) */
    VTV_RAMP_COUNT
};

/* The ramp called name ("none", "dusk", "heat", "grey"); false when there is none. */
bool vtv_ramp_parse(const char *name, enum vtv_ramp_kind *out);

const char *vtv_ramp_name(enum vtv_ramp_kind k);

/* The ramp's control colours (NULL for VTV_RAMP_NONE). */
const float (*vtv_ramp_table(enum vtv_ramp_kind k))[3];

/* The colour at t (clamped to [0,1]; NaN gives the first colour), sRGB-encoded 0..1. */
void vtv_ramp_at(enum vtv_ramp_kind k, float t, float rgb[3]);

#endif
