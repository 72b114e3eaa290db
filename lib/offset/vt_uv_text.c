/* Exact decimal parsing and fixed-point printing of texture coordinates (see vt_uv_text.h).
 *
 * Parsing: a decimal with at most 19 significant digits is an integer m times 10^k. When m fits in
 * the 53-bit significand and |k| <= 22, both m and 10^|k| are exact doubles and one IEEE division
 * or multiplication rounds m * 10^k correctly (Clinger's fast path); anything else goes to strtod.
 * This needs double arithmetic without excess precision (FLT_EVAL_METHOD 0: SSE2, AArch64...).
 *
 * Printing: a finite |x| < 10 is m * 2^-s exactly (m < 2^53). x * 10^d = m * 10^d / 2^s, and
 * m * 10^d < 2^110 fits in a 128-bit integer, so the shift and the remainder give the correctly
 * rounded d-digit value exactly. Other values (or a compiler without __int128) use snprintf. */
#include "vt_uv_text.h"

#include <float.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_text.h"

static const double pow10_double[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                        1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                        1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

static const uint64_t pow10_u64[VT_UV_MAX_DIGITS + 2] = {1ULL,
                                                         10ULL,
                                                         100ULL,
                                                         1000ULL,
                                                         10000ULL,
                                                         100000ULL,
                                                         1000000ULL,
                                                         10000000ULL,
                                                         100000000ULL,
                                                         1000000000ULL,
                                                         10000000000ULL,
                                                         100000000000ULL,
                                                         1000000000000ULL,
                                                         10000000000000ULL,
                                                         100000000000000ULL,
                                                         1000000000000000ULL,
                                                         10000000000000000ULL,
                                                         100000000000000000ULL,
                                                         1000000000000000000ULL};

/* The strtod path: the same acceptance as vt_text_double() (vt_obj's reader). */
static bool parse_slow(const char *s, size_t n, double *out)
{
    char small[128];
    char *tok = small;
    if (n >= sizeof small) {
        tok = malloc(n + 1);
        if (!tok)
            return false;
    }
    memcpy(tok, s, n);
    tok[n] = '\0';
    bool ok = strlen(tok) == n && vt_text_double(tok, out);
    if (tok != small)
        free(tok);
    return ok;
}

static inline bool is_digit(char c)
{
    return c >= '0' && c <= '9';
}

bool vt_uv_parse(const char *s, size_t n, double *out)
{
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD == 0
    const char *p = s, *end = s + n;
    bool neg = false;
    if (p < end && (*p == '+' || *p == '-'))
        neg = *p++ == '-';
    uint64_t mant = 0;
    int significant = 0, seen = 0, exp10 = 0;
    for (; p < end && is_digit(*p); p++, seen++) {
        if (mant == 0 && *p == '0')
            continue;
        if (significant == 19)
            goto slow;
        mant = mant * 10 + (uint64_t)(*p - '0');
        significant++;
    }
    if (p < end && *p == '.') {
        for (p++; p < end && is_digit(*p); p++, seen++) {
            exp10--;
            if (mant == 0 && *p == '0')
                continue;
            if (significant == 19)
                goto slow;
            mant = mant * 10 + (uint64_t)(*p - '0');
            significant++;
        }
    }
    if (seen == 0)
        goto slow;
    if (p < end && (*p == 'e' || *p == 'E')) {
        p++;
        bool eneg = false;
        if (p < end && (*p == '+' || *p == '-'))
            eneg = *p++ == '-';
        if (p == end || !is_digit(*p))
            goto slow;
        int e = 0;
        for (; p < end && is_digit(*p); p++)
            if (e < 100000)
                e = e * 10 + (*p - '0');
        exp10 += eneg ? -e : e;
    }
    if (p != end)
        goto slow;
    if (mant == 0) {
        *out = neg ? -0.0 : 0.0;
        return true;
    }
    if (mant > (UINT64_C(1) << 53) || exp10 < -22 || exp10 > 22)
        goto slow;
    double v = (double)mant;
    v = exp10 < 0 ? v / pow10_double[-exp10] : v * pow10_double[exp10];
    *out = neg ? -v : v;
    return true;
slow:
#endif
    return parse_slow(s, n, out);
}

/* Removes trailing zeros after a point, then the point; turns "-0" into "0". */
static size_t trim_number(char *buf, size_t len)
{
    if (memchr(buf, '.', len)) {
        while (len && buf[len - 1] == '0')
            len--;
        if (len && buf[len - 1] == '.')
            len--;
    }
    buf[len] = '\0';
    if (strcmp(buf, "-0") == 0) {
        buf[0] = '0', buf[1] = '\0';
        len = 1;
    }
    return len;
}

size_t vt_uv_format(double x, unsigned digits, char *buf)
{
    if (digits > VT_UV_MAX_DIGITS)
        digits = VT_UV_MAX_DIGITS;
#if defined(__SIZEOF_INT128__)
    if (x > -10.0 && x < 10.0) {
        uint64_t bits;
        memcpy(&bits, &x, sizeof bits);
        bool neg = (bits >> 63) != 0;
        unsigned biased = (unsigned)(bits >> 52) & 0x7ffu;
        uint64_t m = bits & ((UINT64_C(1) << 52) - 1);
        int e2 = -1074;
        if (biased) {
            m |= UINT64_C(1) << 52;
            e2 = (int)biased - 1075;
        }
        /* |x| < 16 so e2 <= -49: x = m / 2^s with s >= 49 */
        unsigned s = (unsigned)-e2;
        uint64_t q = 0;
        if (s < 128) {
            unsigned __int128 prod = (unsigned __int128)m * pow10_u64[digits];
            unsigned __int128 one = 1;
            q = (uint64_t)(prod >> s);
            unsigned __int128 rem = prod & ((one << s) - 1), half = one << (s - 1);
            if (rem > half || (rem == half && (q & 1)))
                q++;
        } /* else m * 10^d < 2^110 <= 2^(s-1): rounds to 0 */
        size_t len = 0;
        if (q == 0) {
            buf[0] = '0', buf[1] = '\0';
            return 1;
        }
        if (neg)
            buf[len++] = '-';
        uint64_t ip = q / pow10_u64[digits], fp = q % pow10_u64[digits];
        char tmp[24];
        size_t n = 0;
        do {
            tmp[n++] = (char)('0' + ip % 10);
            ip /= 10;
        } while (ip);
        while (n)
            buf[len++] = tmp[--n];
        if (fp) {
            buf[len++] = '.';
            for (unsigned i = digits; i-- > 0;) {
                tmp[i] = (char)('0' + fp % 10);
                fp /= 10;
            }
            unsigned keep = digits;
            while (keep && tmp[keep - 1] == '0')
                keep--;
            memcpy(buf + len, tmp, keep);
            len += keep;
        }
        buf[len] = '\0';
        return len;
    }
#endif
    int n = snprintf(buf, VT_UV_FORMAT_SIZE, "%.*f", (int)digits, x);
    if (n < 0 || n >= VT_UV_FORMAT_SIZE) { /* not reachable for finite x and digits <= 17 */
        buf[0] = '\0';
        return 0;
    }
    return trim_number(buf, (size_t)n);
}
