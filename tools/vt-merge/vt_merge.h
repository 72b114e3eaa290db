/* vt-merge's shared state (tools/vt-merge/vt-merge.c: checks, copying; tools/vt-merge/vt_merge.c:
 * the shard set of `vt-tiles --shard` and its coarse levels). */
#ifndef VT_MERGE_H
#define VT_MERGE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "tool_common.h"
#include "vt_codec.h"
#include "vt_shard.h"
#include "vt_tile_sink.h"
#include "vts.h"
#include "vts_writer.h"

#define SHARD_KEY                                                                                  \
    VT_SHARD_KEY /* shard=I/N: tile set I of N of one build (docs/cli/vt-merge.md)                 \
                  */

struct vt_merge_options {
    char **inputs;
    int input_count;
    const char *out_path, *temp_dir;
    uint32_t threads;
    uint64_t max_store;
};

struct merge {
    const struct vt_merge_options *o;
    struct vts_store **in;
    struct vts_writer *out;
    unsigned char *buf[2]; /* payload of the owner of a tile; another input's copy */
    size_t buf_cap;
    struct vt_progress progress;
    bool shard_build;     /* shards of vt-tiles --shard: they carry a float layer (vt_shard.h) */
    uint32_t copy_layers; /* shards mode: layers copied (the float layer is not) */
    struct vt_tile_sink *sink; /* coarse levels of a shard build */
};

/* Reads the payload of a tile of input k into m->buf[b]; *len 0 for an empty tile. */
int vt_merge_read_tile(struct merge *m, int k, int b, uint32_t layer, uint32_t level, uint32_t tx,
                       uint32_t ty, size_t *len, struct vts_error *err);

/* Checks that the inputs are the complete shard set of one `vt-tiles --shard` build (one line
 * naming the missing, duplicate or foreign shard otherwise). */
int vt_merge_check_shard_build(const struct merge *m, struct vts_error *err);

/* Assembles the shards' carried float texels and builds the remaining levels into m->out. */
int vt_merge_build_coarse(struct merge *m, struct vts_error *err);

#endif
