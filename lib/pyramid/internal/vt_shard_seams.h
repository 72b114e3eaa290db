/* Private to lib/pyramid: the levels above the first pass of a sharded build without wrap
 * (docs/sharding.md, "Seams"). Without wrap every texel of a level is a function of the texels of
 * the finer level only (clamped at the level's edges), whatever the block or pass split, so:
 *   - a shard computes, level after level, every texel whose filter window lies inside what it
 *     computed of the finer level (a rectangle that shrinks a few texels per level at the seams
 *     between parts), and emits every tile whose payload lies inside it;
 *   - the merge computes the texels no shard could (thin strips along the seams) and emits the
 *     tiles no shard could (those whose payload crosses a seam);
 *   - for that, each shard carries the texels of its rectangle that the merge reads: the payloads
 *     of those tiles and the filter windows of the strips, a band a tile or two wide along each
 *     seam per level.
 * Both sides derive all of it from the same geometry (the part grid, the tiles, the kernel), per
 * axis: a texel or tile is the shards' when it is in both axes. */
#ifndef VT_SHARD_SEAMS_H
#define VT_SHARD_SEAMS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_pyramid.h"
#include "vt_source.h"

struct vt_float_file;
struct vt_seams;

/* A rectangle of texels of one level. */
struct vt_seams_rect {
    uint32_t x, y, width, height;
};

/* The geometry of build *o (no wrap, levels above the first pass: vt_pyramid_plan().has_next) cut
 * by the part grid: xcuts[0..gx] and ycuts[0..gy] in first-pass blocks (vt_pyramid_part_cuts()).
 * in describes the original input (channels, alpha, premultiplied). *o must outlive the handle.
 * NULL with err on failure (VTS_ERR_NOMEM, VTS_ERR_ARG). Free with vt_seams_destroy(). */
struct vt_seams *vt_seams_create(const struct vt_pyramid_options *o,
                                 const struct vt_source_info *in, const uint32_t *xcuts,
                                 uint32_t gx, const uint32_t *ycuts, uint32_t gy,
                                 struct vts_error *err);
void vt_seams_destroy(struct vt_seams *s);

/* Levels of up to `bytes` (of floats, the whole level) are held in memory, larger ones in unlinked
 * temporary files in o->temp_dir (default 64 MiB; 0: always files). */
void vt_seams_set_memory(struct vt_seams *s, size_t bytes);

/* The carried rectangle of part (col, row) in tile (tx, ty) of level `level` (levels_per_pass ..
 * level_count - 1): false when that part carries nothing there. */
bool vt_seams_carry_rect(const struct vt_seams *s, uint32_t col, uint32_t row, uint32_t level,
                         uint32_t tx, uint32_t ty, struct vt_seams_rect *out);

/* Tiles above the first pass that part (col, row) emits, or the merge (col = row = UINT32_MAX). */
uint64_t vt_seams_tile_count(const struct vt_seams *s, uint32_t col, uint32_t row);

/* The shard of part (col, row): level_k holds its first pass's texels of level levels_per_pass.
 * Builds its levels above it, emitting their tiles through o->emit (worker 0) and counting them in
 * *done, and hands every carried rectangle to o->seam_carry. 0 or the first error. */
int vt_seams_shard_run(struct vt_seams *s, uint32_t col, uint32_t row,
                       struct vt_float_file *level_k, uint64_t *done, struct vts_error *err);

/* Reads the carried rectangle r of part (col, row) at tile (tx, ty) of `level` into texels (rows
 * `stride` floats apart, the input's channels). */
typedef int (*vt_seams_read_fn)(void *user, uint32_t col, uint32_t row, uint32_t level, uint32_t tx,
                                uint32_t ty, const struct vt_seams_rect *r, float *texels,
                                size_t stride, struct vts_error *err);

/* The merge: assembles the carried texels of every part level by level, computes the strips no
 * shard could and emits the tiles no shard could through o->emit (worker 0; progress through
 * o->progress). 0 or the first error. */
int vt_seams_merge_run(struct vt_seams *s, vt_seams_read_fn read, void *user,
                       struct vts_error *err);

#endif
