/* Private to formats/codec: the codec objects the registry in vt_codec.c lists. */
#ifndef VT_CODEC_IMPL_H
#define VT_CODEC_IMPL_H

#include "vt_codec.h"

/* One definition per codec file; adding a codec = one extern here + one line in vt_codec.c. */
extern const struct vt_codec vt_codec_raw;  /* vt_codec_raw.c: tight little-endian rows, exact */
extern const struct vt_codec vt_codec_png;  /* vt_codec_png.c: libpng, u8/u16, 1..4 channels */
extern const struct vt_codec vt_codec_jpeg; /* vt_codec_jpeg.c: TurboJPEG, u8 grey or RGB */
extern const struct vt_codec vt_codec_bc1;  /* vt_codec_bc.c: BC1/DXT1, u8 RGB(A), 1-bit alpha */
extern const struct vt_codec vt_codec_bc3;  /* vt_codec_bc.c: BC3/DXT5, u8 RGBA */
extern const struct vt_codec vt_codec_bc4;  /* vt_codec_rgtc.c: BC4/RGTC1, u8 one channel */
extern const struct vt_codec vt_codec_bc5;  /* vt_codec_rgtc.c: BC5/RGTC2, u8 RG or normal xy */

#endif
