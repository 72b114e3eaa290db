/* vt-view: range and ramp of the shown colour (see vtv_display.h). */
#include "vtv_display.h"

#include "tool_common.h"
#include "vtv_material.h"
#include "vtv_ramp.h"
#include "vtv_wide.h"

int vtv_display_choose(const struct vts_store *s, uint32_t layer, const float *range, int ramp,
                       struct vtv_display *out, struct vts_error *err)
{
    const struct vts_layer *l = vts_store_layer(s, layer);
    bool is_float = l->sample == VTS_SAMPLE_F16 || l->sample == VTS_SAMPLE_F32;
    *out = (struct vtv_display){0, 0.0f, 1.0f, VTV_RAMP_NONE};
    const char *how = "given";
    if (range) {
        out->features |= VTV_F_RANGE;
        out->min = range[0];
        out->max = range[1];
    } else if (is_float) {
        float r[2];
        int rc = vtv_wide_estimate_range(s, layer, r, err);
        if (rc)
            return rc;
        out->features |= VTV_F_RANGE;
        out->min = r[0];
        out->max = r[1] > r[0] ? r[1] : r[0] + 1.0f;
        how = "of the coarsest level";
    }
    if (ramp < 0)
        ramp = l->channels == 1 && l->sample != VTS_SAMPLE_U8 ? VTV_RAMP_DUSK : VTV_RAMP_NONE;
    if (ramp != VTV_RAMP_NONE && l->channels != 1) {
        vt_log(VT_LOG_WARN, "layer '%s' has %u channels: --ramp %s ignored (one channel only)",
               l->name, l->channels, vtv_ramp_name((enum vtv_ramp_kind)ramp));
        ramp = VTV_RAMP_NONE;
    }
    if (ramp != VTV_RAMP_NONE) {
        out->features |= VTV_F_RAMP;
        out->ramp = ramp;
    }
    if (out->features & VTV_F_RANGE)
        vt_log(VT_LOG_INFO, "layer '%s' (%s): range %g:%g (%s), ramp %s", l->name,
               vts_sample_name(l->sample), (double)out->min, (double)out->max, how,
               vtv_ramp_name((enum vtv_ramp_kind)out->ramp));
    else if (out->features & VTV_F_RAMP)
        vt_log(VT_LOG_INFO, "layer '%s' (%s): ramp %s", l->name, vts_sample_name(l->sample),
               vtv_ramp_name((enum vtv_ramp_kind)out->ramp));
    return 0;
}
