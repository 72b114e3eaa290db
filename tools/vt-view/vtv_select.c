/* vt-view: selection stores (see vtv_select.h). */
#include "vtv_select.h"

#include <stdio.h>
#include <string.h>

#include "tool_common.h"
#include "vtv_material.h"

int vtv_select_store(const struct vts_store *s, char *why, size_t cap)
{
    static const char *const selections[] = {"nearest", "mode", "min", "max"};
    const char *colour = vts_store_meta_find(s, "colour");
    const char *filter = vts_store_meta_find(s, "filter");
    if (cap)
        why[0] = '\0';
    if (colour && strcmp(colour, "index") == 0) {
        snprintf(why, cap, "colour=%s", colour);
        return 1;
    }
    for (size_t i = 0; filter && i < sizeof(selections) / sizeof(selections[0]); i++)
        if (strcmp(filter, selections[i]) == 0) {
            snprintf(why, cap, "filter=%s", filter);
            return 1;
        }
    return 0;
}

void vtv_index_colour(uint32_t v, uint8_t rgb[3])
{
    uint32_t h = (v + 1u) * 0x9E3779B1u;
    h ^= h >> 16;
    h *= 0x85EBCA6Bu;
    h ^= h >> 13;
    for (int c = 0; c < 3; c++)
        rgb[c] = (uint8_t)(48u + ((((h >> (8 * c)) & 255u) * 208u) >> 8));
}

void vtv_select_display(const struct vts_store *s, uint32_t layer, int index, struct vtv_display *d)
{
    const char *colour = vts_store_meta_find(s, "colour");
    if (index == 0 || (index < 0 && !(colour && strcmp(colour, "index") == 0)))
        return;
    const struct vts_layer *l = vts_store_layer(s, layer);
    if (l->channels != 1 || (l->sample != VTS_SAMPLE_U8 && l->sample != VTS_SAMPLE_U16)) {
        vt_log(VT_LOG_WARN,
               "layer '%s' is %u-channel %s: no index colours (one-channel u8 or u16 only)",
               l->name, l->channels, vts_sample_name(l->sample));
        return;
    }
    d->features = (d->features & ~(unsigned)(VTV_F_RANGE | VTV_F_RAMP)) | VTV_F_INDEX;
    d->index_scale = l->sample == VTS_SAMPLE_U8 ? 255.0f : 65535.0f;
    vt_log(VT_LOG_INFO, "layer '%s' (%s): index colours", l->name, vts_sample_name(l->sample));
}
