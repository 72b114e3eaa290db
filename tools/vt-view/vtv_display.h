/* vt-view: how the shown colour (map_Kd's layer, or --layer's) is displayed (docs/viewer.md,
 * "Ranges and ramps"): its values mapped linearly from [min, max] to [0, 1] (VTV_F_RANGE), then
 * its first channel through a colour ramp (VTV_F_RAMP, vtv_ramp.h). The shader variants include
 * them only when used. */
#ifndef VTV_DISPLAY_H
#define VTV_DISPLAY_H

#include "vt_error.h"
#include "vts.h"

struct vtv_display {
    unsigned features; /* VTV_F_RANGE | VTV_F_RAMP bits, added to every shader variant */
    float min, max;    /* with VTV_F_RANGE */
    int ramp;          /* enum vtv_ramp_kind, with VTV_F_RAMP */
    float
        index_scale; /* with VTV_F_INDEX: the shader's value times this is the class (255, 65535) */
};

/* The display of store layer `layer`: range = the given [min, max], else (NULL) the layer's
 * entry in the store's "range" metadata (vt-tiles --layout writes it for f16, f32 and linear u16
 * layers), else for f16 and f32 layers the range of the coarsest level
 * (vtv_wide_estimate_range), else none (u8 and u16 shown as normalised values); ramp = the given
 * enum vtv_ramp_kind, or (-1) the dusk ramp for a one-channel f16/f32/u16 layer, none otherwise. A
 * ramp on a layer of more than one channel is ignored with a warning. Logs the choice (-v). 0 or a
 * read error. */
int vtv_display_choose(const struct vts_store *s, uint32_t layer, const float *range, int ramp,
                       struct vtv_display *out, struct vts_error *err);

#endif
