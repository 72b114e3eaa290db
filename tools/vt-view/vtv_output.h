/* vt-view outputs: the screenshot (PNG, RGB) and the per-frame statistics (JSON). */
#ifndef VTV_OUTPUT_H
#define VTV_OUTPUT_H

#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vtv_clipmap.h"
#include "vtv_render.h"
#include "vtv_stream.h"
#include "vtv_terrain.h"

/* rgba: w x h RGBA8 rows, top first. Written atomically; path "-" streams it to standard output
 * (vt_atomic_file). */
int vtv_write_screenshot(const char *path, const uint8_t *rgba, uint32_t w, uint32_t h,
                         struct vts_error *err);

struct vtv_run_info {
    const char *store;
    const char *mode;      /* "2d" or "3d" */
    const char *filtering; /* "bilinear" or "trilinear" */
    const char *renderer;  /* "virtual" or "reference" */
    uint32_t width, height, feedback_width, feedback_height;
    uint32_t cache_tiles, uploads_per_frame;
    int sync;
    const char *physical_format;        /* "rgba8", "srgb8_alpha8", "bc" or "none" */
    const struct vtv_variant *variants; /* the shader variants drawn */
    uint32_t variant_count;
    const struct vtv_terrain_info *terrain; /* --terrain: the "terrain" object; NULL: none */
    const struct vtv_clipmap *clip;         /* clipmap mode: its per-frame statistics, or NULL */
};

/* Frames without timings first (deterministic under --sync), then "timing_ms". Written
 * atomically; path "-" streams it to standard output (vt_atomic_file). */
int vtv_write_stats(const char *path, const struct vtv_run_info *info,
                    const struct vtv_frame_stats *frames, size_t count, struct vts_error *err);

#endif
