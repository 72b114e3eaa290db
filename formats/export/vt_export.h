/* Export of one layer of a .vts store to the tile layouts web viewers read: Deep Zoom (.dzi +
 * NAME_files/L/x_y.ext), IIIF Image API 3.0 level-0 static tiles (info.json +
 * {region}/{size}/0/default.ext) and XYZ (z/x/y.ext), PNG or JPEG tiles; an index.html that opens
 * the export with OpenSeadragon. Streaming and out of core: a worker holds one block of output
 * tiles at a time; the store is read tile by tile. Specification: docs/cli/vt-export.md. */
#ifndef VT_EXPORT_H
#define VT_EXPORT_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_codec.h"
#include "vt_error.h"
#include "vts.h"

enum vt_export_layout {
    VT_EXPORT_DZI = 0,  /* Deep Zoom: level 0 is 1x1, the top level the full image */
    VT_EXPORT_IIIF = 1, /* IIIF Image API 3.0, level 0 (static tiles) */
    VT_EXPORT_XYZ = 2,  /* z/x/y: z 0 is one tile; tiles padded to the full edge with zeros */
};

/* Parses "dzi", "iiif", "xyz"; returns 0 or VTS_ERR_ARG. */
int vt_export_layout_parse(const char *name, enum vt_export_layout *out);

/* What to export and how. Zero-initialise, then set. */
struct vt_export_params {
    enum vt_export_layout layout;
    uint32_t layer;
    uint32_t tile_px;    /* edge of an exported tile without overlap, 1..VT_EXPORT_MAX_TILE */
    uint32_t overlap_px; /* DZI only: texels each tile repeats from its neighbours */
    const struct vt_codec *codec; /* png or jpeg (vt_codec_find) */
    struct vt_codec_params codec_params;
    const char *name;    /* DZI: NAME.dzi and NAME_files/ */
    const char *iiif_id; /* IIIF: the "id" of info.json (the export's base URL) */
    unsigned threads;    /* 1..256 */
    /* Optional: called on the calling thread about 5 times a second and at the end with the
     * tiles written so far; a non-zero return cancels the run (VTS_ERR_CANCELLED). */
    int (*progress)(void *ctx, uint64_t done, uint64_t total);
    void *progress_ctx;
};

#define VT_EXPORT_MAX_TILE    4096u
#define VT_EXPORT_MAX_OVERLAP 256u

/* The coarsest level of the store is read whole to make the coarser export levels (a store built
 * with every level has it within one tile); vt_export_check() refuses a store whose coarsest level
 * has more texels than this. */
#define VT_EXPORT_MAX_COARSE_TEXELS (1ull << 26)

/* Checks that p can export store: the layer exists (VTS_ERR_RANGE), its samples are u8 or u16
 * and fit the codec (jpeg: u8 or u16, 1 or 3 channels; png: 1..4 channels), the tile and overlap
 * sizes, the store's coarsest level. VTS_ERR_UNSUPPORTED with a one-line reason otherwise. */
int vt_export_check(const struct vts_store *store, const struct vt_export_params *p,
                    struct vts_error *err);

/* Tiles the export of store will hold (for progress). */
uint64_t vt_export_tile_count(const struct vts_store *store, const struct vt_export_params *p);

/* Writes the export into dir, an existing empty directory (vt_export_dir_create()): the descriptor
 * (NAME.dzi, info.json) and every tile. Returns 0, or a negative status with a message naming the
 * store, level and tile or the file that could not be written; dir is then partially filled. */
int vt_export_run(const struct vts_store *store, const struct vt_export_params *p, const char *dir,
                  struct vts_error *err);

/* Writes dir/index.html, a page that opens the export with OpenSeadragon from a copy of
 * osd_js (openseadragon.min.js) placed next to it as dir/openseadragon.min.js: the page works
 * offline, from file://. Returns 0 or a negative status with a message. */
int vt_export_write_html(const struct vts_store *store, const struct vt_export_params *p,
                         const char *dir, const char *osd_js, struct vts_error *err);

/* Staging of the output directory: a failed or killed run never leaves a half-made export under
 * the final name. */
struct vt_export_dir {
    char final_path[4096];
    char tmp_path[4096]; /* final_path.tmp-XXXXXX, next to it */
};

/* Refuses final_path when it exists and is not a directory, or is a non-empty directory and
 * !force (VTS_ERR_ARG "'out': exists and is not empty (--force replaces it)"), or when it contains
 * the file at keep (the store: VTS_ERR_ARG); then creates the staging directory. */
int vt_export_dir_create(struct vt_export_dir *d, const char *final_path, bool force,
                         const char *keep, struct vts_error *err);

/* Moves the staging directory to the final name; a directory that was there (empty, or replaced
 * with force) is removed after the move. Returns 0 or VTS_ERR_IO with a message. */
int vt_export_dir_commit(struct vt_export_dir *d, struct vts_error *err);

/* Removes the staging directory and everything in it (after a failure). Accepts a d whose create
 * failed. */
void vt_export_dir_abort(struct vt_export_dir *d);

#endif
