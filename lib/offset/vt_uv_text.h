/* Exact decimal text for texture coordinates: a parser and a fixed-point printer that are as exact
 * as strtod and printf("%.*f") (glibc's are correctly rounded) but several times faster on the
 * short numbers OBJ files hold. Each takes a fast path only when it can prove the result exact and
 * falls back to strtod / snprintf otherwise, so the results never differ. Needs LC_NUMERIC "C". */
#ifndef VT_UV_TEXT_H
#define VT_UV_TEXT_H

#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Largest number of digits after the point vt_uv_format() takes, and the buffer it needs. */
#define VT_UV_MAX_DIGITS  17
#define VT_UV_FORMAT_SIZE 352

/* Parses the n bytes at s as one finite decimal number (the whole of it: [+-]digits[.digits][e..],
 * no nan, inf or hex), the same set vt_obj's reader accepts, into the correctly rounded double.
 * Returns false (and leaves *out alone) for anything else. */
bool vt_uv_parse(const char *s, size_t n, double *out);

/* Writes x rounded to `digits` decimal places (round half to even on the exact binary value, like
 * printf("%.*f")) into buf (VT_UV_FORMAT_SIZE bytes), trailing zeros after the point removed and
 * the point too when nothing follows it ("0.5", "1", "0.0000019073"); "-0" is written "0". x must
 * be finite and digits <= VT_UV_MAX_DIGITS. Returns the length written (NUL-terminated). */
size_t vt_uv_format(double x, unsigned digits, char *buf);

#ifdef __cplusplus
}
#endif
#endif
