/* The tile sink: what every tool that makes tiles does with each of them (vt-tiles for an image and
 * for an atlas layout, vt-merge for the coarse levels of a shard set): encode it with its layer's
 * codec into the worker's own scratch buffer and put it into the store writer. Also the two codec
 * choices these tools share: the encoder effort of `--mode fast|best` (vt-convert too) and the
 * codec `--codec auto` stands for. */
#ifndef VT_TILE_SINK_H
#define VT_TILE_SINK_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_codec.h"
#include "vt_error.h"
#include "vt_image.h"
#include "vts_writer.h"

#define VT_TILE_SINK_AUTO "auto" /* the --codec name resolved by vt_tile_sink_codec_name() */
#define VT_TILE_SINK_GPU  "gpu"  /* auto among the GPU block codecs: vt_tile_sink_gpu_codec() */

/* Encoder effort of `--mode best` (best) or `--mode fast` for codec: fast is 0 (the codec's
 * default); best is 9 (zlib level 9) for png and 1 for every other codec (the best bc1/bc3
 * encoder; raw and jpeg ignore it, and shard builds record the value as it is). */
int vt_tile_sink_effort(const struct vt_codec *codec, bool best);

/* The codec `auto` picks for a layer: "raw" for float samples, "png" for 16-bit samples, kept
 * alpha (alpha true: some texel is not opaque), normal and data colour, "jpeg" otherwise.
 * sample (enum vts_sample) is the sample type of the texels the layer is made of, before any
 * narrowing for the codec; it is where the two builds differ, and says so explicitly:
 *   - vt-tiles INPUT passes the input's sample (its texels keep their depth: a 16-bit input gets
 *     png, a float one raw);
 *   - vt-tiles --layout passes VTS_SAMPLE_U8 (an atlas layer is 8-bit: 16-bit and float textures
 *     are converted first, so they do not make the layer png). */
const char *vt_tile_sink_auto_codec(uint32_t sample, bool alpha, uint32_t colour);

/* The codec name a --codec value means: vt_tile_sink_auto_codec(sample, alpha, colour) for
 * VT_TILE_SINK_AUTO, the value itself otherwise (look it up with vt_codec_find()). */
const char *vt_tile_sink_codec_name(const char *requested, uint32_t sample, bool alpha,
                                    uint32_t colour);

/* The GPU block codec `--codec gpu` picks for a layer of 8-bit tiles with this many channels:
 * "bc5" for a 3-channel normal layer (x and y kept, z rebuilt) and for 2 channels, "bc4" for one
 * channel, "bc3" for kept alpha (alpha true, 4 channels), "bc1" otherwise. */
const char *vt_tile_sink_gpu_codec(uint32_t channels, bool alpha, uint32_t colour);

/* vt_tile_sink_codec_name() that also resolves VT_TILE_SINK_GPU, for a layer of `channels`
 * channels (after alpha is dropped or kept). */
const char *vt_tile_sink_layer_codec_name(const char *requested, uint32_t sample, uint32_t channels,
                                          bool alpha, uint32_t colour);

/* How the tiles of one store layer are encoded. */
struct vt_tile_sink_layer {
    const struct vt_codec *codec;  /* NULL: the caller puts this layer's payloads itself */
    struct vt_codec_params params; /* effort from vt_tile_sink_effort() */
    uint32_t channels, sample;     /* of the tiles given to vt_tile_sink_put() */
};

struct vt_tile_sink;

/* Creates a sink putting tiles into writer (which it does not own and which must outlive it) for
 * workers 0 .. workers-1; layers[0 .. layer_count-1] describe the writer's layers, tiles are
 * tile_payload_px square. Each worker gets a scratch buffer of the largest encoded_bound() of the
 * layers, and at least min_scratch_bytes (payloads the caller builds itself, see
 * vt_tile_sink_scratch()). Returns NULL and fills err (VTS_ERR_ARG, VTS_ERR_NOMEM) on failure.
 * Free with vt_tile_sink_destroy(). */
struct vt_tile_sink *vt_tile_sink_create(struct vts_writer *writer, uint32_t tile_payload_px,
                                         const struct vt_tile_sink_layer *layers,
                                         uint32_t layer_count, unsigned workers,
                                         size_t min_scratch_bytes, struct vts_error *err);

/* Encodes tile (its layer's channels and sample, tile_payload_px square) with the layer's codec
 * into the worker's scratch buffer and puts it as tile (tx, ty) of level `level` of layer `layer`;
 * tile NULL puts an empty tile. Thread-safe for distinct workers (each worker one call at a time).
 * Returns 0, the codec's status as "cannot encode tile X,Y of level L: <reason>", or the
 * writer's status and message. */
int vt_tile_sink_put(struct vt_tile_sink *s, unsigned worker, uint32_t layer, uint32_t level,
                     uint32_t tx, uint32_t ty, const struct vt_image *tile, struct vts_error *err);

/* The scratch buffer of worker `worker` (*capacity bytes, at least min_scratch_bytes), for a
 * payload the caller builds and puts itself (a shard's carried texels); owned by the sink, valid
 * until vt_tile_sink_destroy(). Not to be used during a vt_tile_sink_put() of the same worker. */
void *vt_tile_sink_scratch(struct vt_tile_sink *s, unsigned worker, size_t *capacity);

/* Frees the sink and its buffers (not the writer). Accepts NULL. */
void vt_tile_sink_destroy(struct vt_tile_sink *s);

#endif
