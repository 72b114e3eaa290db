/* Unit tests of lib/offset/vt_uv_text.c: the fast paths give exactly what strtod and printf("%.*f")
 * give.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_test.h"
#include "vt_text.h"
#include "vt_uv_text.h"

static uint64_t state = 0x9e3779b97f4a7c15ULL;

static uint64_t next_random(void)
{
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return state;
}

static double unit_random(void)
{
    return (double)(next_random() >> 11) * (1.0 / 9007199254740992.0);
}

static bool same_double(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* vt_uv_parse must accept what vt_text_double accepts, with the same value. */
static int parse_agrees(const char *s)
{
    double a = 12345, b = 12345;
    bool ok_a = vt_uv_parse(s, strlen(s), &a);
    bool ok_b = vt_text_double(s, &b);
    if (ok_a != ok_b || (ok_a && !same_double(a, b))) {
        fprintf(stderr, "parse '%s': fast %d %.17g, strtod %d %.17g\n", s, ok_a, a, ok_b, b);
        return 0;
    }
    return 1;
}

static void parse_matches_strtod_on_edge_cases(void)
{
    static const char *const cases[] = {
        "0",
        "-0",
        "+0",
        "0.0",
        "-0.0",
        "1",
        "1.",
        ".5",
        "-.5",
        "+1.25",
        "0.1",
        "0.3",
        "0.123456",
        "1e5",
        "1E5",
        "1e-5",
        "2.5e+3",
        "1e22",
        "1e23",
        "1e-22",
        "1e-23",
        "9007199254740992",
        "9007199254740993",
        "9007199254740995",
        "1234567890123456789",
        "12345678901234567890",
        "0.12345678901234567890123",
        "0.00000000000000000000000000001",
        "1e-400",
        "1e400",
        "4.9406564584124654e-324",
        "2.2250738585072014e-308",
        "1.7976931348623157e308",
        "1.7976931348623159e308",
        "0e99999999",
        "nan",
        "NaN",
        "inf",
        "-inf",
        "infinity",
        "0x1p3",
        "1e",
        "1e+",
        "e5",
        ".",
        "-",
        "+",
        "",
        "1.2.3",
        "1-2",
        "--1",
        "1e5.5",
        "0.5 ",
        " 0.5",
        "0,5",
        "0.000000953674316406250",
        "0.99999999999999994",
        "0.99999999999999995",
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        VT_CHECK(parse_agrees(cases[i]));
}

static void parse_matches_strtod_on_random_decimals(void)
{
    char buf[64];
    int bad = 0;
    for (int i = 0; i < 200000 && bad < 10; i++) {
        uint64_t r = next_random();
        int digits = (int)(r % 20) + 1;
        int point = (int)((r >> 8) % (uint64_t)(digits + 1));
        int len = 0;
        if ((r >> 16) & 1)
            buf[len++] = '-';
        for (int d = 0; d < digits; d++) {
            if (d == point)
                buf[len++] = '.';
            buf[len++] = (char)('0' + next_random() % 10);
        }
        if ((r >> 17) % 4 == 0)
            len += snprintf(buf + len, sizeof buf - (size_t)len, "e%d", (int)((r >> 20) % 61) - 30);
        buf[len] = '\0';
        if (!parse_agrees(buf))
            bad++;
    }
    VT_CHECK_INT_EQ(bad, 0);
}

/* printf("%.*f") with trailing zeros and point removed, "-0" as "0". */
static void reference_format(double x, unsigned digits, char *buf, size_t cap)
{
    int n = snprintf(buf, cap, "%.*f", (int)digits, x);
    if (strchr(buf, '.')) {
        while (n > 0 && buf[n - 1] == '0')
            n--;
        if (n > 0 && buf[n - 1] == '.')
            n--;
    }
    buf[n] = '\0';
    if (strcmp(buf, "-0") == 0)
        strcpy(buf, "0");
}

static int format_agrees(double x, unsigned digits)
{
    char a[VT_UV_FORMAT_SIZE], b[VT_UV_FORMAT_SIZE];
    size_t n = vt_uv_format(x, digits, a);
    reference_format(x, digits, b, sizeof b);
    if (strcmp(a, b) != 0 || n != strlen(a)) {
        fprintf(stderr, "format %.17g with %u digits: fast '%s', printf '%s'\n", x, digits, a, b);
        return 0;
    }
    return 1;
}

static void format_matches_printf(void)
{
    static const double cases[] = {0.0,
                                   -0.0,
                                   1.0,
                                   0.5,
                                   1.5,
                                   2.5,
                                   0.125,
                                   0.375,
                                   -0.125,
                                   0.1,
                                   1.0 / 3.0,
                                   9.9999999999999999,
                                   9.999999999,
                                   1e-300,
                                   4.9406564584124654e-324,
                                   -1e-20,
                                   1048575.5 / 1048576.0,
                                   0.5 / 1048576.0,
                                   1.0 - 0.5 / 16777216.0,
                                   12.75,
                                   -12345.678,
                                   1e300};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        for (unsigned d = 0; d <= VT_UV_MAX_DIGITS; d++)
            VT_CHECK(format_agrees(cases[i], d));
    int bad = 0;
    for (int i = 0; i < 300000 && bad < 10; i++) {
        uint64_t r = next_random();
        double x = unit_random();
        if (r % 4 == 1)
            x = x * 20 - 10;
        else if (r % 4 == 2) /* texel centres and edges of a 2^24 atlas */
            x = (double)((r >> 8) % (1u << 25)) / (double)(1u << 25);
        else if (r % 4 == 3) /* values with exact decimal ties */
            x = (double)((r >> 8) % 100000) / 1024.0 / 128.0;
        if (!format_agrees(x, (unsigned)((r >> 40) % (VT_UV_MAX_DIGITS + 1))))
            bad++;
    }
    VT_CHECK_INT_EQ(bad, 0);
}

static void format_trims_and_round_trips(void)
{
    char buf[VT_UV_FORMAT_SIZE];
    vt_uv_format(0.5, 10, buf);
    VT_CHECK(strcmp(buf, "0.5") == 0);
    vt_uv_format(1.0, 10, buf);
    VT_CHECK(strcmp(buf, "1") == 0);
    vt_uv_format(-0.0, 10, buf);
    VT_CHECK(strcmp(buf, "0") == 0);
    vt_uv_format(-1e-12, 10, buf);
    VT_CHECK(strcmp(buf, "0") == 0);
    vt_uv_format(0.5 / 1048576.0, 10, buf);
    VT_CHECK(strcmp(buf, "0.0000004768") == 0);
    vt_uv_format(2.5, 0, buf);
    VT_CHECK(strcmp(buf, "2") == 0); /* ties to even, as printf */
    /* 17 decimals of a value in [0, 1) read back to the same double */
    int bad = 0;
    for (int i = 0; i < 100000; i++) {
        double x = unit_random(), back;
        size_t n = vt_uv_format(x, 17, buf);
        if (!vt_uv_parse(buf, n, &back) || fabs(back - x) > 0x1p-53)
            bad++;
    }
    VT_CHECK_INT_EQ(bad, 0);
}

int main(void)
{
    VT_RUN(parse_matches_strtod_on_edge_cases);
    VT_RUN(parse_matches_strtod_on_random_decimals);
    VT_RUN(format_matches_printf);
    VT_RUN(format_trims_and_round_trips);
    return vt_test_main_result();
}
