/* vt-view clipmap mode (--clipmap N, docs/viewer.md "Clipmap mode"): the clipmap-style runtime of
 * Ephanov & Coleman (2006) over the same store. Per level an n x n window of tiles around the
 * paging centre (vts_clipmap.h: windows snapped to the tile grid, toroidal slots, front and back
 * windows, the load plan), the plan cut to a per-frame upload budget in bytes, coarsest level
 * first; tiles read through vtv_loader (on the render thread with --sync, else on its threads)
 * and uploaded into one texture array layer per level (vtv_clipmap_gl.h). */
#ifndef VTV_CLIPMAP_H
#define VTV_CLIPMAP_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"
#include "vts.h"
#include "vts_clipmap.h"
#include "vtv_clipmap_gl.h"
#include "vtv_loader.h"

/* What one frame did (the --stats JSON's clipmap keys). */
struct vtv_clipmap_frame {
    uint64_t tiles;           /* tiles uploaded */
    uint64_t bytes;           /* bytes uploaded: tiles * the bytes of one tile's upload */
    uint64_t reads;           /* tiles read and decoded (sync: = tiles) */
    uint32_t strips;          /* strips (front to target at the frame's start) now complete */
    uint32_t levels_complete; /* levels whose front equals their target after the uploads */
    uint64_t first;   /* its uploaded tiles: list[first .. first + tiles) (kept frames only) */
    double centre[2]; /* the paging centre, level-0 texels */
    struct vts_tile_rect front[VTS_MAX_LEVELS]; /* after the uploads */
};

struct vtv_clipmap_options {
    uint32_t n;          /* window edge, tiles */
    uint64_t budget;     /* bytes uploaded per frame at most */
    bool sync;           /* read on the render thread (deterministic) */
    uint32_t threads;    /* loader threads without sync */
    bool centre_fixed;   /* --clipmap-centre X,Y */
    double centre[2];    /* its X, Y (level-0 texels) */
    uint32_t frames_cap; /* frames whose statistics are kept */
    unsigned bc_format;  /* GLenum: the layer's BC blocks uploaded as stored in this compressed
                            format (vtv_render_bc_format; the tile content and border multiples
                            of 4), or 0: texels decoded on the CPU */
    bool rebuild_z;      /* with bc_format, BC5 normal xy: z rebuilt in the shader */
};

struct vtv_clipmap {
    struct vts_clipmap cm;
    const struct vts_store *store;
    uint32_t layer;
    struct vtv_clipmap_options opt;
    struct vtv_loader *loader;
    struct vtv_clipmap_gl gl;
    uint32_t max_tiles;            /* per frame: floor(budget / gl.tile_bytes) */
    struct vts_clipmap_tile *plan; /* max_tiles (sync) or the async queue's capacity */
    uint32_t plan_cap;
    uint64_t *queue_index; /* async submission: tile ids and level, x, y */
    uint32_t *queue_lxy;
    uint64_t *dropped;
    uint8_t *zero; /* an empty tile's upload (zeros) */
    /* statistics of the frames so far */
    struct vtv_clipmap_frame *frames;
    uint32_t frame_count;
    uint32_t (*list)[3]; /* uploaded tiles of all frames: level, x, y */
    size_t list_count, list_cap;
    uint64_t failed; /* tiles that could not be read or decoded, in all */
    char error[512]; /* the first failure's message */
};

/* Sets up the clipmap of layer of store: the arithmetic, the loader and the GL texture (needs a
 * current context), drawn through the display features (vtv_display.h: the shown colour's range,
 * ramp or index colours). Errors (VTS_ERR_ARG: a usage problem, e.g. a budget below one tile;
 * VTS_ERR_LIMIT: too large for this GL) in err. Free with vtv_clipmap_free (also after a failed
 * init). */
int vtv_clipmap_init(struct vtv_clipmap *c, const struct vts_store *store, uint32_t layer,
                     const struct vtv_clipmap_options *opt, unsigned display_features,
                     struct vts_error *err);
void vtv_clipmap_free(struct vtv_clipmap *c);

/* One frame's paging: the targets moved to the windows around the paging centre (cx, cy, level-0
 * texels; --clipmap-centre replaces it), then the plan loaded and uploaded within the budget.
 * Records the frame's statistics (out, and in c->frames for the first frames_cap frames).
 * Returns 0 or VTS_ERR_NOMEM. */
int vtv_clipmap_update(struct vtv_clipmap *c, double cx, double cy, struct vtv_clipmap_frame *out);

#endif
