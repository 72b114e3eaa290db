/* Mip filtering, part one (vt_filter.h): filter names, the 2:1 kernels and normal
 * renormalisation. The sample conversions are in vt_filter_convert.c, the reduction in
 * vt_filter_reduce.c; the three files share the public header only.
 *
 * Numerics: kernel weights are computed and normalised in double, then stored as float. */
#include "vt_filter.h"

#include <assert.h>
#include <math.h>
#include <string.h>

/* ---- names ---- */

static const char *const filter_names[] = {"box",     "triangle", "lanczos3", "kaiser",
                                           "nearest", "mode",     "min",      "max"};

int vt_filter_parse(const char *name, enum vt_filter_kind *out)
{
    for (size_t i = 0; name && i < sizeof filter_names / sizeof filter_names[0]; i++) {
        if (strcmp(name, filter_names[i]) == 0) {
            *out = (enum vt_filter_kind)i;
            return 0;
        }
    }
    return VTS_ERR_ARG;
}

const char *vt_filter_name(enum vt_filter_kind kind)
{
    if ((unsigned)kind < sizeof filter_names / sizeof filter_names[0])
        return filter_names[kind];
    return "?";
}

bool vt_filter_is_selection(enum vt_filter_kind kind)
{
    return kind == VT_FILTER_NEAREST || kind == VT_FILTER_MODE || kind == VT_FILTER_MIN ||
           kind == VT_FILTER_MAX;
}

/* ---- kernels ---- */

#define PI           3.14159265358979323846
#define KAISER_ALPHA 4.0
#define SINC_RADIUS  3.0

static double sinc(double x)
{
    if (x == 0.0)
        return 1.0;
    double px = PI * x;
    return sin(px) / px;
}

/* Modified Bessel function of the first kind, order 0, by its power series (converges fast for
 * the arguments we use, |x| <= KAISER_ALPHA). */
static double bessel_i0(double x)
{
    double sum = 1.0, term = 1.0, q = x * x / 4.0;
    for (int k = 1; k < 50; k++) {
        term *= q / ((double)k * k);
        sum += term;
        if (term < sum * 1e-17)
            break;
    }
    return sum;
}

/* The kernel K(x), x in coarser-texel units. */
static double kernel_eval(enum vt_filter_kind kind, double x)
{
    double ax = fabs(x);
    switch (kind) {
    case VT_FILTER_BOX:
    case VT_FILTER_NEAREST: /* selections have the box's taps and use no weights */
    case VT_FILTER_MODE:
    case VT_FILTER_MIN:
    case VT_FILTER_MAX:
        return ax <= 0.5 ? 1.0 : 0.0;
    case VT_FILTER_TRIANGLE:
        return ax < 1.0 ? 1.0 - ax : 0.0;
    case VT_FILTER_LANCZOS3:
        return ax < SINC_RADIUS ? sinc(ax) * sinc(ax / SINC_RADIUS) : 0.0;
    case VT_FILTER_KAISER: {
        if (ax >= SINC_RADIUS)
            return 0.0;
        double r = ax / SINC_RADIUS;
        return sinc(ax) * bessel_i0(KAISER_ALPHA * sqrt(1.0 - r * r)) / bessel_i0(KAISER_ALPHA);
    }
    }
    return 0.0;
}

void vt_kernel_init(struct vt_kernel *k, enum vt_filter_kind kind)
{
    static const int firsts[] = {0, -1, -5, -5};
    static const int counts[] = {2, 4, 12, 12};
    assert((unsigned)kind <= VT_FILTER_MAX);
    memset(k, 0, sizeof *k);
    k->kind = kind;
    /* a selection reads the box's 2x2 taps (its weights are never used) */
    enum vt_filter_kind taps = vt_filter_is_selection(kind) ? VT_FILTER_BOX : kind;
    k->first = firsts[taps];
    k->count = counts[taps];
    assert(k->count <= VT_KERNEL_MAX_TAPS);

    /* Tap t is finer texel j = 2i + first + t, whose centre lies (j + 0.5) - (2i + 1) finer
     * texels from the output centre, i.e. half that in coarser texels. */
    double w[VT_KERNEL_MAX_TAPS], sum = 0.0;
    for (int t = 0; t < k->count; t++) {
        w[t] = kernel_eval(kind, ((double)(k->first + t) - 0.5) / 2.0);
        sum += w[t];
    }
    for (int t = 0; t < k->count; t++)
        k->weights[t] = (float)(w[t] / sum);
}

uint32_t vt_kernel_margin(const struct vt_kernel *k)
{
    int left = -k->first, right = k->first + k->count - 2;
    int m = left > right ? left : right;
    return m > 0 ? (uint32_t)m : 0;
}

/* ---- normals ---- */

void vt_filter_renormalize(struct vt_fregion *r)
{
    uint32_t ch = r->channels;
    if (ch < 3)
        return;
    size_t n = (size_t)r->width * r->height;
    for (size_t i = 0; i < n; i++) {
        float *p = r->px + i * ch;
        float len2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
        if (len2 > 0.0f && len2 < INFINITY) {
            float inv = 1.0f / sqrtf(len2);
            p[0] *= inv;
            p[1] *= inv;
            p[2] *= inv;
        } else {
            p[0] = 0.0f;
            p[1] = 0.0f;
            p[2] = 1.0f;
        }
    }
}
