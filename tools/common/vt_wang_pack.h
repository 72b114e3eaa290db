/* Tool-side access to a Wang pack store (docs/wang.md): its parameters from the metadata, a whole
 * level decoded, the virtual output assembled from it. Shared by vt-info and vt-view. */
#ifndef VT_WANG_PACK_H
#define VT_WANG_PACK_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_image.h"
#include "vt_wang.h"
#include "vts.h"

/* True when the store carries the wang.kind key (a pack, maybe with bad metadata). */
bool vt_wang_pack_is(const struct vts_store *s);

/* Parses the pack metadata of s (vt_wang_info_parse; messages name the store) and checks it
 * against the store: layer 0 u8, level 0 of cols * tile x rows * tile texels. Release info with
 * vt_wang_info_release either way. */
int vt_wang_pack_open(const struct vts_store *s, struct vt_wang_info *info, struct vts_error *err);

/* Decodes level `level` of layer 0 whole (tile contents stitched) into *out (allocated: free with
 * vt_image_release). Returns 0 or the tile reader's status and message. */
int vt_wang_pack_read_level(const struct vts_store *s, uint32_t level, struct vt_image *out,
                            struct vts_error *err);

/* Prints the pack's parameters (text summary lines "wang ...:"). */
void vt_wang_pack_print(const struct vt_wang_info *info);

/* Writes the region (x, y, w, h) in texels of level `level` of the virtual output as a PNG at
 * path (atomically). Returns 0 or a status with a message. */
int vt_wang_pack_write_region(const struct vts_store *s, const struct vt_wang_info *info,
                              uint32_t level, uint64_t x, uint64_t y, uint32_t w, uint32_t h,
                              const char *path, struct vts_error *err);

#endif
