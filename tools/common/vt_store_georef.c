#include "vt_store_georef.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Reads geo.transform's six numbers; false when the store has none or it is malformed. */
static bool read_transform(const char *v, double t[6])
{
    if (!v)
        return false;
    for (int i = 0; i < 6; i++) {
        char *end;
        t[i] = strtod(v, &end);
        if (end == v || !isfinite(t[i]))
            return false;
        v = end;
    }
    while (*v == ' ')
        v++;
    return *v == '\0';
}

bool vt_store_georef(const struct vts_store *s, uint32_t layer, struct vt_georef *g)
{
    const struct vts_layer *L = vts_store_layer(s, layer);
    *g = (struct vt_georef){.crs_wkt = vts_store_meta_find(s, "geo.crs_wkt"),
                            .nodata = vts_store_meta_find(s, "nodata"),
                            .bands = L ? L->channels : 0};
    g->has_transform = read_transform(vts_store_meta_find(s, "geo.transform"), g->transform);
    return g->has_transform || g->crs_wkt || g->nodata;
}

void vt_store_crs_name(const char *wkt, char *buf, size_t size)
{
    const char *q = strchr(wkt, '"');
    const char *e = q ? strchr(q + 1, '"') : NULL;
    if (!e)
        snprintf(buf, size, "(unnamed)");
    else
        snprintf(buf, size, "%.*s", (int)(e - q - 1), q + 1);
}
