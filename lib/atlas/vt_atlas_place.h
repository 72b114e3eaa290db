/* The placement of vt-atlas: from a scanned scene (vt_atlas_scene.h) to a packed struct vt_layout
 * (layers, wrap replication, texel-density scales, shared entries, grid groups, paths relative to
 * the output), packed by vt_atlas_pack(). Pure computation apart from the working directory. */
#ifndef VT_ATLAS_PLACE_H
#define VT_ATLAS_PLACE_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_atlas_choice.h"
#include "vt_atlas_pack.h"
#include "vt_atlas_scene.h"
#include "vt_error.h"
#include "vt_layout.h"

struct vt_atlas_place_options {
    uint32_t tile_content, border, max_edge;
    uint32_t gutter;    /* texels of the texture's own edge around each sub-tile texture (a power
                           of two or 0; see vt_atlas_pack_options) */
    bool density;       /* even out texel density (scene mode) */
    uint32_t max_scale; /* density scales within 1/max_scale..max_scale (a power of two) */
    enum vt_atlas_wrap wrap;       /* what to do with a material whose moved charts leave [0,1] */
    uint32_t max_repeat;           /* most copies per direction a replicated entry may hold */
    uint32_t grid_rows, grid_cols; /* both non-zero: --grid (materials are the pieces) */
    const char *output;            /* atlas.json path: texture paths are made relative to it */
    const char *generator;         /* the layout's "generator" ("vt-atlas 0.1.0"), or NULL */
};

struct vt_atlas_place_report {
    struct vt_atlas_pack_stats pack;
    double target_density;         /* texels per world unit^2 (0 without --density) */
    uint32_t scaled;               /* entries with scale != 1 */
    uint32_t replicated;           /* entries with more than one copy */
    uint32_t constant;             /* entries without any texture */
    uint32_t materials;            /* materials (or list/grid textures) placed */
    uint32_t wang;                 /* materials naming a Wang pack: not placed (no entry) */
    uint32_t shared;               /* materials in an entry with others (name and aliases) */
    uint32_t shared_cells;         /* entries with aliases */
    uint32_t fit;                  /* textured entries whose charts fit in one copy */
    uint32_t split;                /* entries that wrap (vt-offset cuts their faces) */
    uint32_t cropped;              /* entries holding less than their whole block of copies */
    uint32_t charts, moved_charts; /* over the materials placed */
    uint64_t whole_area;           /* atlas texels (width x height) had every entry held its whole
                                      block of copies (0 when no entry is cropped) */
};

/* What vt_atlas_place() chose for one material, for -v listings (material order). */
struct vt_atlas_place_choice {
    const char *how; /* "constant", "fit", "replicate", "split"; "wang": a pack material */
    uint32_t entry;  /* the layout entry it uses (UINT32_MAX for "wang": none) */
    uint32_t repeat_u, repeat_v;
    uint32_t crop_width, crop_height; /* texels the entry holds */
};

/* Builds *layout (overwritten; release it after success or failure). Materials with the same
 * texture file in every layer (the same constant where there is none) and the same scale share
 * one entry, the first used named by it and the others its aliases, unless the union of their UV
 * boxes would cost more atlas texels than separate entries would
 * (--grid pieces never share). Returns 0, VTS_ERR_BAD_INPUT (--wrap report:
 * "'scene.obj':12: material 'ground' has a chart that leaves one copy: u 0..8, v 0..8 (--wrap)"),
 * VTS_ERR_LIMIT (the atlas does not fit --max-size, too many copies) or VTS_ERR_NOMEM. */
int vt_atlas_place(const struct vt_atlas_scene *scene, const struct vt_atlas_place_options *o,
                   struct vt_layout *layout, struct vt_atlas_place_report *report,
                   struct vts_error *err);

/* As vt_atlas_place(), and fills choices[0 .. scene->material_count) (may be NULL). Materials
 * that name a Wang pack (vt_wang) get no entry: layout->wangs records them (their pack relative
 * to o->output, scale and constants), report->wang counts them; a scene of pack materials only
 * has nothing to place (VTS_ERR_BAD_INPUT). */
int vt_atlas_place_choices(const struct vt_atlas_scene *scene,
                           const struct vt_atlas_place_options *o, struct vt_layout *layout,
                           struct vt_atlas_place_report *report,
                           struct vt_atlas_place_choice *choices, struct vts_error *err);

/* path as seen from the directory of output: absolute paths are kept, relative ones (to the
 * working directory) are rewritten relative to output's directory ("a/atlas.json" and "tex/b.png"
 * give "../tex/b.png"). Returns a malloc'ed string (free() it); NULL when out of memory or the
 * working directory is unknown. */
char *vt_atlas_place_relative_path(const char *output, const char *path);

#endif
