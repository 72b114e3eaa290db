/* Mip filtering: 2:1 reduction kernels, conversions between stored samples and the float working
 * space (linear light, premultiplied alpha, normals in [-1,1]), and normal renormalisation. */
#ifndef VT_FILTER_H
#define VT_FILTER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"

enum vt_filter_kind {
    VT_FILTER_BOX = 0,      /* 2x2 average: exact, fastest, slightly blurry and aliasing */
    VT_FILTER_TRIANGLE = 1, /* tent over 4x4 texels (bilinear-like), smoother */
    VT_FILTER_LANCZOS3 = 2, /* windowed sinc, 3 lobes (12x12 texels): sharpest, may ring */
    VT_FILTER_KAISER = 3,   /* Kaiser-windowed sinc (alpha 4, width 3): sharp, less ringing */
    /* Selections (docs/filters.md, "Selections"): each coarser texel is one of the values of the
     * 2x2 finer texels it covers (per texel, or per channel for min/max), never a mix. */
    VT_FILTER_NEAREST = 4, /* the top-left texel of the 2x2 */
    VT_FILTER_MODE = 5,    /* the most frequent texel of the 2x2; ties: the first in the order
                              top-left, top-right, bottom-left, bottom-right */
    VT_FILTER_MIN = 6,     /* per channel, the smallest of the 2x2 (NaN only if all are) */
    VT_FILTER_MAX = 7,     /* per channel, the largest of the 2x2 (NaN only if all are) */
};

/* Parses "box", "triangle", "lanczos3", "kaiser", "nearest", "mode", "min", "max"; returns 0 or
 * VTS_ERR_ARG. */
int vt_filter_parse(const char *name, enum vt_filter_kind *out);
const char *vt_filter_name(enum vt_filter_kind kind);

/* True for the selections (nearest, mode, min, max): every output value is one of the input's
 * working values, so stored values survive exactly when the stored sample is kept. */
bool vt_filter_is_selection(enum vt_filter_kind kind);

#define VT_KERNEL_MAX_TAPS 16

/* Taps of a 2:1 reduction: output texel i of the coarser level is the weighted sum of texels
 * 2i + first .. 2i + first + count - 1 of the finer level. Weights sum to 1 (float). A selection
 * has the box's taps (first 0, count 2) and reads them without weights. */
struct vt_kernel {
    enum vt_filter_kind kind;
    int first;
    int count;
    float weights[VT_KERNEL_MAX_TAPS];
};

void vt_kernel_init(struct vt_kernel *k, enum vt_filter_kind kind);

/* Finer-level texels needed beyond a reduced block on each side: a block of output texels
 * [a, b) reads finer texels [2a - margin, 2b + margin). */
uint32_t vt_kernel_margin(const struct vt_kernel *k);

/* How stored texels map to the working space. */
struct vt_pixel_mode {
    uint32_t channels; /* 1..4 */
    uint32_t colour;   /* enum vts_colour: srgb colour channels are linearised; normal: xyz
                          mapped from [0,1] to [-1,1]; linear and data unchanged */
    bool alpha;        /* last channel is alpha: colour channels are premultiplied in the working
                          space (not for data) */
};

/* Converts n texels from a stored sample type (enum vts_sample; u8/u16 are normalised) to
 * working floats (n * channels floats). */
void vt_filter_to_working(const struct vt_pixel_mode *m, uint32_t sample, const void *src,
                          float *dst, size_t n);

/* Converts n working texels back: unpremultiplies (alpha 0 gives colour 0), linear -> sRGB,
 * normals [-1,1] -> [0,1], clamps to [0,1] for u8/u16 and rounds to nearest (correctly rounded for
 * sRGB u8: the code whose linear interval contains the value); f16 rounds to nearest even. */
void vt_filter_from_working(const struct vt_pixel_mode *m, uint32_t sample, const float *src,
                            void *dst, size_t n);

/* Working-space pixels of a rectangle of one level, in that level's texel coordinates. */
struct vt_fregion {
    int64_t x0, y0;         /* level coordinates of px[0] */
    uint32_t width, height; /* texels */
    uint32_t channels;
    float *px; /* width * height * channels, rows top to bottom, owned by caller */
};

/* Edge behaviour of a level. Clamp: a position outside [0, size) reads the nearest edge texel.
 * Wrap: positions are not changed here (the caller reads level 0 modulo its size). */
struct vt_edges {
    uint32_t level_w, level_h; /* size of the finer (source) level */
    bool wrap_x, wrap_y;
};

/* Computes every texel of dst (a region of the coarser level) from src (a region of the finer
 * level) with kernel k: dst texel X reads finer texels 2X' + first ... where X' = X clamped to
 * [0, ceil(level_w / 2)) unless wrap_x (same for Y); each finer position is clamped to
 * [0, level_w) unless wrap. Every position read must lie inside src: otherwise VTS_ERR_ARG and
 * dst is unspecified (a caller bug). Separable (horizontal then vertical); scratch must hold
 * scratch_floats >= vt_filter_reduce_scratch(k, src, dst) floats. Deterministic: the same
 * inputs give the same bits whatever the region split. A selection kernel (vt_filter_is_selection)
 * reads the same 2x2 finer texels per coarser texel (clamped or wrapped alike) and picks among
 * them; it reads src directly (no scratch). */
int vt_filter_reduce(const struct vt_kernel *k, const struct vt_edges *edges,
                     const struct vt_fregion *src, struct vt_fregion *dst, float *scratch,
                     size_t scratch_floats, struct vts_error *err);
size_t vt_filter_reduce_scratch(const struct vt_kernel *k, const struct vt_fregion *src,
                                const struct vt_fregion *dst);

/* Stored texels of a region (the input's own samples, before any conversion). */
struct vt_stored_rows {
    const void *px;                   /* the region's first row */
    size_t stride;                    /* bytes between rows */
    uint32_t sample;                  /* enum vts_sample */
    const struct vt_pixel_mode *mode; /* how they map to the working space */
};

/* vt_filter_reduce() from stored texels: src gives the region's position and size (its px is not
 * read), stored its samples; each finer row is converted (vt_filter_to_working) once, just before
 * its horizontal pass, into a row of scratch. Gives the same bits as converting the whole region
 * first and calling vt_filter_reduce(), without a float copy of it. scratch must hold
 * vt_filter_reduce_stored_scratch(k, src, dst) floats. */
int vt_filter_reduce_stored(const struct vt_kernel *k, const struct vt_edges *edges,
                            const struct vt_fregion *src, const struct vt_stored_rows *stored,
                            struct vt_fregion *dst, float *scratch, size_t scratch_floats,
                            struct vts_error *err);
size_t vt_filter_reduce_stored_scratch(const struct vt_kernel *k, const struct vt_fregion *src,
                                       const struct vt_fregion *dst);

/* Renormalises the xyz of every texel of a normal-map region to unit length (zero vectors
 * become (0,0,1)). */
void vt_filter_renormalize(struct vt_fregion *r);

#endif
