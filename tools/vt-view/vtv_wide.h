/* vt-view: layers of 16-bit and float samples (docs/viewer.md, "Ranges and ramps"). u8 layers are
 * handed to GL as RGBA8 (vtv_loader); u16, f16 and f32 layers keep their channel count and
 * precision: u16 as normalised 16-bit, f16 as half floats, f32 as floats, except sRGB u16 layers,
 * decoded to linear f32 (GL has no 16-bit sRGB format; the frame then encodes sRGB as for an
 * sRGB8 layer). The values reach the shader as they are; --range maps them to [0,1] there. */
#ifndef VTV_WIDE_H
#define VTV_WIDE_H

#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_image.h"
#include "vts.h"

/* What a loaded tile holds for one layer: sample type (enum vts_sample) and channels. */
struct vtv_texel_format {
    uint32_t sample;   /* VTS_SAMPLE_U8: RGBA8 (channels 4) */
    uint32_t channels; /* 1..4 */
};

/* The format a layer is handed over in (see above); BC layers uploaded compressed are not asked. */
void vtv_wide_format(const struct vts_layer *info, struct vtv_texel_format *out);

size_t vtv_wide_texel_bytes(const struct vtv_texel_format *f);

/* A decoded tile of a layer whose format is not RGBA8 (img: the layer's channels and sample) into
 * dst, rows tight, in the layer's vtv_wide_format. */
void vtv_wide_convert(const struct vt_image *img, const struct vts_layer *info, void *dst);

/* The smallest and largest finite values of layer (every channel but alpha) over the content of
 * the coarsest level's tiles: the default --range of a float layer. Empty tiles are skipped; with
 * no finite value, [0, 1]. 0 or the read/decode error. */
int vtv_wide_estimate_range(const struct vts_store *s, uint32_t layer, float range[2],
                            struct vts_error *err);

#endif
