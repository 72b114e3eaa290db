// The only C++ on the BC path: libsquish behind an extern "C" API. Exceptions stop here (STYLE 8).
#include <squish.h>

#include "internal/vt_squish_shim.h"

static int vt_squish_shim_squish_flags(unsigned flags)
{
    int squish_flags = (flags & VT_SQUISH_SHIM_BC3) ? squish::kDxt5 : squish::kDxt1;
    if (flags & VT_SQUISH_SHIM_ITERATIVE)
        squish_flags |= squish::kColourIterativeClusterFit;
    else if (flags & VT_SQUISH_SHIM_CLUSTER_FIT)
        squish_flags |= squish::kColourClusterFit;
    else
        squish_flags |= squish::kColourRangeFit;
    if (flags & VT_SQUISH_SHIM_WEIGHT_BY_ALPHA)
        squish_flags |= squish::kWeightColourByAlpha;
    return squish_flags;
}

extern "C" int vt_squish_shim_compress_block(const unsigned char *src_rgba8, unsigned flags,
                                             unsigned char *dst)
{
    try {
        // Compress (not CompressImage): one block, no OpenMP region, uniform perceptual metric off
        // (NULL = equal weights, which is what PSNR measures).
        squish::Compress(src_rgba8, dst, vt_squish_shim_squish_flags(flags));
        return 0;
    } catch (...) {
        return -1;
    }
}

extern "C" int vt_squish_shim_decompress_block(const unsigned char *src_block, unsigned flags,
                                               unsigned char *dst_rgba8)
{
    try {
        squish::Decompress(dst_rgba8, src_block, vt_squish_shim_squish_flags(flags));
        return 0;
    } catch (...) {
        return -1;
    }
}
