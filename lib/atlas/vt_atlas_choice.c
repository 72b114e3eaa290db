/* What an atlas entry holds for a texcoord box (vt_atlas_choice.h). */
#include "vt_atlas_choice.h"

#include <math.h>
#include <stdint.h>

enum vt_atlas_choice vt_atlas_choose(enum vt_atlas_wrap wrap, uint32_t max_repeat, bool has_box,
                                     double umin, double umax, double vmin, double vmax,
                                     uint32_t *ru, uint32_t *rv)
{
    *ru = *rv = 1;
    if (!has_box || (umax <= 1 && vmax <= 1))
        return VT_ATLAS_CHOICE_FIT;
    double cu = ceil(umax) < 1 ? 1 : ceil(umax), cv = ceil(vmax) < 1 ? 1 : ceil(vmax);
    bool few = cu <= max_repeat && cv <= max_repeat;
    double area = (umax - umin) * (vmax - vmin);
    enum vt_atlas_choice c;
    switch (wrap) {
    case VT_ATLAS_WRAP_REPORT:
        return VT_ATLAS_CHOICE_REPORT;
    case VT_ATLAS_WRAP_SPLIT:
        return VT_ATLAS_CHOICE_SPLIT;
    case VT_ATLAS_WRAP_REPLICATE:
        c = few ? VT_ATLAS_CHOICE_REPLICATE : VT_ATLAS_CHOICE_TOO_MANY;
        break;
    default:
        c = few && area <= VT_ATLAS_REPLICATE_MAX_AREA ? VT_ATLAS_CHOICE_REPLICATE
                                                       : VT_ATLAS_CHOICE_SPLIT;
        break;
    }
    if (c == VT_ATLAS_CHOICE_REPLICATE) {
        *ru = (uint32_t)cu;
        *rv = (uint32_t)cv;
    }
    return c;
}

double vt_atlas_box_cost(enum vt_atlas_choice c, double umin, double umax, double vmin, double vmax)
{
    if (c == VT_ATLAS_CHOICE_SPLIT)
        return 1;
    if (c == VT_ATLAS_CHOICE_FIT && umax - umin <= 0)
        return 1;
    return (umax - umin) * (vmax - vmin);
}

/* The texels [*start, *start + *len) of one axis of a block of copies (n texels each) that a
 * range [lo, hi] of texcoords reads, with VT_ATLAS_CROP_MARGIN texels around it and aligned to
 * VT_ATLAS_CROP_ALIGN; flip: rows from the top (v up). */
void vt_atlas_crop_axis(double lo, double hi, uint32_t n, uint32_t copies, bool flip,
                        uint32_t *start, uint32_t *len)
{
    double total = (double)n * copies;
    double a = flip ? (copies - hi) * n : lo * n, b = flip ? (copies - lo) * n : hi * n;
    a = floor(a) - VT_ATLAS_CROP_MARGIN;
    b = ceil(b) + VT_ATLAS_CROP_MARGIN;
    a = a < 0 ? 0 : a;
    b = b > total ? total : b;
    uint64_t s = (uint64_t)a / VT_ATLAS_CROP_ALIGN * VT_ATLAS_CROP_ALIGN;
    uint64_t e =
        ((uint64_t)b + VT_ATLAS_CROP_ALIGN - 1) / VT_ATLAS_CROP_ALIGN * VT_ATLAS_CROP_ALIGN;
    if (e > (uint64_t)total)
        e = (uint64_t)total;
    if (e <= s) {
        s = 0;
        e = (uint64_t)total;
    }
    *start = (uint32_t)s;
    *len = (uint32_t)(e - s);
}
