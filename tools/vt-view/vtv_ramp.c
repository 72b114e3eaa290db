/* vt-view colour ramps (see vtv_ramp.h). The control colours are this project's own values. */
#include "vtv_ramp.h"

#include <stddef.h>
#include <string.h>

static const char *const names[VTV_RAMP_COUNT] = {"none", "dusk", "heat", "grey"};

static const float tables[VTV_RAMP_COUNT][VTV_RAMP_POINTS][3] = {
    [VTV_RAMP_DUSK] = {{0.26f, 0.00f, 0.33f},
                       {0.28f, 0.14f, 0.46f},
                       {0.24f, 0.29f, 0.53f},
                       {0.19f, 0.41f, 0.56f},
                       {0.15f, 0.52f, 0.56f},
                       {0.13f, 0.63f, 0.53f},
                       {0.29f, 0.74f, 0.43f},
                       {0.60f, 0.82f, 0.25f},
                       {0.98f, 0.90f, 0.14f}},
    [VTV_RAMP_HEAT] = {{0.00f, 0.00f, 0.00f},
                       {0.30f, 0.00f, 0.00f},
                       {0.60f, 0.05f, 0.00f},
                       {0.85f, 0.20f, 0.00f},
                       {1.00f, 0.40f, 0.00f},
                       {1.00f, 0.60f, 0.05f},
                       {1.00f, 0.80f, 0.20f},
                       {1.00f, 0.93f, 0.55f},
                       {1.00f, 1.00f, 1.00f}},
    [VTV_RAMP_GREY] = {{0.000f, 0.000f, 0.000f},
                       {0.125f, 0.125f, 0.125f},
                       {0.250f, 0.250f, 0.250f},
                       {0.375f, 0.375f, 0.375f},
                       {0.500f, 0.500f, 0.500f},
                       {0.625f, 0.625f, 0.625f},
                       {0.750f, 0.750f, 0.750f},
                       {0.875f, 0.875f, 0.875f},
                       {1.000f, 1.000f, 1.000f}},
};

bool vtv_ramp_parse(const char *name, enum vtv_ramp_kind *out)
{
    for (int k = 0; k < VTV_RAMP_COUNT; k++)
        if (strcmp(name, names[k]) == 0) {
            *out = (enum vtv_ramp_kind)k;
            return true;
        }
    return false;
}

const char *vtv_ramp_name(enum vtv_ramp_kind k)
{
    return (unsigned)k < VTV_RAMP_COUNT ? names[k] : "?";
}

const float (*vtv_ramp_table(enum vtv_ramp_kind k))[3]
{
    return k > VTV_RAMP_NONE && k < VTV_RAMP_COUNT ? tables[k] : NULL;
}

void vtv_ramp_at(enum vtv_ramp_kind k, float t, float rgb[3])
{
    const float(*tab)[3] = vtv_ramp_table(k);
    if (!tab) {
        float v = t >= 0.0f ? (t <= 1.0f ? t : 1.0f) : 0.0f;
        rgb[0] = rgb[1] = rgb[2] = v;
        return;
    }
    /* as the shader: s = clamp(t, 0, 1) * 8, i = min(floor(s), 7), mix(tab[i], tab[i + 1], s - i)
     */
    float s = (t >= 0.0f ? (t <= 1.0f ? t : 1.0f) : 0.0f) * (VTV_RAMP_POINTS - 1);
    int i = (int)s;
    i = i < VTV_RAMP_POINTS - 2 ? i : VTV_RAMP_POINTS - 2;
    float f = s - (float)i;
    for (int c = 0; c < 3; c++)
        rgb[c] = tab[i][c] + (tab[i + 1][c] - tab[i][c]) * f;
}
