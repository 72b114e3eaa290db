/* vt-view application: options and the frame loop (stream, main pass, feedback, outputs). */
#ifndef VTV_APP_H
#define VTV_APP_H

#include <stdbool.h>
#include <stdint.h>

struct vtv_options {
    const char *store_path, *obj_path;
    const char *camera_path, *screenshot, *stats, *layer_name;
    const char *reference_scene; /* --reference-scene ORIGINAL.obj (with --reference) */
    bool headless, sync, reference, trilinear, no_bc_upload, prefetch;
    int debug;
    uint32_t aniso; /* --filtering anisoN: N (implies trilinear), else 1 */
    int nearest;    /* --filtering nearest: 1; another --filtering: 0 (filtered as asked); none:
                       -1 (nearest for a selection store, vtv_select.h, else bilinear) */
    uint32_t width, height, orbit, frames, feedback_div, cache_tiles, uploads, threads;
    uint32_t ram_tiles; /* --ram-cache (UINT32_MAX: as --cache) */
    uint32_t reads;     /* --reads: --sync reads per frame (0: no limit) */
    float light_dir[3], light_colour[3], ambient[3]; /* --light, --light-colour, --ambient */
    bool auto_lod;                                   /* --lod-bias auto (default) */
    float lod_bias;                                  /* --lod-bias N */
    bool has_range;                                  /* --range MIN:MAX given */
    float range[2];                                  /* its MIN, MAX (MIN < MAX) */
    int ramp;  /* --ramp: enum vtv_ramp_kind, or -1 (default: a ramp for one-channel wide layers) */
    int index; /* --ramp index: 1; another --ramp: 0; none: -1 (index for a colour=index store) */
    const char *wang_path;       /* --wang PACK.vts: vtv_wang.h draws it instead */
    uint32_t extent_x, extent_y; /* --extent MxN: tiles of the Wang output in the frame */
    uint32_t origin_x, origin_y; /* --origin X,Y: its top-left tile */
    bool wang_tilemap;           /* --tilemap: the hash precomputed (Wei's TileMap) */
    const char *terrain;         /* --terrain ELEVATION.vts[:LAYER] | :LAYER (vtv_terrain.h) */
    uint32_t terrain_grid;       /* --terrain-grid G */
    double terrain_exaggeration; /* --terrain-exaggeration F */
    uint32_t clipmap;            /* --clipmap N: clipmap mode with N x N tile windows (0: off) */
    uint64_t budget;             /* --budget: clipmap bytes uploaded per frame */
    bool clipmap_centre_set;     /* --clipmap-centre X,Y */
    double clipmap_centre[2];    /* its X, Y in level-0 texels */
};

void vtv_options_default(struct vtv_options *o);

/* Runs the viewer; returns the process exit status. */
int vtv_app_run(const struct vtv_options *o);

#endif
