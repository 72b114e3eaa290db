/* vt-view tile loader: reads a tile through libvts, decodes it with the layer's codec and converts
 * it to RGBA8 payload texels (content + borders; 16-bit and float layers in their own format,
 * vtv_wide.h), either on the calling thread (--sync, the
 * reference image, the benchmark) or on background threads that take a prioritised queue. */
#ifndef VTV_LOADER_H
#define VTV_LOADER_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"
#include "vts.h"

struct vtv_load {
    uint64_t index; /* tile index (vtv_cache_index) */
    uint32_t level, x, y;
    bool empty;      /* stored with length 0 */
    int status;      /* 0 or a negative vt_status (message in error) */
    char error[512]; /* when status != 0 */
    uint8_t *rgba;   /* per layer of the loader, in its order, vtv_loader_slice_bytes() each:
                        RGBA8 texels (a compressed BC1..BC5 layer: its blocks as stored, first; a
                        16-bit or float layer: its vtv_wide_format, first); NULL when empty
                        (every layer stored empty) or failed */
    size_t bytes;    /* bytes in rgba: layers * vtv_loader_slice_bytes() */
    size_t bytes_read;
    struct vtv_load *next;
};

struct vtv_loader;

/* Layers one loader reads for each tile position (diffuse, normal, specular, alpha). */
#define VTV_LOADER_MAX_LAYERS 4

enum vtv_loader_flags {
    VTV_LOADER_COMPRESSED = 1u << 0, /* BC1..BC5 layers: hand over the blocks, do not decode */
};

/* Decodes tiles of `layer` of store; threads = 0 gives a loader without threads (only
 * vtv_loader_load_now); flags: enum vtv_loader_flags (ignored unless the layer is BC1..BC5).
 * Returns NULL and fills err on failure (bad layer, codec not built in). */
struct vtv_loader *vtv_loader_create(const struct vts_store *store, uint32_t layer,
                                     uint32_t threads, unsigned flags, struct vts_error *err);
/* Reads the same tile position of each of layer_count layers (1..VTV_LOADER_MAX_LAYERS) into one
 * result, so that a tile's layers arrive together; bit k of compressed_mask: layer k hands over
 * its BC1..BC5 blocks. A tile is empty when every layer is stored empty; a layer stored empty
 * while others are not shows a flat normal (normal layers) or zeros. A failure of any layer fails
 * the tile. */
struct vtv_loader *vtv_loader_create_layers(const struct vts_store *store, const uint32_t *layers,
                                            uint32_t layer_count, uint32_t threads,
                                            unsigned compressed_mask, struct vts_error *err);
void vtv_loader_destroy(struct vtv_loader *l);

/* Bytes of one layer's slice in a result: payload_px^2 times the widest texel of its layers, at
 * least 4 (RGBA8). */
size_t vtv_loader_slice_bytes(const struct vtv_loader *l);

/* Reads and decodes one tile on the calling thread (one such thread at a time: it uses the
 * loader's own buffers). Returns a result to give back with vtv_loader_release() (or free with
 * vtv_load_free()), or NULL when out of memory. */
struct vtv_load *vtv_loader_load_now(struct vtv_loader *l, uint64_t index, uint32_t level,
                                     uint32_t x, uint32_t y);
void vtv_load_free(struct vtv_load *r);
/* Gives a list of results back; their buffers are reused for later tiles. */
void vtv_loader_release(struct vtv_loader *l, struct vtv_load *list);

/* Replaces the queue of tiles not yet taken by a thread with these n tiles (highest priority
 * first). The tiles that were dropped from the old queue are written to dropped (capacity: the
 * old queue length, at most vtv_loader_queue_capacity()) and their count returned. */
uint32_t vtv_loader_queue_capacity(const struct vtv_loader *l);
uint32_t vtv_loader_submit(struct vtv_loader *l, const uint64_t *index, const uint32_t *lxy,
                           uint32_t n, uint64_t *dropped);

/* Takes up to max finished loads (oldest first) as a linked list; NULL when none. */
struct vtv_load *vtv_loader_take(struct vtv_loader *l, uint32_t max);

/* Blocks until the queue is empty and no thread is working (used by tests of the async path). */
void vtv_loader_wait_idle(struct vtv_loader *l);

#endif
