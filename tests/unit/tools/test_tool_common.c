/* Unit tests of tools/tool_common: number parsing, abbreviation-free getopt_long. */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "tool_common.h"
#include "vt_test.h"

static void parse_u32_accepts_numbers_in_range(void)
{
    uint32_t v = 99;
    VT_CHECK_INT_EQ(vt_parse_u32("0", 0, 10, &v), 0);
    VT_CHECK_INT_EQ(v, 0);
    VT_CHECK_INT_EQ(vt_parse_u32("007", 0, 10, &v), 0);
    VT_CHECK_INT_EQ(v, 7);
    VT_CHECK_INT_EQ(vt_parse_u32("4294967295", 0, UINT32_MAX, &v), 0);
    VT_CHECK_INT_EQ(v, UINT32_MAX);
}

static void parse_u32_rejects_junk_and_range(void)
{
    const char *bad[] = {"",   "-1",   "+1",  " 1",         "1 ",
                         "1x", "0x10", "1.5", "4294967296", "99999999999999999999999"};
    uint32_t v = 42;
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        VT_CHECK_INT_EQ(vt_parse_u32(bad[i], 0, UINT32_MAX, &v), -1);
    VT_CHECK_INT_EQ(vt_parse_u32("11", 0, 10, &v), -1);
    VT_CHECK_INT_EQ(vt_parse_u32("4", 5, 10, &v), -1);
    VT_CHECK_INT_EQ(vt_parse_u32(NULL, 0, 10, &v), -1);
    VT_CHECK_INT_EQ(v, 42); /* untouched on failure */
}

static void parse_u32_pair_splits_at_the_separator(void)
{
    uint32_t a = 0, b = 0;
    VT_CHECK_INT_EQ(vt_parse_u32_pair("3,17", ',', 0, 100, &a, &b), 0);
    VT_CHECK_INT_EQ(a, 3);
    VT_CHECK_INT_EQ(b, 17);
    VT_CHECK_INT_EQ(vt_parse_u32_pair("300x200", 'x', 1, 1000, &a, &b), 0);
    VT_CHECK_INT_EQ(a * 1000 + b, 300200);
    const char *bad[] = {"3", "3,", ",3", "3,4,5", "3;4", "a,b", "3,101", "", "3 ,4"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        VT_CHECK_INT_EQ(vt_parse_u32_pair(bad[i], ',', 0, 100, &a, &b), -1);
}

/* Runs vt_getopt_long over the space-separated words of line (argv[0] included) and writes the
 * sequence of results to out; *last receives argv[optind - 1] at the end. */
static void getopt_results(const char *line, char *out, char *last, size_t last_cap)
{
    static const struct option opts[] = {{"verbose", no_argument, NULL, 'v'},
                                         {"extract", required_argument, NULL, 'e'},
                                         {NULL, 0, NULL, 0}};
    char buf[128], *argv[16];
    int argc = 0, c;
    snprintf(buf, sizeof buf, "%s", line);
    for (char *w = strtok(buf, " "); w && argc < 15; w = strtok(NULL, " "))
        argv[argc++] = w;
    argv[argc] = NULL;
    optind = 0; /* glibc: full reinitialisation */
    opterr = 0;
    while ((c = vt_getopt_long(argc, argv, ":ve:", opts)) != -1)
        *out++ = (char)c;
    *out = '\0';
    snprintf(last, last_cap, "%s", optind > 0 ? argv[optind - 1] : "");
}

static void getopt_long_refuses_abbreviations(void)
{
    char out[16], last[32];
    getopt_results("t --verbose --extract 1 --extract=2 -v", out, last, sizeof last);
    VT_CHECK(strcmp(out, "veev") == 0);
    getopt_results("t --verb", out, last, sizeof last);
    VT_CHECK(strcmp(out, "?") == 0);
    VT_CHECK(strcmp(last, "--verb") == 0); /* where vt_usage_getopt_error() looks */
    getopt_results("t --ext 3", out, last, sizeof last);
    VT_CHECK(strcmp(out, "?") == 0);
    VT_CHECK(strcmp(last, "--ext") == 0);
    getopt_results("t --ext=3", out, last, sizeof last);
    VT_CHECK(strcmp(out, "?") == 0);
    getopt_results("t --extract", out, last, sizeof last);
    VT_CHECK(strcmp(out, ":") == 0);
}

int main(void)
{
    vt_tool_init("test_tool_common");
    VT_RUN(parse_u32_accepts_numbers_in_range);
    VT_RUN(parse_u32_rejects_junk_and_range);
    VT_RUN(parse_u32_pair_splits_at_the_separator);
    VT_RUN(getopt_long_refuses_abbreviations);
    return vt_test_main_result();
}
