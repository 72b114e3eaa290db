/* vt-info --extract: a level, a tile or a Wang region as PNG or TIFF, with georeferencing sidecars.
 */
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "tool_common.h"
#include "vt_georef_file.h"
#include "vt_output_path.h"
#include "vt_store_georef.h"
#include "vt_tile_reader.h"
#include "vt_wang_pack.h"
#include "vti.h"

#define EXTRACT_MAX_TEXELS (1ull << 32) /* --extract refuses larger images */

/* True when the output is named .tif or .tiff (--extract then writes a TIFF). */
bool vti_wants_tiff(const char *path)
{
    const char *dot = strrchr(path, '.');
    return dot && !strchr(dot, '/') &&
           (strcasecmp(dot, ".tif") == 0 || strcasecmp(dot, ".tiff") == 0);
}

/* Usage errors for a layer, level or tile the store does not have, giving the valid range. */
static int check_extract_range(const struct vts_store *s, const struct options *o)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    const char *name = vts_store_name(s);
    struct vts_level L;
    if (o->layer >= g->layer_count)
        return vt_usage_error("layer %u is outside '%s' (layers 0..%u)", o->layer, name,
                              g->layer_count - 1);
    if (o->level >= g->level_count)
        return vt_usage_error("level %u is outside '%s' (levels 0..%u)", o->level, name,
                              g->level_count - 1);
    vts_store_level(s, o->level, &L);
    if (o->has_tile && (o->tile_x >= L.tiles_x || o->tile_y >= L.tiles_y))
        return vt_usage_error("tile %u,%u is outside level %u of '%s' (tiles 0..%u,0..%u)",
                              o->tile_x, o->tile_y, o->level, name, L.tiles_x - 1, L.tiles_y - 1);
    uint32_t fit = o->level;
    for (; !o->has_tile && (uint64_t)L.width * L.height > EXTRACT_MAX_TEXELS; fit++)
        vts_store_level(s, fit + 1, &L); /* the last level fits in one tile */
    if (fit != o->level)
        return vt_usage_error(
            "level %u of '%s' has more than 2^32 texels, the most --extract writes: use level %u or coarser, or --tile",
            o->level, name, fit);
    return 0;
}

/* --extract LEVEL --wang-region X,Y,W,H: the virtual output of a Wang pack. */
static int run_wang_region(const struct vts_store *s, const struct options *o)
{
    struct vt_wang_info info;
    struct vts_error err = {0};
    int rc = vt_wang_pack_open(s, &info, &err);
    if (rc == 0 && o->level >= vts_store_geometry(s)->level_count) {
        vt_wang_info_release(&info);
        return vt_usage_error("level %u is outside '%s' (levels 0..%u)", o->level,
                              vts_store_name(s), vts_store_geometry(s)->level_count - 1);
    }
    if (rc == 0)
        rc = vt_wang_pack_write_region(s, &info, o->level, o->wang_x, o->wang_y, o->wang_w,
                                       o->wang_h, o->out_path, &err);
    vt_wang_info_release(&info);
    if (rc != 0) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        return VT_EXIT_BAD_INPUT;
    }
    vt_log(VT_LOG_INFO, "wrote '%s'", o->out_path);
    return VT_EXIT_OK;
}

/* An extract of a georeferenced store gets its position as sidecar files (docs/geospatial.md):
 * OUT.aux.xml and a world file, with the transform of the level (and tile) written. */
static int write_georef(const struct vts_store *s, const struct options *o)
{
    struct vt_georef g;
    vt_store_georef(s, o->layer, &g);
    if ((!g.has_transform && !g.crs_wkt) || vt_output_path_is_stdio(o->out_path))
        return VT_EXIT_OK;
    if (g.has_transform) {
        double t[6];
        memcpy(t, g.transform, sizeof t);
        const struct vts_geometry *geo = vts_store_geometry(s);
        int64_t x = 0, y = 0; /* a tile's payload starts at its border */
        if (o->has_tile) {
            x = (int64_t)o->tile_x * geo->tile_content_px - geo->border_px;
            y = (int64_t)o->tile_y * geo->tile_content_px - geo->border_px;
        }
        vt_georef_region(t, o->level, x, y, g.transform);
    }
    char world[VT_PATH_MAX];
    struct vts_error err = {0};
    if (vt_georef_file_write(o->out_path, &g, world, sizeof world, &err) != 0) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        return VT_EXIT_BAD_INPUT;
    }
    vt_log(VT_LOG_INFO, "wrote '%s.aux.xml'%s%s%s", o->out_path, world[0] ? " and '" : "", world,
           world[0] ? "'" : "");
    return VT_EXIT_OK;
}

int vti_run_extract(const struct vts_store *s, const struct options *o)
{
    if (o->wang_region)
        return run_wang_region(s, o);
    struct vt_tile_reader r;
    struct vts_error err = {0};
    struct vts_tile_entry e;
    int rc = check_extract_range(s, o);
    if (rc != 0)
        return rc;
    bool tiff = vti_wants_tiff(o->out_path);
    rc = vt_tile_reader_init(&r, s, o->layer, &err);
    const char *nodata = vts_store_meta_find(s, "nodata"); /* empty tiles are nodata */
    char *end = NULL;
    if (nodata) {
        r.fill = strtod(nodata, &end);
        r.has_fill = end != nodata && !*end;
    }
    if (rc == 0 && !tiff && (r.img.sample == VTS_SAMPLE_F16 || r.img.sample == VTS_SAMPLE_F32))
        vt_log(VT_LOG_WARN,
               "layer %u holds %s samples: writing a 16-bit PNG clamped to [0,1] (a .tif output "
               "keeps the values)",
               o->layer, vts_sample_name(r.img.sample));
    if (rc == 0 && o->has_tile &&
        vts_store_tile(s, o->layer, o->level, o->tile_x, o->tile_y, &e, NULL) == 0 && e.length == 0)
        vt_log(VT_LOG_WARN, "tile %u,%u of level %u is empty: writing %s", o->tile_x, o->tile_y,
               o->level, r.has_fill ? "its nodata value" : "zeros");
    if (rc == 0)
        rc = vt_tile_reader_write_image(&r, o->level, o->has_tile, o->tile_x, o->tile_y,
                                        o->out_path, tiff, &err);
    vt_tile_reader_release(&r);
    if (rc != 0) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        return VT_EXIT_BAD_INPUT;
    }
    vt_log(VT_LOG_INFO, "wrote '%s'", o->out_path);
    return write_georef(s, o);
}
