/* vt-view --wang PACK.vts: an arbitrarily large texture drawn from a Wang pack (vt-wang) with
 * TileTex (vtv_wang_glsl.h), or with --reference the same output assembled on the CPU into one
 * plain mipmapped texture (docs/wang.md, docs/cli/vt-view.md). The frame shows the extent (in
 * tiles) of the output from tile --origin (default its top-left corner), trilinear filtering; in a
 * window, dragging and the arrow keys pan it and +/- and the wheel zoom it (TileTex only). */
#ifndef VTV_WANG_H
#define VTV_WANG_H

#include "vtv_app.h"

/* Runs the viewer on o->wang_path; returns the process exit status. */
int vtv_wang_run(const struct vtv_options *o);

#endif
