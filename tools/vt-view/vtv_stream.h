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
#include "vtv_render.h"

struct vtv_frame_stats {
    uint64_t requested;       /* tiles in the request list (with ancestors) */
    uint64_t loaded;          /* tiles read and decoded that were applied this frame */
    uint64_t resident;        /* tiles in the physical texture after the uploads */
    uint64_t uploads;         /* tiles uploaded this frame */
    uint64_t fallback_pixels; /* pixels drawn from a coarser level than wanted */
    uint64_t empty;           /* tiles known to be stored empty */
    uint64_t failed;          /* tiles that could not be read or decoded, in all */
    double ms;                /* wall time of the frame */
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
};

/* Opens the cache (slots tiles), the loader (threads; 0 with sync) and uploads every tile of the
 * coarsest level, which stays resident. bc_upload: BC1/BC3 blocks go to a compressed physical
 * texture as stored when the GL can take them (else they are decoded on the CPU). */
int vtv_stream_init(struct vtv_stream *s, const struct vts_store *store, uint32_t layer,
                    uint32_t slots, uint32_t threads, bool sync, uint32_t budget, bool bc_upload,
                    struct vtv_render *render, struct vts_error *err);
void vtv_stream_free(struct vtv_stream *s);

/* Before the main pass: applies finished loads (sync: loads the pending list now). */
void vtv_stream_update(struct vtv_stream *s, struct vtv_frame_stats *st);

/* After the tile-determination pass: pixels are n RGBA16UI texels. */
int vtv_stream_request(struct vtv_stream *s, const uint16_t *pixels, size_t n,
                       struct vtv_frame_stats *st);

/* Level 0 of the layer decoded into one RGBA8 image (free() it); NULL and err on failure. */
uint8_t *vtv_stream_level0(const struct vts_store *store, uint32_t layer, struct vts_error *err);

#endif
