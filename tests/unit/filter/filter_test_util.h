/* Shared by the lib/filter tests (each includes its own copy): a seeded xorshift generator and
 * the double-precision sRGB references the conversions and reductions are checked against. */
#ifndef FILTER_TEST_UTIL_H
#define FILTER_TEST_UTIL_H

#include <math.h>
#include <stdint.h>

static uint64_t rng_state = 0x9e3779b97f4a7c15u;

static inline uint32_t rng_u32(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (uint32_t)(rng_state >> 16);
}

static inline float rng_unit(void) /* [0, 1) */
{
    return (float)(rng_u32() >> 8) * 0x1p-24f;
}

static inline double ref_srgb_to_linear(double s)
{
    return s <= 0.04045 ? s / 12.92 : pow((s + 0.055) / 1.055, 2.4);
}

static inline double ref_linear_to_srgb(double v)
{
    return v <= 0.0031308 ? v * 12.92 : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

/* The u8 code whose sRGB interval [k - 0.5, k + 0.5] / 255 contains linear_to_srgb(v). */
static inline unsigned ref_srgb_code(float v, unsigned max)
{
    if (!(v > 0.0f))
        return 0;
    if (v >= 1.0f)
        return max;
    return (unsigned)floor(ref_linear_to_srgb(v) * max + 0.5);
}

#endif
