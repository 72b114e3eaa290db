/* Cut-out detection for vt-atlas: whether the alpha channel of a map_Kd texture is coverage that
 * a renderer should alpha-test (a fence, leaves) or something else (a smooth mask, a gradient).
 * The rule and its thresholds are documented in docs/atlas-format.md ("Alpha modes"). */
#ifndef VT_ATLAS_ALPHA_H
#define VT_ATLAS_ALPHA_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_source.h"

#define VT_ATLAS_ALPHA_CLEAR       0.125       /* alpha at most this: a clear texel */
#define VT_ATLAS_ALPHA_SOLID       0.875       /* alpha at least this: a solid texel */
#define VT_ATLAS_ALPHA_MAX_PARTIAL 0.10        /* a cut-out has at most this fraction in between */
#define VT_ATLAS_ALPHA_MIN_CLEAR   0.001       /* and at least this fraction of clear texels */
#define VT_ATLAS_ALPHA_BAND_BYTES  (16u << 20) /* most bytes of one band read (one row at least) */

struct vt_atlas_alpha_counts {
    uint64_t texels;  /* width x height of the texture */
    uint64_t read;    /* texels read (fewer than texels when the scan stopped early) */
    uint64_t clear;   /* alpha <= VT_ATLAS_ALPHA_CLEAR */
    uint64_t partial; /* in between */
};

/* True when the counts say cut-out: at most VT_ATLAS_ALPHA_MAX_PARTIAL of all texels partial and
 * at least VT_ATLAS_ALPHA_MIN_CLEAR clear. */
bool vt_atlas_alpha_is_cutout(const struct vt_atlas_alpha_counts *c);

/* Reads the alpha channel of src top-down in full-width bands (at most 64 rows and
 * VT_ATLAS_ALPHA_BAND_BYTES, one row at least: memory is bounded by the width, never the area)
 * and counts its texels into *c; stops as soon as the partial texels rule a cut-out out. A source
 * without alpha counts as solid (nothing is read). Returns 0, or the source's status (its message
 * names the file), VTS_ERR_NOMEM or VTS_ERR_LIMIT. */
int vt_atlas_alpha_scan(struct vt_source *src, struct vt_atlas_alpha_counts *c,
                        struct vts_error *err);

#endif
