/* vt-tiles INPUT -o OUT.vts: the single-image build (called from tools/vt-tiles/vt-tiles.c). Opens
 * the input (one source per worker unless it reads sequentially), picks the codec, output channels
 * and sample, settles the border and tile geometry, and runs the out-of-core pyramid into the store
 * writer; with --shard I/N, builds part I of N plus the carried texels vt-merge needs
 * (docs/sharding.md). */
#ifndef VT_TILES_IMAGE_H
#define VT_TILES_IMAGE_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_filter.h"

/* The vt-tiles options that apply to a single-image build (validated by vt-tiles' parser). */
struct vt_tiles_image_options {
    const char *input, *output; /* INPUT (a path to open) and OUT.vts */
    const char *input_name;     /* INPUT in messages and the "source" metadata: "<stdin>" for
                                   standard input (input is then its spooled copy) */
    const char *codec_name;     /* raw | png | jpeg | bc1 | bc3 | auto */
    const char *name;           /* layer name */
    const char *temp_dir;       /* pass images; NULL: the output's directory */
    uint32_t tile_size, border, quality, threads, colour, aniso, subsampling;
    bool border_set, colour_set, keep_content, wrap, best;
    bool index;       /* --colour index: colour data, filter mode or nearest ("colour" metadata) */
    bool band_layers; /* --band-layers: one layer per band of the input (docs/geospatial.md) */
    enum vt_filter_kind filter;
    const char *filtering; /* bilinear, trilinear, anisoN (aniso holds 0, 1 or N) */
    uint64_t max_pixels, max_store;
    uint32_t shard, shard_count; /* --shard I/N (docs/sharding.md); 0 = whole build */
    bool has_value_scale;        /* --value-scale/--value-offset given: layer.N.scale/offset */
    double value_scale, value_offset;
};

/* Runs the build; logs through tool_common (vt_log, progress). Returns the exit status: 0, 1 (an
 * unreadable input, a failed write) or 2 (an unavailable codec, a tile geometry the options do
 * not allow). */
int vt_tiles_image_run(const struct vt_tiles_image_options *o);

#endif
