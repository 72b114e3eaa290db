/* vt-tiles --layout atlas.json: builds the store of an atlas from its source textures
 * (lib/compose/vt_atlas_build.h), one layer (--layer) or every layer of the layout into one store,
 * and optionally level 0 of a layer as one image (--export-atlas). See docs/atlas-build.md. */
#ifndef VT_TILES_LAYOUT_H
#define VT_TILES_LAYOUT_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_filter.h"

/* The vt-tiles options that apply to an atlas build. */
struct vt_tiles_layout_options {
    const char *layout;       /* atlas.json */
    const char *output;       /* OUT.vts; may be NULL when export_atlas is set */
    const char *layer;        /* --layer NAME, or NULL for every layer */
    const char *export_atlas; /* --export-atlas OUT.tif|.tiff|.png, or NULL */
    const char *codec_name;   /* "auto" (png for alpha, normal and data layers, else jpeg) */
    const char *filtering;    /* recorded in the metadata only: the layout fixes the border */
    uint32_t quality, subsampling;
    bool best;
    uint32_t tile_size; /* checked against the layout when tile_size_set */
    bool tile_size_set, keep_content;
    uint32_t border; /* checked against the layout when border_set */
    bool border_set;
    enum vt_filter_kind filter;
    uint64_t max_pixels; /* per texture */
    uint64_t max_store;  /* tile bytes the store may hold (0: no limit) */
    unsigned threads;
    uint64_t cache_bytes; /* decoded texture blocks kept in memory; 0 = 256 MiB */
    const char *temp_dir; /* where blocks over the budget spill; NULL = the output's directory */
    uint32_t shard, shard_count; /* --shard I/N (docs/sharding.md, "Atlas shards"); 0 = whole */
};

/* Runs the build; logs through tool_common (vt_log, progress). Returns the exit status: 0, 1 (an
 * unreadable layout or texture, naming the file; a failed write) or 2 (an option that conflicts
 * with the layout, an unknown --layer or codec). */
int vt_tiles_layout_run(const struct vt_tiles_layout_options *o);

#endif
