/* vt-view tile streaming: ties the cache, the loader, the feedback list and the GL uploads
 * together, one step before the main pass (finished loads -> uploads, at most `budget` per frame,
 * page table) and one after the tile-determination pass (requests -> loader). */
#ifndef VTV_STREAM_H
#define VTV_STREAM_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"
#include "vtv_cache.h"
#include "vtv_feedback.h"
#include "vtv_loader.h"
#include "vtv_ramcache.h"
#include "vtv_render.h"

struct vtv_frame_stats {
    uint64_t requested;       /* tiles in the request list (with ancestors) */
    uint64_t loaded;          /* tiles read and decoded that were applied this frame */
    uint64_t resident;        /* tiles in the physical texture after the uploads */
    uint64_t uploads;         /* tiles uploaded this frame */
    uint64_t bytes_uploaded;  /* bytes those uploads sent to GL */
    uint64_t fallback_pixels; /* pixels drawn from a coarser level than wanted */
    uint64_t empty;           /* tiles known to be stored empty */
    uint64_t failed;          /* tiles that could not be read or decoded, in all */
    uint64_t ram_hits;        /* uploads served by the RAM cache (no read, no decode) */
    uint64_t reads;           /* tiles read and decoded this frame (--sync; demand + prefetch) */
    uint64_t prefetched;      /* tiles read ahead of demand into the RAM cache this frame */
    float lod_bias;           /* levels added to the level of detail in this frame */
    uint32_t levels;          /* entries of missed */
    uint32_t missed[VTS_MAX_LEVELS]; /* per level: tiles wanted that were not resident */
    double ms;                       /* wall time of the frame */
};

/* Streaming options beyond the cache size. */
struct vtv_stream_options {
    uint32_t ram_tiles; /* RAM cache of decoded payloads, in tiles (0: none) */
    bool prefetch;      /* read the neighbours and the next finer tiles of wanted ones ahead */
    uint32_t reads;     /* --sync: tiles read from the store per frame at most (0: no limit) */
    bool auto_lod;      /* raise the level of detail when the tiles wanted outgrow the cache */
    float lod_bias;     /* the bias when not auto_lod (levels, >= 0) */
};

struct vtv_stream {
    struct vtv_cache cache;
    struct vtv_loader *loader;
    struct vtv_feedback feedback;
    struct vtv_render *render;
    bool sync;
    uint32_t budget;
    uint64_t stamp; /* frame number of the latest tile determination (starts at 1) */
    uint64_t *pending;
    uint32_t *pending_lxy;
    uint32_t pending_count;
    uint64_t *dropped;
    uint64_t empty, failed;
    struct vtv_stream_options opt;
    struct vtv_ramcache *ram;
    uint8_t *wanted; /* per tile: asked for by the latest tile determination */
    uint64_t *ready; /* async: wanted tiles the RAM cache holds, to upload */
    uint32_t ready_count;
    uint64_t *ahead; /* prefetch candidates (index, then level, x, y in ahead_lxy) */
    uint32_t *ahead_lxy;
    uint32_t ahead_count, ahead_cap;
};

/* Opens the cache (slots tiles), the loader (threads; 0 with sync) and uploads every tile of the
 * coarsest level, which stays resident. layers: per map kind (enum vtv_map) the store layer drawn
 * for it, or UINT32_MAX; each one used gets a physical texture with the same slots, and the loader
 * reads all of them per tile position (one residency decision per position). bc_upload: BC1..BC5
 * blocks go to a compressed physical texture as stored when the GL can take them (else they are
 * decoded on the CPU). */
int vtv_stream_init(struct vtv_stream *s, const struct vts_store *store, const uint32_t *layers,
                    uint32_t slots, uint32_t threads, bool sync, uint32_t budget, bool bc_upload,
                    const struct vtv_stream_options *opt, struct vtv_render *render,
                    struct vts_error *err);
void vtv_stream_free(struct vtv_stream *s);

/* Before the main pass: applies finished loads (sync: loads the pending list now). */
void vtv_stream_update(struct vtv_stream *s, struct vtv_frame_stats *st);

/* After the tile-determination pass: pixels are n RGBA16UI texels. */
int vtv_stream_request(struct vtv_stream *s, const uint16_t *pixels, size_t n,
                       struct vtv_frame_stats *st);

/* Level 0 of the layer decoded into one RGBA8 image (free() it); NULL and err on failure. */
uint8_t *vtv_stream_level0(const struct vts_store *store, uint32_t layer, struct vts_error *err);

#endif
