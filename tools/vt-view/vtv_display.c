/* vt-view: range and ramp of the shown colour (see vtv_display.h). */
#include "vtv_display.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "tool_common.h"
#include "vtv_material.h"
#include "vtv_ramp.h"
#include "vtv_wide.h"

/* Entry `layer` of the store's "range" metadata (vt-tiles --layout: per layer MIN:MAX or "-",
 * comma-separated): true with range filled when it holds one. */
static bool meta_range(const struct vts_store *s, uint32_t layer, float range[2])
{
    const char *p = vts_store_meta_find(s, "range");
    for (uint32_t i = 0; p && i < layer; i++)
        if ((p = strchr(p, ',')) != NULL)
            p++;
    if (!p)
        return false;
    char *end;
    double lo = strtod(p, &end), hi;
    if (end == p || *end != ':')
        return false;
    const char *q = end + 1;
    hi = strtod(q, &end);
    if (end == q || (*end != ',' && *end != '\0') || !isfinite(lo) || !isfinite(hi) ||
        !(lo <= hi) || fabs(lo) > 3e38 || fabs(hi) > 3e38)
        return false;
    range[0] = (float)lo;
    range[1] = (float)hi;
    return true;
}

int vtv_display_choose(const struct vts_store *s, uint32_t layer, const float *range, int ramp,
                       struct vtv_display *out, struct vts_error *err)
{
    const struct vts_layer *l = vts_store_layer(s, layer);
    bool is_float = l->sample == VTS_SAMPLE_F16 || l->sample == VTS_SAMPLE_F32;
    *out = (struct vtv_display){0, 0.0f, 1.0f, VTV_RAMP_NONE, 0.0f};
    const char *how = "given";
    if (range) {
        out->features |= VTV_F_RANGE;
        out->min = range[0];
        out->max = range[1];
    } else {
        float r[2];
        bool have = meta_range(s, layer, r);
        how = "the store's";
        if (!have && is_float) {
            int rc = vtv_wide_estimate_range(s, layer, r, err);
            if (rc)
                return rc;
            have = true;
            how = "of the coarsest level";
        }
        if (have) {
            out->features |= VTV_F_RANGE;
            out->min = r[0];
            out->max = r[1] > r[0] ? r[1] : r[0] + 1.0f;
        }
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
