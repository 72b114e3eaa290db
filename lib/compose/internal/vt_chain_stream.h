/* A mip chain (vt_mip_chain.h) built from a stream of rows, top to bottom, without holding any
 * level whole: each 2:1 reduction keeps only the finer rows its kernel still needs, and each level
 * is handed out in blocks of at most VT_CHAIN_STREAM_EDGE x VT_CHAIN_STREAM_EDGE texels as soon as
 * its rows are done. The texels are those of vt_mip_chain_from_source() for the same spec, bit for
 * bit (vt_filter_reduce gives the same bits whatever the region split), for the cases it streams:
 * one whole copy (crop = the whole texture), clamped or wrapped, the texture at the entry's size
 * or at 2^k times it (its own mip level k: the input rows are reduced k times first). A wrapped
 * level's first rows wait for its last ones: each level below streams out rotated by a few rows
 * (vt_chain_stream.c). Memory: a few rows of each level (kernel taps + a band; with wrap also the
 * first rows the last ones read, and whole the levels of fewer than ~2 kernels of rows), plus
 * one or two rows of blocks per level. */
#ifndef VT_CHAIN_STREAM_H
#define VT_CHAIN_STREAM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_image.h"
#include "vt_mip_chain.h"

#define VT_CHAIN_STREAM_EDGE 64u /* block edge, texels (vt_block_cache.h's) */

/* Receives block (bx, by) of chain level `level`: w x h texels of the spec's channels and sample
 * type, rows tight. */
typedef int (*vt_chain_stream_emit_fn)(void *user, uint32_t level, uint32_t bx, uint32_t by,
                                       const uint8_t *px, uint32_t w, uint32_t h,
                                       struct vts_error *err);

struct vt_chain_stream;

/* Whether the stream can build the chain of spec from a texture of tw x th texels; *pre receives
 * the reductions before level 0 (k). */
bool vt_chain_stream_fits(const struct vt_mip_chain_spec *s, uint32_t tw, uint32_t th,
                          uint32_t *pre);

/* A stream for the chain of spec from a texture of tw x th texels (vt_chain_stream_fits).
 * Returns NULL and fills err (VTS_ERR_NOMEM, VTS_ERR_LIMIT). Free with _destroy. */
struct vt_chain_stream *vt_chain_stream_create(const struct vt_mip_chain_spec *s, uint32_t tw,
                                               uint32_t th, vt_chain_stream_emit_fn emit,
                                               void *user, struct vts_error *err);

/* The next rows of the texture (the spec's channels and sample type, tw wide), in order. 0 or the
 * status of the emit callback / VTS_ERR_NOMEM. After the last row every block has been emitted. */
int vt_chain_stream_push(struct vt_chain_stream *cs, const struct vt_image *rows,
                         struct vts_error *err);

/* Bytes of the buffers the stream holds now (they grow on the first pushes, then stay). */
size_t vt_chain_stream_bytes(const struct vt_chain_stream *cs);

void vt_chain_stream_destroy(struct vt_chain_stream *cs);

#endif
