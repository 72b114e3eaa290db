/* The mip chain of one atlas entry in one layer: the entry's texture (or constant fill) decoded,
 * converted to the layer's format (its channels and sample type), resampled to the entry's size,
 * cut to the entry's crop of its block of copies (repeat_u x repeat_v copies side by side; the
 * whole block without a crop), then reduced level by level in the float working space (linear light
 * for sRGB, premultiplied alpha, renormalised normals) with edges clamped at the crop's rectangle,
 * or wrapped around for a wrap entry. Used by vt_atlas_build.c; see docs/atlas-build.md. */
#ifndef VT_MIP_CHAIN_H
#define VT_MIP_CHAIN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_filter.h"
#include "vt_image.h"
#include "vt_source.h"
#include "vts.h"

/* What the chain holds: the layer's output format and the entry's geometry. */
struct vt_mip_chain_spec {
    uint32_t width, height;     /* one copy, atlas texels at level 0 */
    uint32_t crop_x, crop_y;    /* the rectangle of the block of copies the chain holds: texel */
    uint32_t crop_width;        /* (a, b) of level 0 is texel ((crop_x + a) mod width, (crop_y + */
    uint32_t crop_height;       /* b) mod height) of the resampled texture; sizes >= 1 */
    bool wrap;                  /* reduce with wrap-around edges (a wrap entry: crop = one copy) */
    uint32_t level_count;       /* levels to compute, >= 1 (level l is ceil(size / 2^l)) */
    uint32_t colour_channels;   /* 1 (grey) or 3 (RGB) */
    bool alpha;                 /* an alpha channel follows the colour channels */
    uint32_t colour;            /* enum vts_colour of the layer */
    enum vt_filter_kind filter; /* reduction kernel */
    uint64_t max_pixels;        /* refuse a crop of more texels than this */
    uint32_t sample;            /* enum vts_sample of the layer; 0 = VTS_SAMPLE_U8 */
    bool srgb_source;           /* a float layer of an sRGB layout layer (colour linear): the
                                   colour of integer sources is sRGB-encoded */
};

/* Level l: crop_width / 2^l x crop_height / 2^l rounded up, the spec's sample type,
 * colour_channels + alpha channels. Level 0 holds the texture's texels exactly (inputs of the
 * layer's sample type at scale 1 are copied byte for byte; 8-bit texels in a u16 layer are v *
 * 257). */
struct vt_mip_chain {
    uint32_t level_count;
    struct vt_image levels[VTS_MAX_LEVELS];
    size_t bytes; /* pixel bytes of every level */
};

/* Builds the chain from an opened source whose size must be the entry's size times a power of two
 * (a finer texture: its own mip level k is used; a coarser one: texels are replicated); other
 * sizes are resampled nearest-neighbour. Sources of another sample type are converted to the
 * layer's (vt_mip_chain_convert). Returns 0, VTS_ERR_LIMIT, VTS_ERR_NOMEM or the source's read
 * error. */
int vt_mip_chain_from_source(struct vt_mip_chain *c, const struct vt_mip_chain_spec *s,
                             struct vt_source *src, struct vts_error *err);

/* The same from the source's texels already decoded (raw: the whole image, as read from it). */
int vt_mip_chain_from_image(struct vt_mip_chain *c, const struct vt_mip_chain_spec *s,
                            const struct vt_source_info *in, const struct vt_image *raw,
                            struct vts_error *err);

/* Step 1 alone: rows of the source (raw, any height) converted to the layer's channels and sample
 * type; out is allocated (free with vt_image_release). The atlas build never narrows (a layer's
 * sample type is its widest texture's); a narrower layer would get the sources' normalised values,
 * rounded (no sRGB encoding of float values). Into a u16 layer: 8-bit
 * values v become v * 257 (exact). Into a float layer (whose colour is never sRGB: float data is
 * linear): integer sources of an sRGB texture are decoded to linear light (alpha stays as it is),
 * others become their normalised value; f16 into f32 is exact. */
int vt_mip_chain_convert(const struct vt_mip_chain_spec *s, const struct vt_source_info *in,
                         const struct vt_image *raw, struct vt_image *out, struct vts_error *err);

/* A constant fill (RGBA in 0..1, stored values): every level is one texel. */
int vt_mip_chain_from_fill(struct vt_mip_chain *c, const struct vt_mip_chain_spec *s,
                           const double fill[4], struct vts_error *err);

/* Frees the levels and zeroes *c. Accepts NULL. */
void vt_mip_chain_release(struct vt_mip_chain *c);

/* The working-space mode of a layer format (shared with the compositor's coarse-level mixing). */
void vt_mip_chain_mode(const struct vt_mip_chain_spec *s, struct vt_pixel_mode *out);

/* The spec's sample type (VTS_SAMPLE_U8 for 0). */
uint32_t vt_mip_chain_sample(const struct vt_mip_chain_spec *s);

#endif
