/* The geometry of an export: which levels it has, how each is cut into tiles, what every tile's
 * file is called; and the checks of what can be exported. Pure computation, no I/O. */
#include <inttypes.h>
#include <stdio.h>
#include <string.h>

#include "internal/vt_export_impl.h"
#include "vt_error.h"

int vt_export_layout_parse(const char *name, enum vt_export_layout *out)
{
    static const char *const names[] = {"dzi", "iiif", "xyz"};
    for (int i = 0; i < 3; i++) {
        if (strcmp(name, names[i]) == 0) {
            *out = (enum vt_export_layout)i;
            return 0;
        }
    }
    return VTS_ERR_ARG;
}

static uint32_t ceil_shift(uint32_t size, uint32_t j)
{
    if (j >= 32)
        return 1;
    uint64_t v = ((uint64_t)size + ((1ull << j) - 1)) >> j;
    return v ? (uint32_t)v : 1;
}

void vt_export_plan_make(struct vt_export_plan *plan, enum vt_export_layout layout, uint32_t width,
                         uint32_t height, uint32_t tile_px, uint32_t overlap_px, const char *ext)
{
    *plan = (struct vt_export_plan){.layout = layout,
                                    .width = width,
                                    .height = height,
                                    .tile_px = tile_px,
                                    .overlap_px = layout == VT_EXPORT_DZI ? overlap_px : 0,
                                    .ext = ext};
    uint32_t top = 0;
    if (layout == VT_EXPORT_DZI) {
        /* Deep Zoom: level 0 is 1x1, each level doubles: N = ceil(log2(max(w, h))). */
        uint32_t edge = width > height ? width : height;
        while (top < 32 && (1ull << top) < edge)
            top++;
    } else {
        /* IIIF and XYZ: down to the first level that fits one tile. */
        while (ceil_shift(width, top) > tile_px || ceil_shift(height, top) > tile_px)
            top++;
    }
    plan->level_count = top + 1;
}

void vt_export_plan_init(struct vt_export_plan *plan, const struct vts_store *store,
                         const struct vt_export_params *p)
{
    const struct vts_geometry *g = vts_store_geometry(store);
    vt_export_plan_make(plan, p->layout, g->width, g->height, p->tile_px, p->overlap_px,
                        p->codec->fourcc == VTS_CODEC_JPEG ? "jpg" : "png");
}

uint32_t vt_export_level_width(const struct vt_export_plan *plan, uint32_t j)
{
    return ceil_shift(plan->width, j);
}

uint32_t vt_export_level_height(const struct vt_export_plan *plan, uint32_t j)
{
    return ceil_shift(plan->height, j);
}

uint32_t vt_export_tiles_x(const struct vt_export_plan *plan, uint32_t j)
{
    return (uint32_t)(((uint64_t)vt_export_level_width(plan, j) + plan->tile_px - 1) /
                      plan->tile_px);
}

uint32_t vt_export_tiles_y(const struct vt_export_plan *plan, uint32_t j)
{
    return (uint32_t)(((uint64_t)vt_export_level_height(plan, j) + plan->tile_px - 1) /
                      plan->tile_px);
}

/* [a, b) of tile i along an axis of size texels. */
static void tile_span(const struct vt_export_plan *plan, uint32_t i, uint32_t size, uint32_t *a,
                      uint32_t *b)
{
    uint64_t start = (uint64_t)i * plan->tile_px, end = start + plan->tile_px;
    uint32_t o = plan->overlap_px;
    start = start > o ? start - o : 0;
    end += o;
    *a = (uint32_t)start;
    *b = end < size ? (uint32_t)end : size;
}

struct vt_export_rect vt_export_tile_rect(const struct vt_export_plan *plan, uint32_t j, uint32_t c,
                                          uint32_t r)
{
    struct vt_export_rect rect;
    tile_span(plan, c, vt_export_level_width(plan, j), &rect.x0, &rect.x1);
    tile_span(plan, r, vt_export_level_height(plan, j), &rect.y0, &rect.y1);
    return rect;
}

uint32_t vt_export_level_number(const struct vt_export_plan *plan, uint32_t j)
{
    return plan->level_count - 1 - j;
}

/* IIIF: the region (full-size texels) and size of tile (c, r) of level j, in canonical form as
 * the Image API 3.0 and OpenSeadragon's level-0 requests write them: "full" for the whole image,
 * "max" for the full size, otherwise x,y,w,h and w,h. */
static int iiif_path(const struct vt_export_plan *plan, uint32_t j, uint32_t c, uint32_t r,
                     char *buf, size_t cap)
{
    uint64_t span = (uint64_t)plan->tile_px << j;
    uint64_t rx = c * span, ry = r * span;
    uint64_t rw = plan->width - rx < span ? plan->width - rx : span;
    uint64_t rh = plan->height - ry < span ? plan->height - ry : span;
    struct vt_export_rect t = vt_export_tile_rect(plan, j, c, r);
    uint32_t sw = t.x1 - t.x0, sh = t.y1 - t.y0;
    char region[96], size[48];
    if (rx == 0 && ry == 0 && rw == plan->width && rh == plan->height)
        snprintf(region, sizeof region, "full");
    else
        snprintf(region, sizeof region, "%" PRIu64 ",%" PRIu64 ",%" PRIu64 ",%" PRIu64, rx, ry, rw,
                 rh);
    if (sw == plan->width && sh == plan->height)
        snprintf(size, sizeof size, "max");
    else
        snprintf(size, sizeof size, "%u,%u", sw, sh);
    return snprintf(buf, cap, "%s/%s/0/default.%s", region, size, plan->ext);
}

int vt_export_tile_path(const struct vt_export_plan *plan, const char *name, uint32_t j, uint32_t c,
                        uint32_t r, char *buf, size_t cap)
{
    int n;
    uint32_t number = vt_export_level_number(plan, j);
    if (plan->layout == VT_EXPORT_DZI)
        n = snprintf(buf, cap, "%s_files/%u/%u_%u.%s", name, number, c, r, plan->ext);
    else if (plan->layout == VT_EXPORT_XYZ)
        n = snprintf(buf, cap, "%u/%u/%u.%s", number, c, r, plan->ext);
    else
        n = iiif_path(plan, j, c, r, buf, cap);
    return n < 0 || (size_t)n >= cap ? -1 : n;
}

uint64_t vt_export_tile_count(const struct vts_store *store, const struct vt_export_params *p)
{
    struct vt_export_plan plan;
    uint64_t n = 0;
    vt_export_plan_init(&plan, store, p);
    for (uint32_t j = 0; j < plan.level_count; j++)
        n += (uint64_t)vt_export_tiles_x(&plan, j) * vt_export_tiles_y(&plan, j);
    return n;
}

static int check_samples(const struct vts_store *store, const struct vt_export_params *p,
                         const struct vts_layer *l, struct vts_error *err)
{
    const char *name = vts_store_name(store);
    if (l->sample != VTS_SAMPLE_U8 && l->sample != VTS_SAMPLE_U16)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "'%s': layer %u holds %s samples; vt-export writes 8 and 16-bit "
                            "tiles only (vt-info --extract writes float levels as TIFF or EXR)",
                            name, p->layer, vts_sample_name(l->sample));
    if (p->codec->fourcc == VTS_CODEC_JPEG && l->channels != 1 && l->channels != 3)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "'%s': layer %u has %u channels; JPEG stores 1 (grey) or 3 (RGB): "
                            "use --format png",
                            name, p->layer, l->channels);
    if (p->codec->fourcc != VTS_CODEC_JPEG && p->codec->fourcc != VTS_CODEC_PNG)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "export tiles are png or jpeg, not %s",
                            p->codec->name);
    return 0;
}

int vt_export_check(const struct vts_store *store, const struct vt_export_params *p,
                    struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(store);
    const struct vts_layer *l = vts_store_layer(store, p->layer);
    struct vts_level coarse;
    if (!l)
        return vt_error_set(err, VTS_ERR_RANGE, "'%s': no layer %u (the store has %u)",
                            vts_store_name(store), p->layer, g->layer_count);
    int rc = check_samples(store, p, l, err);
    if (rc != 0)
        return rc;
    if (p->tile_px < 1 || p->tile_px > VT_EXPORT_MAX_TILE)
        return vt_error_set(err, VTS_ERR_ARG, "tile size %u is outside 1..%u", p->tile_px,
                            VT_EXPORT_MAX_TILE);
    if (p->overlap_px > VT_EXPORT_MAX_OVERLAP || p->overlap_px > p->tile_px)
        return vt_error_set(err, VTS_ERR_ARG, "overlap %u is outside 0..%u", p->overlap_px,
                            p->tile_px < VT_EXPORT_MAX_OVERLAP ? p->tile_px
                                                               : VT_EXPORT_MAX_OVERLAP);
    vts_store_level(store, g->level_count - 1, &coarse);
    if ((uint64_t)coarse.width * coarse.height > VT_EXPORT_MAX_COARSE_TEXELS)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "'%s': its coarsest level %u is %ux%u texels; the coarser export "
                            "levels are made from it in memory (at most %llu texels): build the "
                            "store with more levels",
                            vts_store_name(store), g->level_count - 1, coarse.width, coarse.height,
                            (unsigned long long)VT_EXPORT_MAX_COARSE_TEXELS);
    return 0;
}
