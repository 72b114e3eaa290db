/* Merging shards (docs/sharding.md, docs/cli/vt-merge.md): what vt-merge needs to know about a set
 * of shard stores besides copying their tiles. Plain shards carry `shard=I/N` metadata; the shards
 * of `vt-tiles --shard` also carry the build (vt_shard.h) and, in an extra layer, the texels of
 * their first pass's last level, from which the merge resumes the pyramid (vt_pyramid_resume.h). */
#ifndef VT_SHARD_MERGE_H
#define VT_SHARD_MERGE_H

#include <stdbool.h>

#include "vt_error.h"
#include "vt_pyramid.h"
#include "vt_pyramid_resume.h"
#include "vt_shard.h"
#include "vts.h"

/* The inputs of a merge, as opened by the caller (who keeps them open while this is used). */
struct vt_shard_merge {
    struct vts_store *const *stores;
    const char *const *names; /* as messages name the inputs (their command-line paths) */
    int count;                /* >= 1 */
};

/* Reads the payload of tile (tx, ty) of level `level`, layer `layer` of input k into buf
 * (capacity bytes: vts_store_max_payload() of the input is enough); *len is 0 for an empty tile.
 * Fails with "'<name>': layer L level V tile X,Y: <reason>" (the store's, or "payload checksum
 * mismatch"). Thread-safe (vts_store_read). */
int vt_shard_merge_read(const struct vt_shard_merge *m, int k, uint32_t layer, uint32_t level,
                        uint32_t tx, uint32_t ty, void *buf, size_t capacity, size_t *len,
                        struct vts_error *err);

/* Shards mode, one tile (index: its position in the index of layer, level, tx, ty): reads the
 * payload of the first input that stores it into buf[0] (*owner = that input, *len its length; -1
 * and 0 when no input stores it) and checks that every other input storing it holds the same
 * bytes (read into buf[1]), VTS_ERR_BAD_INPUT naming both otherwise. Buffers of capacity bytes,
 * enough for any payload of the inputs. */
int vt_shard_merge_tile(const struct vt_shard_merge *m, uint64_t index, uint32_t layer,
                        uint32_t level, uint32_t tx, uint32_t ty, unsigned char *const buf[2],
                        size_t capacity, int *owner, size_t *len, struct vts_error *err);

/* True when the inputs are shards I/N of one build: I = 1..N once each, N = the input count, the
 * same metadata in the same order apart from VT_SHARD_KEY. Then the output is that build and
 * keeps none of the keys vt_shard_merge_drops_key() names. */
bool vt_shard_merge_is_single_build(const struct vt_shard_merge *m);

/* The union of the shards' VT_SHARD_RANGE_KEY lists (atlas shards: per layer "MIN:MAX" of the
 * textures each read, or "-"), formatted as vt-tiles --layout writes its "range" key. Returns 1
 * with out filled when some layer has a range, 0 when none has, -1 when a shard lacks the key or
 * a list is malformed or longer than cap. */
int vt_shard_merge_range(const struct vt_shard_merge *m, char *out, size_t cap);

/* True for the metadata keys a complete shard set drops: VT_SHARD_KEY, and when vt_tiles_build is
 * true (shards of vt-tiles --shard) every VT_SHARD_KEY ".*" key as well. */
bool vt_shard_merge_drops_key(const char *key, bool vt_tiles_build);

/* Checks that the inputs, of which at least one has VT_SHARD_BUILD_KEY, are the complete shard
 * set of one `vt-tiles --shard` build: every input a shard of it, each of 1/N .. N/N once, the
 * same metadata apart from VT_SHARD_KEY. VTS_ERR_BAD_INPUT with one line naming the missing,
 * duplicate or foreign shard otherwise. */
int vt_shard_merge_check(const struct vt_shard_merge *m, struct vts_error *err);

/* The options of the passes after the shards' first one, from the first input's layer table and
 * metadata: fills *o (resume_input pointing to *input, which receives the original input's
 * description) and *build; the caller sets threads, temp_dir, emit, progress and user. Returns 0,
 * or VTS_ERR_BAD_INPUT for a store that is not a well-formed vt-tiles shard. */
int vt_shard_merge_options(const struct vt_shard_merge *m, struct vt_pyramid_options *o,
                           struct vt_source_info *input, struct vt_shard_build *build,
                           struct vts_error *err);

/* Assembles the carried texels of the shards (layer 1, level levels_per_pass: for each tile, the
 * first input that stores it) into the resumed level of the build *o (options from
 * vt_shard_merge_options(); the build must have levels above the carried one). Returns the handle
 * to run (vt_pyramid_resume_run()) and destroy, or NULL with err naming the input and tile (an
 * unreadable or missing carried tile, one of the wrong size). */
struct vt_pyramid_resume *vt_shard_merge_assemble(const struct vt_shard_merge *m,
                                                  const struct vt_pyramid_options *o,
                                                  struct vts_error *err);

/* Without wrap (shard.build carry=seams): the shards built the levels above their first pass but
 * along the seams between parts. Reads their carried texels (layer 1), computes the strips along
 * the seams and emits the tiles no shard could through o->emit (options from
 * vt_shard_merge_options(); worker 0, progress through o->progress). 0, or the first error with
 * err naming the input and tile (an unreadable, missing or wrong-sized carried tile). */
int vt_shard_merge_seams(const struct vt_shard_merge *m, const struct vt_pyramid_options *o,
                         struct vts_error *err);

/* Tiles vt_shard_merge_seams() emits (for progress). */
uint64_t vt_shard_merge_seam_tiles(const struct vt_shard_merge *m,
                                   const struct vt_pyramid_options *o);

#endif
