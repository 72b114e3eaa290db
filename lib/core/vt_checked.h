/* Overflow-checked size arithmetic for every size that comes from a file or an argument. */
#ifndef VT_CHECKED_H
#define VT_CHECKED_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

/* Each stores a op b in *out and returns true, or returns false (and leaves *out unspecified) when
 * the exact result does not fit. */
static inline bool vt_u64_mul(uint64_t a, uint64_t b, uint64_t *out)
{
    return !__builtin_mul_overflow(a, b, out);
}

static inline bool vt_u64_add(uint64_t a, uint64_t b, uint64_t *out)
{
    return !__builtin_add_overflow(a, b, out);
}

static inline bool vt_size_mul(size_t a, size_t b, size_t *out)
{
    return !__builtin_mul_overflow(a, b, out);
}

static inline bool vt_size_add(size_t a, size_t b, size_t *out)
{
    return !__builtin_add_overflow(a, b, out);
}

/* a * b * c, for image byte counts (width * height * bytes per texel). */
static inline bool vt_size_mul3(size_t a, size_t b, size_t c, size_t *out)
{
    size_t ab;
    return vt_size_mul(a, b, &ab) && vt_size_mul(ab, c, out);
}

/* True when [off, off + len) lies inside [0, limit); checks the sum for overflow. */
static inline bool vt_range_within(uint64_t off, uint64_t len, uint64_t limit)
{
    uint64_t end;
    return vt_u64_add(off, len, &end) && end <= limit;
}

/* Makes room for need elements of elem bytes in the array *p of capacity *cap (in elements),
 * doubling from first (or from *cap) with every size checked. Returns true, or false when out of
 * memory or the size overflows (then *p and *cap are unchanged). */
static inline bool vt_array_grow(void **p, size_t *cap, size_t need, size_t elem, size_t first)
{
    if (need <= *cap)
        return true;
    size_t n = *cap ? *cap : first ? first : 1, bytes;
    while (n < need)
        if (!vt_size_mul(n, 2, &n))
            return false;
    if (!vt_size_mul(n, elem, &bytes))
        return false;
    void *q = realloc(*p, bytes);
    if (!q)
        return false;
    *p = q;
    *cap = n;
    return true;
}

#endif
