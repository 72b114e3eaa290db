/* Georeferencing sidecars of extracted images (vt_georef_file.h). */
#include "vt_georef_file.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_atomic_file.h"

void vt_georef_region(const double t[6], uint32_t level, int64_t x, int64_t y, double out[6])
{
    double s = ldexp(1.0, (int)level); /* level texels are 2^level level-0 texels */
    double fx = (double)x * s, fy = (double)y * s;
    out[0] = t[0] + fx * t[1] + fy * t[2];
    out[1] = t[1] * s;
    out[2] = t[2] * s;
    out[3] = t[3] + fx * t[4] + fy * t[5];
    out[4] = t[4] * s;
    out[5] = t[5] * s;
}

/* Writes len bytes of text to path through a temporary file. */
static int georef_put(const char *path, const char *text, size_t len, struct vts_error *err)
{
    struct vt_atomic_file f;
    int rc = vt_atomic_file_create(&f, path, "tmp", 0, err);
    if (rc)
        return rc;
    rc = vt_atomic_file_pwrite(&f, text, len, 0, err);
    if (rc == 0)
        rc = vt_atomic_file_commit(&f, err);
    if (rc)
        vt_atomic_file_abort(&f);
    return rc;
}

/* Appends s to buf (*used of size bytes), XML-escaped; false when it does not fit. */
static bool georef_append_xml(char *buf, size_t size, size_t *used, const char *s)
{
    for (; *s; s++) {
        const char *e = *s == '&' ? "&amp;" : *s == '<' ? "&lt;" : *s == '>' ? "&gt;" : NULL;
        char one[2] = {*s, '\0'};
        const char *piece = e ? e : one;
        size_t n = strlen(piece);
        if (*used + n >= size)
            return false;
        memcpy(buf + *used, piece, n + 1);
        *used += n;
    }
    return true;
}

static bool georef_append(char *buf, size_t size, size_t *used, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

static bool georef_append(char *buf, size_t size, size_t *used, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf + *used, size - *used, fmt, ap);
    va_end(ap);
    if (n < 0 || (size_t)n >= size - *used)
        return false;
    *used += (size_t)n;
    return true;
}

/* x.png -> x.pgw, x.tif / x.tiff -> x.tfw (GDAL's first and last letter of the extension + w),
 * anything else -> x.EXT.wld. */
static void georef_world_name(const char *image, char *out, size_t size)
{
    const char *slash = strrchr(image, '/');
    const char *dot = strrchr(slash ? slash : image, '.');
    size_t ext = dot ? strlen(dot + 1) : 0;
    if (dot && ext >= 2)
        snprintf(out, size, "%.*s.%c%cw", (int)(dot - image), image, dot[1], dot[ext]);
    else
        snprintf(out, size, "%s.wld", image);
}

int vt_georef_file_write(const char *image_path, const struct vt_georef *g, char *world_path,
                         size_t world_size, struct vts_error *err)
{
    world_path[0] = '\0';
    if (!g->has_transform && !g->crs_wkt)
        return 0;
    size_t wkt_len = g->crs_wkt ? strlen(g->crs_wkt) : 0;
    size_t size = 6 * wkt_len + 1024 + (size_t)g->bands * 128;
    char *xml = malloc(size);
    if (!xml)
        return vt_error_set(err, VTS_ERR_NOMEM, "'%s.aux.xml': out of memory", image_path);
    size_t used = 0;
    const double *t = g->transform;
    bool ok = georef_append(xml, size, &used, "<PAMDataset>\n");
    if (ok && g->crs_wkt)
        ok = georef_append(xml, size, &used, "  <SRS dataAxisToSRSAxisMapping=\"1,2\">") &&
             georef_append_xml(xml, size, &used, g->crs_wkt) &&
             georef_append(xml, size, &used, "</SRS>\n");
    if (ok && g->has_transform)
        ok = georef_append(
            xml, size, &used,
            "  <GeoTransform>%.17g, %.17g, %.17g, %.17g, %.17g, %.17g</GeoTransform>\n", t[0], t[1],
            t[2], t[3], t[4], t[5]);
    for (uint32_t b = 1; ok && g->nodata && b <= g->bands; b++)
        ok = georef_append(xml, size, &used, "  <PAMRasterBand band=\"%u\">\n    <NoDataValue>",
                           b) &&
             georef_append_xml(xml, size, &used, g->nodata) &&
             georef_append(xml, size, &used, "</NoDataValue>\n  </PAMRasterBand>\n");
    ok = ok && georef_append(xml, size, &used, "</PAMDataset>\n");
    char path[4096];
    int rc = 0;
    if (!ok || snprintf(path, sizeof path, "%s.aux.xml", image_path) >= (int)sizeof path)
        rc = vt_error_set(err, VTS_ERR_ARG, "'%s.aux.xml': name or content too long", image_path);
    if (rc == 0)
        rc = georef_put(path, xml, used, err);
    free(xml);
    if (rc || !g->has_transform)
        return rc;
    /* the world file: A D B E C F, C/F the centre of the first texel */
    char world[512];
    int n = snprintf(world, sizeof world, "%.17g\n%.17g\n%.17g\n%.17g\n%.17g\n%.17g\n", t[1], t[4],
                     t[2], t[5], t[0] + 0.5 * t[1] + 0.5 * t[2], t[3] + 0.5 * t[4] + 0.5 * t[5]);
    georef_world_name(image_path, world_path, world_size);
    return georef_put(world_path, world, (size_t)n, err);
}
