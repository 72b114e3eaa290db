/* lib/atlas: what an atlas entry holds for the union of its charts' texcoord boxes,
 * each chart moved by whole repeats (0 <= umin, vmin < 1): the --wrap choice, its cost in atlas
 * texels and the crop of one axis (docs/real-scenes.md). Pure functions of their arguments. */
#ifndef VT_ATLAS_CHOICE_H
#define VT_ATLAS_CHOICE_H

#include <stdbool.h>
#include <stdint.h>

/* Where a material's charts, each moved by whole repeats to start in [0,1) (vt_chart.h), do not
 * fit in one copy of its texture: see docs/real-scenes.md for the rules and their costs. */
enum vt_atlas_wrap {
    VT_ATLAS_WRAP_AUTO,      /* replicate when the cropped copies take at most
                                VT_ATLAS_REPLICATE_MAX_AREA textures and max_repeat copies per
                                direction, else split (the default) */
    VT_ATLAS_WRAP_REPORT,    /* an error naming the material */
    VT_ATLAS_WRAP_REPLICATE, /* copies side by side, cropped to the texels used (max_repeat) */
    VT_ATLAS_WRAP_SPLIT      /* one copy that wraps; vt-offset cuts the faces on integer lines */
};

/* The automatic choice replicates while the cropped copies cost at most this many textures. */
#define VT_ATLAS_REPLICATE_MAX_AREA 2.0

/* Texels kept around the used region of a cropped entry, and the multiple its crop rectangle is
 * aligned to (so that its first mip levels are the texture's own). */
#define VT_ATLAS_CROP_MARGIN 4
#define VT_ATLAS_CROP_ALIGN  8

enum vt_atlas_choice {
    VT_ATLAS_CHOICE_FIT,       /* inside [0,1] x [0,1]: one copy */
    VT_ATLAS_CHOICE_REPLICATE, /* copies side by side (*ru x *rv) */
    VT_ATLAS_CHOICE_SPLIT,     /* one copy that wraps; vt-offset cuts the faces */
    VT_ATLAS_CHOICE_REPORT,    /* --wrap report: an error */
    VT_ATLAS_CHOICE_TOO_MANY   /* --wrap replicate beyond max_repeat: an error */
};

/* The choice for the box (has_box false: no texcoords, fit) under --wrap and --max-repeat;
 * *ru, *rv get the copies (1 unless replicated). */
enum vt_atlas_choice vt_atlas_choose(enum vt_atlas_wrap wrap, uint32_t max_repeat, bool has_box,
                                     double umin, double umax, double vmin, double vmax,
                                     uint32_t *ru, uint32_t *rv);

/* Atlas texels the box costs with choice c, in textures (copies of the whole texture). */
double vt_atlas_box_cost(enum vt_atlas_choice c, double umin, double umax, double vmin,
                         double vmax);

/* The texels [*start, *start + *len) of one axis of a block of copies (n texels each) that the
 * texcoord range [lo, hi] reads, with VT_ATLAS_CROP_MARGIN texels around it and aligned to
 * VT_ATLAS_CROP_ALIGN; flip: rows counted from the top (v up). */
void vt_atlas_crop_axis(double lo, double hi, uint32_t n, uint32_t copies, bool flip,
                        uint32_t *start, uint32_t *len);

#endif
