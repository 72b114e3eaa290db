/* vt-view terrain: the elevation level read once, the displaced grid built (see vtv_terrain.h). */
#include "vtv_terrain.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "tool_common.h"
#include "vt_checked.h"
#include "vt_codec.h"
#include "vt_filter.h"
#include "vt_image.h"
#include "vtv_tangent.h"

void vtv_terrain_parse(char *spec, const char **path, const char **layer)
{
    struct stat st;
    *path = spec;
    *layer = NULL;
    if (spec[0] != ':' && stat(spec, &st) == 0)
        return; /* an existing file, colons and all */
    char *c = strrchr(spec, ':');
    if (!c)
        return;
    *c = '\0';
    *layer = c[1] ? c + 1 : NULL;
    if (c == spec)
        *path = NULL;
}

/* A finite number from metadata value s (the whole string). */
static bool meta_number(const char *s, double *out)
{
    char *end;
    if (!s)
        return false;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || !isfinite(v))
        return false;
    *out = v;
    return true;
}

/* The elevation layer: by name or index, else the first one-channel layer. */
static int pick_layer(const struct vts_store *s, const char *path, const char *name, uint32_t *out,
                      struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    if (!name) {
        for (uint32_t i = 0; i < g->layer_count; i++)
            if (vts_store_layer(s, i)->channels == 1) {
                *out = i;
                return 0;
            }
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "%s: no one-channel layer to take the elevation from (name one with "
                            "--terrain %s:LAYER)",
                            path, path);
    }
    bool found = false;
    for (uint32_t i = 0; i < g->layer_count && !found; i++)
        if (strcmp(vts_store_layer(s, i)->name, name) == 0) {
            *out = i;
            found = true;
        }
    if (!found && vt_parse_u32(name, 0, g->layer_count - 1, out) != 0)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "%s: no layer '%s' for the elevation", path,
                            name);
    const struct vts_layer *l = vts_store_layer(s, *out);
    if (l->channels != 1)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "%s: layer '%s' has %u channels: an elevation layer has one", path,
                            l->name, l->channels);
    return 0;
}

/* The store's geo.transform (GDAL's six numbers), when it has a usable one. */
static bool geo_transform(const struct vts_store *s, double t[6])
{
    const char *tv = vts_store_meta_find(s, "geo.transform");
    return tv &&
           sscanf(tv, "%lf %lf %lf %lf %lf %lf", &t[0], &t[1], &t[2], &t[3], &t[4], &t[5]) == 6 &&
           isfinite(t[0]) && isfinite(t[1]) && isfinite(t[3]) && isfinite(t[5]) && t[1] != 0 &&
           t[5] != 0;
}

/* The coarsest level with at least G texels across and down (level 0 when none has). */
static uint32_t pick_level(const struct vts_store *s, uint32_t grid)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    uint32_t best = 0;
    for (uint32_t l = 1; l < g->level_count; l++) {
        struct vts_level lv;
        if (vts_store_level(s, l, &lv) != 0 || lv.width < grid || lv.height < grid)
            break;
        best = l;
    }
    return best;
}

/* The stored value of texel (x, y) of a decoded tile as a double (u8/u16 as integers, f16/f32 as
 * they are). */
static double stored_value(const struct vt_image *img, uint32_t sample, uint32_t x, uint32_t y)
{
    const void *p = vt_image_at(img, x, y);
    switch (sample) {
    case VTS_SAMPLE_U8:
        return *(const uint8_t *)p;
    case VTS_SAMPLE_U16: {
        uint16_t v;
        memcpy(&v, p, 2);
        return v;
    }
    default: {
        struct vt_pixel_mode plain = {1, VTS_COLOUR_DATA, false};
        float f;
        vt_filter_to_working(&plain, sample, p, &f, 1);
        return f;
    }
    }
}

struct elevation {
    double *h; /* w x h elevations (NaN: nodata until filled) */
    uint32_t w, hgt;
};

/* Reads level `level` of layer into e->h: value = stored * scale + offset, NaN for nodata, not
 * finite or empty tiles. */
static int read_level(const struct vts_store *s, const char *path, uint32_t layer, uint32_t level,
                      double scale, double offset, bool has_nodata, double nodata,
                      struct elevation *e, struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    const struct vts_layer *info = vts_store_layer(s, layer);
    const struct vt_codec *codec = vt_codec_by_fourcc(info->codec);
    struct vts_level lv;
    vts_store_level(s, level, &lv);
    if (!codec)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "%s: layer '%s': unknown codec", path,
                            info->name);
    size_t n;
    if (!vt_size_mul((size_t)lv.width, lv.height, &n) || n > ((size_t)1 << 28))
        return vt_error_set(err, VTS_ERR_LIMIT, "%s: elevation level %u is too large (%ux%u)", path,
                            level, lv.width, lv.height);
    e->w = lv.width;
    e->hgt = lv.height;
    e->h = malloc(n * sizeof(double));
    size_t cap = (size_t)vts_store_max_payload(s) + 1;
    void *buf = malloc(cap);
    struct vt_image img = {0};
    int rc = e->h && buf ? 0 : vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    if (rc == 0)
        rc = vt_image_alloc(&img, g->tile_payload_px, g->tile_payload_px, 1, info->sample, err);
    double nd = info->sample == VTS_SAMPLE_F32 ? (double)(float)nodata : nodata;
    uint32_t c = g->tile_content_px, b = g->border_px;
    for (uint32_t ty = 0; rc == 0 && ty < lv.tiles_y; ty++)
        for (uint32_t tx = 0; rc == 0 && tx < lv.tiles_x; tx++) {
            size_t len = 0;
            uint32_t x0 = tx * c, y0 = ty * c;
            uint32_t w = lv.width - x0 < c ? lv.width - x0 : c;
            uint32_t hh = lv.height - y0 < c ? lv.height - y0 : c;
            rc = vts_store_read(s, layer, level, tx, ty, buf, cap, &len, 0, err);
            if (rc == 0 && len > 0) {
                struct vts_error e2 = {0};
                if (codec->decode(buf, len, &img, &e2) != 0)
                    rc = vt_error_set(err, e2.status ? e2.status : VTS_ERR_BAD_INPUT,
                                      "%s: tile %u,%u of level %u: %s", path, tx, ty, level,
                                      e2.message);
            }
            for (uint32_t y = 0; rc == 0 && y < hh; y++)
                for (uint32_t x = 0; x < w; x++) {
                    double v = NAN;
                    if (len > 0) {
                        v = stored_value(&img, info->sample, b + x, b + y);
                        bool nod = has_nodata && (v == nd || (isnan(nd) && isnan(v)));
                        v = nod || !isfinite(v) ? NAN : v * scale + offset;
                    }
                    e->h[(size_t)(y0 + y) * lv.width + x0 + x] = v;
                }
        }
    free(buf);
    vt_image_release(&img);
    return rc;
}

/* Bilinear elevation at level-0 position (x, y) of the elevation store (texel corners at
 * integers), level `level` (texel k covers level-0 [k 2^level, (k + 1) 2^level)); clamped. */
static double sample(const struct elevation *e, uint32_t level, double x, double y)
{
    double s = ldexp(1.0, -(int)level);
    double u = x * s - 0.5, v = y * s - 0.5;
    u = fmin(fmax(u, 0.0), e->w - 1.0);
    v = fmin(fmax(v, 0.0), e->hgt - 1.0);
    uint32_t x0 = (uint32_t)u, y0 = (uint32_t)v;
    uint32_t x1 = x0 + 1 < e->w ? x0 + 1 : x0, y1 = y0 + 1 < e->hgt ? y0 + 1 : y0;
    double fx = u - x0, fy = v - y0;
    const double *r0 = e->h + (size_t)y0 * e->w, *r1 = e->h + (size_t)y1 * e->w;
    double a = r0[x0] + (r0[x1] - r0[x0]) * fx, b = r1[x0] + (r1[x1] - r1[x0]) * fx;
    return a + (b - a) * fy;
}

/* The displaced grid's vertices (double, relative to the extent's centre) into m. */
static int build_mesh(const struct elevation *e, const struct vtv_terrain_options *o,
                      uint32_t level, const double win[4], double sx, double sz, struct vtv_mesh *m,
                      struct vts_error *err)
{
    uint32_t G = o->grid;
    size_t nv = (size_t)G * G, tris = (size_t)(G - 1) * (G - 1) * 2, floats;
    double *p = malloc(nv * 3 * sizeof(double)); /* x y z of each grid vertex */
    float *nrm = malloc(nv * 3 * sizeof(float));
    /* indexed: G^2 vertices, 3 uint32 indices per triangle (G <= VTV_TERRAIN_GRID_MAX keeps both
       counts far below 2^32) */
    bool fits = vt_size_mul(nv, VTV_VERTEX_FLOATS, &floats) && tris * 3 < UINT32_MAX;
    m->vertices = fits ? malloc(floats * sizeof(float)) : NULL;
    m->indices = fits ? malloc(tris * 3 * sizeof(uint32_t)) : NULL;
    m->groups = calloc(1, sizeof(*m->groups));
    m->layers[VTV_MAP_DIFFUSE] = strdup("");
    if (!p || !nrm || !m->vertices || !m->indices || !m->groups || !m->layers[VTV_MAP_DIFFUSE]) {
        free(p);
        free(nrm);
        return vt_error_set(err, VTS_ERR_NOMEM,
                            "out of memory for a terrain grid of %u x %u vertices", G, G);
    }
    for (int k = 0; k < 3; k++) {
        m->lo[k] = INFINITY;
        m->hi[k] = -INFINITY;
    }
    for (uint32_t j = 0; j < G; j++)
        for (uint32_t i = 0; i < G; i++) {
            double fu = (double)i / (G - 1), fv = (double)j / (G - 1);
            double *q = p + ((size_t)j * G + i) * 3;
            q[0] = (fu - 0.5) * sx;
            q[2] = (fv - 0.5) * sz;
            double ex = win[0] + fu * (win[2] - win[0]), ey = win[1] + fv * (win[3] - win[1]);
            q[1] = o->exaggeration * sample(e, level, ex, ey);
            for (int k = 0; k < 3; k++) {
                m->lo[k] = fmin(m->lo[k], q[k]);
                m->hi[k] = fmax(m->hi[k], q[k]);
            }
        }
    /* normals: central differences (one-sided at the edges) of the displaced grid */
    for (uint32_t j = 0; j < G; j++)
        for (uint32_t i = 0; i < G; i++) {
            uint32_t il = i ? i - 1 : i, ir = i + 1 < G ? i + 1 : i;
            uint32_t jt = j ? j - 1 : j, jb = j + 1 < G ? j + 1 : j;
            const double *l = p + ((size_t)j * G + il) * 3, *r = p + ((size_t)j * G + ir) * 3;
            const double *t = p + ((size_t)jt * G + i) * 3, *b = p + ((size_t)jb * G + i) * 3;
            double dx = (r[1] - l[1]) / (r[0] - l[0]), dz = (b[1] - t[1]) / (b[2] - t[2]);
            double n[3] = {-dx, 1.0, -dz}, len = sqrt(dx * dx + 1.0 + dz * dz);
            for (int k = 0; k < 3; k++)
                nrm[((size_t)j * G + i) * 3 + k] = (float)(n[k] / len);
        }
    /* the vertices, row by row */
    float *out = m->vertices;
    for (uint32_t j = 0; j < G; j++)
        for (uint32_t i = 0; i < G; i++, out += VTV_VERTEX_FLOATS) {
            size_t at = (size_t)j * G + i;
            for (int k = 0; k < 3; k++) {
                out[k] = (float)p[at * 3 + k];
                out[5 + k] = nrm[at * 3 + k];
            }
            out[3] = (float)((double)i / (G - 1));
            out[4] = (float)((double)j / (G - 1));
            out[8] = 1.0f; /* tangent +x (no normal map is drawn) */
            out[9] = out[10] = 0.0f;
            out[11] = 1.0f;
        }
    /* two triangles per cell, counter-clockwise seen from above (+y) */
    uint32_t *idx = m->indices;
    for (uint32_t j = 0; j + 1 < G; j++)
        for (uint32_t i = 0; i + 1 < G; i++) {
            const uint32_t corner[6][2] = {{i, j},     {i, j + 1}, {i + 1, j},
                                           {i + 1, j}, {i, j + 1}, {i + 1, j + 1}};
            for (int c = 0; c < 6; c++)
                *idx++ = corner[c][1] * G + corner[c][0];
        }
    free(p);
    free(nrm);
    m->vertex_count = (uint32_t)nv;
    m->index_count = (uint32_t)(tris * 3);
    m->group_count = 1;
    m->groups[0].count = m->index_count;
    m->groups[0].faces = tris;
    vtv_material_plain(&m->groups[0].mat);
    m->groups[0].mat.illum = 1; /* lit: directional light plus ambient */
    m->groups[0].features = vtv_material_features(&m->groups[0].mat);
    return 0;
}

void vtv_terrain_texel(const struct vtv_terrain_info *info, double x, double z, double *tx,
                       double *ty)
{
    /* the grid: x = (u - 1/2) * extent[0] with u = tx / width; likewise z and v */
    *tx = (x / info->extent[0] + 0.5) * info->colour_width;
    *ty = (z / info->extent[1] + 0.5) * info->colour_height;
}

int vtv_terrain_build(const struct vts_store *colour, const char *colour_path,
                      const struct vtv_terrain_options *o, struct vtv_mesh *m,
                      struct vtv_terrain_info *info, struct vts_error *err)
{
    memset(m, 0, sizeof(*m));
    memset(info, 0, sizeof(*info));
    char spec[1024];
    if (snprintf(spec, sizeof spec, "%s", o->spec) >= (int)sizeof spec)
        return vt_error_set(err, VTS_ERR_ARG, "--terrain: path too long");
    const char *path, *lname;
    vtv_terrain_parse(spec, &path, &lname);
    struct vts_store *own = NULL;
    const struct vts_store *s = colour;
    if (path) {
        own = vts_open(path, err);
        if (!own)
            return err->status;
        s = own;
    } else {
        path = colour_path;
    }
    snprintf(info->store, sizeof info->store, "%s", path);
    uint32_t layer = 0;
    struct elevation e = {0};
    int rc = pick_layer(s, path, lname, &layer, err);
    const struct vts_layer *li = rc == 0 ? vts_store_layer(s, layer) : NULL;
    char key[48];
    double scale = 1.0, offset = 0.0, nodata = 0.0;
    if (rc == 0) {
        snprintf(info->layer, sizeof info->layer, "%s", li->name);
        snprintf(key, sizeof key, "layer.%u.scale", layer);
        const char *sv = vts_store_meta_find(s, key);
        bool has_scale = meta_number(sv, &scale) && scale != 0.0;
        if (sv && !has_scale)
            rc = vt_error_set(err, VTS_ERR_BAD_INPUT,
                              "%s: metadata %s '%s' is not a finite number other than 0", path, key,
                              sv);
        else if (!has_scale && (li->sample == VTS_SAMPLE_U8 || li->sample == VTS_SAMPLE_U16))
            rc = vt_error_set(err, VTS_ERR_BAD_INPUT,
                              "%s: layer '%s' holds %s samples but the store has no %s (build "
                              "it with vt-tiles --value-scale S --value-offset O)",
                              path, li->name, vts_sample_name(li->sample), key);
    }
    if (rc == 0) {
        snprintf(key, sizeof key, "layer.%u.offset", layer);
        const char *ov = vts_store_meta_find(s, key);
        if (ov && !meta_number(ov, &offset))
            rc = vt_error_set(err, VTS_ERR_BAD_INPUT, "%s: metadata %s '%s' is not a number", path,
                              key, ov);
    }
    const char *nv = vts_store_meta_find(s, "nodata");
    bool has_nodata =
        nv && (strcmp(nv, "nan") == 0 || strcmp(nv, "NaN") == 0 || meta_number(nv, &nodata));
    if (has_nodata && !meta_number(nv, &nodata))
        nodata = NAN;
    uint32_t level = rc == 0 ? pick_level(s, o->grid) : 0;
    if (rc == 0)
        rc = read_level(s, path, layer, level, scale, offset, has_nodata, nodata, &e, err);
    double lo = INFINITY, hi = -INFINITY;
    uint64_t holes = 0;
    size_t n = (size_t)e.w * e.hgt;
    for (size_t i = 0; rc == 0 && i < n; i++) {
        if (isnan(e.h[i])) {
            holes++;
            continue;
        }
        lo = fmin(lo, e.h[i]);
        hi = fmax(hi, e.h[i]);
    }
    if (rc == 0 && !(lo <= hi))
        rc = vt_error_set(err, VTS_ERR_BAD_INPUT,
                          "%s: layer '%s' level %u holds no valid elevation (every texel is "
                          "nodata or empty)",
                          path, li->name, level);
    for (size_t i = 0; rc == 0 && i < n; i++)
        if (isnan(e.h[i]))
            e.h[i] = lo;
    if (rc == 0) {
        const struct vts_geometry *eg = vts_store_geometry(s), *cg = vts_store_geometry(colour);
        double t[6], ct[6], sx = cg->width, sz = cg->height;
        /* the grid's corners in level-0 texels of the elevation store */
        double win[4] = {0, 0, eg->width, eg->height};
        info->geo = geo_transform(s, t);
        if (info->geo) {
            sx = eg->width * fabs(t[1]);
            sz = eg->height * fabs(t[5]);
        }
        /* both georeferenced (north-up): the grid covers the colour store's extent, the
         * elevation sampled where the CRS places it */
        info->mapped = info->geo && s != colour && geo_transform(colour, ct) && t[2] == 0 &&
                       t[4] == 0 && ct[2] == 0 && ct[4] == 0;
        if (info->mapped) {
            sx = cg->width * fabs(ct[1]);
            sz = cg->height * fabs(ct[5]);
            win[0] = (ct[0] - t[0]) / t[1];
            win[1] = (ct[3] - t[3]) / t[5];
            win[2] = (ct[0] + cg->width * ct[1] - t[0]) / t[1];
            win[3] = (ct[3] + cg->height * ct[5] - t[3]) / t[5];
            const char *a = vts_store_meta_find(s, "geo.crs_wkt");
            const char *b = vts_store_meta_find(colour, "geo.crs_wkt");
            if (a && b && strcmp(a, b) != 0)
                vt_log(VT_LOG_WARN,
                       "%s and %s name different CRSs: their geo.transforms are mapped as if "
                       "they were the same",
                       path, colour_path);
        }
        memcpy(info->window, win, sizeof win);
        info->unit_per_texel = sx / cg->width;
        info->extent[0] = sx;
        info->extent[1] = sz;
        info->colour_width = cg->width;
        info->colour_height = cg->height;
        info->grid = o->grid;
        info->level = level;
        info->level_width = e.w;
        info->level_height = e.hgt;
        info->scale = scale;
        info->offset = offset;
        info->min_height = lo;
        info->max_height = hi;
        info->nodata_texels = holes;
        info->exaggeration = o->exaggeration;
        rc = build_mesh(&e, o, level, win, sx, sz, m, err);
    }
    free(e.h);
    vts_close(own);
    if (rc != 0)
        vtv_mesh_free(m);
    return rc;
}
