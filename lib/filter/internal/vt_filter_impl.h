/* Private to lib/filter: what its files share beyond vt_filter.h (the conversions' tables, used
 * by the reduction). */
#ifndef VT_FILTER_IMPL_H
#define VT_FILTER_IMPL_H

#include "vt_filter.h"

/* For 8-bit samples of mode m that convert through one table for every channel (opaque colour,
 * data): the table of w[0] * t[p] + w[1] * t[q] (in that order, float arithmetic, as the
 * reduction's horizontal pass computes it) indexed by p << 8 | q, when w is the box kernel's
 * (0.5, 0.5); NULL otherwise. Built once, thread-safe. */
const float *vt_filter_u8_pair_table(const struct vt_pixel_mode *m, const float *w);

#endif
