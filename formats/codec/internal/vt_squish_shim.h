/* Private to formats/codec: the extern "C" face of libsquish (C++, namespace squish), used by
 * vt_codec_bc.c. One 4x4 block per call: squish::Compress/Decompress on a block never start OpenMP
 * threads (in Debian's build only squish::CompressImage/DecompressImage have an OpenMP loop), so a
 * worker pool keeps its one thread per job. Every function is thread-safe and never throws. */
#ifndef VT_SQUISH_SHIM_H
#define VT_SQUISH_SHIM_H

#ifdef __cplusplus
extern "C" {
#endif

enum vt_squish_shim_flags {
    VT_SQUISH_SHIM_BC3 = 1 << 0,             /* DXT5, 16 bytes a block; else BC1/DXT1, 8 bytes */
    VT_SQUISH_SHIM_CLUSTER_FIT = 1 << 1,     /* squish's cluster fit; else its range fit */
    VT_SQUISH_SHIM_ITERATIVE = 1 << 2,       /* iterative cluster fit (slowest) */
    VT_SQUISH_SHIM_WEIGHT_BY_ALPHA = 1 << 3, /* weigh colour error by alpha (cluster fits) */
};

/* Compresses one block: src_rgba8 is 16 RGBA texels (64 bytes, row-major); dst receives 8 (BC1) or
 * 16 (BC3) bytes. For BC1, texels with alpha < 128 become the transparent black of the 3-colour
 * mode. Returns 0, or -1 when libsquish threw (nothing else is known to make it fail). */
int vt_squish_shim_compress_block(const unsigned char *src_rgba8, unsigned flags,
                                  unsigned char *dst);

/* Decodes one block (8 or 16 bytes, by VT_SQUISH_SHIM_BC3 in flags) into 16 RGBA texels. Used by
 * the tests to cross-check vt_codec_bc.c's decoder. Returns 0, or -1 when libsquish threw. */
int vt_squish_shim_decompress_block(const unsigned char *src_block, unsigned flags,
                                    unsigned char *dst_rgba8);

#ifdef __cplusplus
}
#endif
#endif
