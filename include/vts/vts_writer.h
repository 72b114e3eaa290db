/* .vts store writer: tiles in any order, from many threads; output appears atomically on finish. */
#ifndef VTS_WRITER_H
#define VTS_WRITER_H

#include <stddef.h>
#include <stdint.h>

#include "vts.h"

#ifdef __cplusplus
extern "C" {
#endif

struct vts_writer;

/* Starts a store at path with geometry g and g->layer_count layer descriptions. Payloads are
 * spooled to a hidden temporary file next to path; nothing appears under path before
 * vts_writer_finish() succeeds. Returns NULL and fills err on failure. Free with
 * vts_writer_destroy(). */
VTS_API struct vts_writer *vts_writer_create(const char *path, const struct vts_geometry *g,
                                             const struct vts_layer *layers, struct vts_error *err);

/* Limits the tile payload bytes the store may hold after deduplication (0: no limit, the
 * default). A put that would exceed it fails with VTS_ERR_LIMIT naming the store, and so does
 * every later put. Tools expose it as --max-store-size. */
VTS_API void vts_writer_set_max_bytes(struct vts_writer *w, uint64_t max_bytes);

/* Stores the payload of one tile (payload_len 0 = empty tile). Identical payloads are stored
 * once. Any order; safe to call from many threads at once; each tile at most once (VTS_ERR_ARG).
 * Tiles never put are empty. Returns 0, VTS_ERR_RANGE, VTS_ERR_ARG, VTS_ERR_LIMIT or VTS_ERR_IO. */
VTS_API int vts_writer_put(struct vts_writer *w, uint32_t layer, uint32_t level, uint32_t tx,
                           uint32_t ty, const void *payload, size_t payload_len,
                           struct vts_error *err);

/* Sets a metadata pair (replaces an earlier value of key). Key: 1..255 printable ASCII bytes
 * without '=' or spaces; value: UTF-8 text without NUL. Not thread-safe against itself. */
VTS_API int vts_writer_set_meta(struct vts_writer *w, const char *key, const char *value,
                                struct vts_error *err);

/* Writes header, index, metadata and the payloads (coarse levels first, Hilbert order within a
 * level, layers of a tile together), flushes to disk and renames over path. Call once, after every
 * put has returned. On failure nothing is left under path (a previous file there is intact). */
VTS_API int vts_writer_finish(struct vts_writer *w, struct vts_error *err);

/* Counters for reports: tiles put with data, empty tiles put, payloads shared with an earlier
 * identical tile, payload bytes after deduplication. */
struct vts_writer_stats {
    uint64_t tiles_stored;
    uint64_t tiles_empty;
    uint64_t tiles_shared;
    uint64_t unique_bytes;
};
VTS_API void vts_writer_stats(struct vts_writer *w, struct vts_writer_stats *out);

/* Frees the writer; without a successful finish, removes the temporary files. Accepts NULL. */
VTS_API void vts_writer_destroy(struct vts_writer *w);

#ifdef __cplusplus
}
#endif
#endif
