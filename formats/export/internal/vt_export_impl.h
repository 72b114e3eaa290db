/* Private to formats/export: the geometry of an export (its levels, tiles and file paths), shared
 * by the planner (vt_export_plan.c), the run (vt_export.c) and the descriptors
 * (vt_export_meta.c). */
#ifndef VT_EXPORT_IMPL_H
#define VT_EXPORT_IMPL_H

#include <stddef.h>
#include <stdint.h>

#include "vt_export.h"

/* Levels of an export are numbered here by their reduction j: level j is the full image reduced
 * 2^j times, ceil(width / 2^j) x ceil(height / 2^j) texels (the store's level j when it has one).
 */
struct vt_export_plan {
    enum vt_export_layout layout;
    uint32_t width, height; /* the full image (the store's level 0) */
    uint32_t tile_px, overlap_px;
    uint32_t level_count; /* j = 0 .. level_count - 1 */
    const char *ext;      /* "png" or "jpg" */
};

/* A rectangle of one level, in its texels: [x0, x1) x [y0, y1). */
struct vt_export_rect {
    uint32_t x0, y0, x1, y1;
};

/* The plan of a width x height image (tile_px >= 1; overlap_px for DZI only, ignored otherwise;
 * ext "png" or "jpg"). */
void vt_export_plan_make(struct vt_export_plan *plan, enum vt_export_layout layout, uint32_t width,
                         uint32_t height, uint32_t tile_px, uint32_t overlap_px, const char *ext);

/* The plan of p's export of store. */
void vt_export_plan_init(struct vt_export_plan *plan, const struct vts_store *store,
                         const struct vt_export_params *p);

/* Size of level j. */
uint32_t vt_export_level_width(const struct vt_export_plan *plan, uint32_t j);
uint32_t vt_export_level_height(const struct vt_export_plan *plan, uint32_t j);

/* Tiles across and down level j. */
uint32_t vt_export_tiles_x(const struct vt_export_plan *plan, uint32_t j);
uint32_t vt_export_tiles_y(const struct vt_export_plan *plan, uint32_t j);

/* The texels of level j that tile (c, r) shows: overlap included (DZI), clipped to the level. */
struct vt_export_rect vt_export_tile_rect(const struct vt_export_plan *plan, uint32_t j, uint32_t c,
                                          uint32_t r);

/* The layout's number of level j: DZI level, XYZ zoom; IIIF has none (its paths name regions). */
uint32_t vt_export_level_number(const struct vt_export_plan *plan, uint32_t j);

/* Writes the path of tile (c, r) of level j, relative to the export's directory, into buf
 * (NAME_files/L/c_r.ext, {region}/{size}/0/default.ext or z/c/r.ext). Returns the length, or -1
 * when it does not fit. */
int vt_export_tile_path(const struct vt_export_plan *plan, const char *name, uint32_t j, uint32_t c,
                        uint32_t r, char *buf, size_t cap);

/* Writes the descriptor of the export into dir: NAME.dzi (DZI), info.json (IIIF); nothing for XYZ.
 * Returns 0 or VTS_ERR_IO with a message. */
int vt_export_write_descriptor(const struct vt_export_plan *plan, const struct vt_export_params *p,
                               const char *dir, struct vts_error *err);

/* Writes len bytes to the new file dir/rel (its parent folders created as needed; an existing
 * file is an error). Returns 0 or VTS_ERR_IO with a message naming the file. */
int vt_export_write_file(const char *dir, const char *rel, const void *bytes, size_t len,
                         struct vts_error *err);

#endif
