#include "tool_common.h"

#include <stdarg.h>
#include <string.h>
#include <time.h>
#include <unistd.h> /* isatty, optind, optopt */

#include "vt_output_path.h"
#include "vt_version.h"
#include "vts.h"

#define PROGRESS_REDRAW_S 0.2 /* at most 5 redraws per second */

#define LOG_ALIASES     4
#define LOG_MESSAGE_MAX 4096

/* The only mutable globals of the tools: set once from main, read by every message. */
static const char *tool_name = "vtpipe";
static int log_level = VT_LOG_WARN; /* enum vt_log_level; messages above it are dropped */
static struct {
    const char *path, *name;
} log_aliases[LOG_ALIASES]; /* vt_log_alias(); path NULL = unused */

void vt_tool_init(const char *name)
{
    tool_name = name;
}

const char *vt_tool_name(void)
{
    return tool_name;
}

void vt_log_set_level(int level)
{
    log_level = level < VT_LOG_ERROR ? VT_LOG_ERROR : level;
}

int vt_log_get_level(void)
{
    return log_level;
}

void vt_log_alias(const char *path, const char *name)
{
    for (int i = 0; i < LOG_ALIASES; i++)
        if (!log_aliases[i].path) {
            log_aliases[i].path = path;
            log_aliases[i].name = name;
            return;
        }
}

/* The alias whose quoted path starts at s (s[0] is a quote), or -1; *len gets the quoted length. */
static int alias_at(const char *s, size_t *len)
{
    for (int i = 0; i < LOG_ALIASES && log_aliases[i].path; i++) {
        size_t n = strlen(log_aliases[i].path);
        if (n > 0 && strncmp(s + 1, log_aliases[i].path, n) == 0 && s[n + 1] == '\'') {
            *len = n + 2;
            return i;
        }
    }
    return -1;
}

/* Writes text to stderr with every quoted alias path replaced by its quoted name. */
static void put_aliased(const char *text)
{
    for (const char *p = text; *p;) {
        size_t len;
        int i = *p == '\'' ? alias_at(p, &len) : -1;
        if (i >= 0) {
            fprintf(stderr, "'%s'", log_aliases[i].name);
            p += len;
        } else {
            fputc(*p++, stderr);
        }
    }
}

#if defined(__GNUC__) /* lets the compiler check the callers' formats */
static void log_va(const char *fmt, va_list ap) __attribute__((format(printf, 1, 0)));
#endif

static void log_va(const char *fmt, va_list ap)
{
    fprintf(stderr, "%s: ", tool_name);
    if (!log_aliases[0].path) {
        vfprintf(stderr, fmt, ap);
    } else {
        char text[LOG_MESSAGE_MAX];
        vsnprintf(text, sizeof text, fmt, ap);
        put_aliased(text);
    }
    fputc('\n', stderr);
}

void vt_log(int level, const char *fmt, ...)
{
    if (level > log_level)
        return;
    va_list ap;
    va_start(ap, fmt);
    log_va(fmt, ap);
    va_end(ap);
}

int vt_usage_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    log_va(fmt, ap);
    va_end(ap);
    fprintf(stderr, "try '%s --help'\n", tool_name);
    return VT_EXIT_USAGE;
}

int vt_getopt_long(int argc, char *const argv[], const char *optstring,
                   const struct option *longopts)
{
    int index = -1;
    int c = getopt_long(argc, argv, optstring, longopts, &index);
    if (c == -1 || c == '?' || c == ':' || index < 0)
        return c;
    /* The option's own element: the one before its argument when that came separately. */
    int at = optarg && optind >= 2 && optarg == argv[optind - 1] ? optind - 2 : optind - 1;
    const char *name = longopts[index].name;
    size_t len = strcspn(argv[at], "=");
    if (strncmp(argv[at], "--", 2) == 0 && len - 2 == strlen(name) &&
        strncmp(argv[at] + 2, name, len - 2) == 0)
        return c;
    optind = at + 1; /* where vt_usage_getopt_error() looks for the option */
    optopt = 0;
    return '?';
}

int vt_usage_getopt_error(int c, char *const argv[])
{
    const char *arg = optind > 0 ? argv[optind - 1] : "";
    char name[64];
    if (strncmp(arg, "--", 2) == 0) /* long option: its text up to '=' */
        snprintf(name, sizeof name, "%.*s", (int)strcspn(arg, "="), arg);
    else
        snprintf(name, sizeof name, "-%c", optopt ? optopt : '?');
    if (c == ':')
        return vt_usage_error("option '%s' needs an argument", name);
    if (arg[0] == '-' && arg[1] == '-' && optopt != 0) /* glibc: "--flag=value" of a flag */
        return vt_usage_error("option '%s' takes no argument", name);
    return vt_usage_error("unknown option '%s'", name);
}

int vt_parse_u32(const char *s, uint32_t min, uint32_t max, uint32_t *out)
{
    uint64_t v = 0;
    if (!s || !*s)
        return -1;
    for (const char *p = s; *p; p++) {
        if (*p < '0' || *p > '9')
            return -1;
        v = v * 10 + (uint64_t)(*p - '0');
        if (v > max)
            return -1;
    }
    if (v < min)
        return -1;
    *out = (uint32_t)v;
    return 0;
}

int vt_parse_size(const char *s, uint64_t *out)
{
    uint64_t v = 0;
    const char *p = s;
    if (!s || *s < '0' || *s > '9')
        return -1;
    for (; *p >= '0' && *p <= '9'; p++)
        if (__builtin_mul_overflow(v, 10, &v) || __builtin_add_overflow(v, *p - '0', &v))
            return -1;
    unsigned shift = 0;
    switch (*p) {
    case 0:
        break;
    case 'k':
    case 'K':
        shift = 10;
        break;
    case 'm':
    case 'M':
        shift = 20;
        break;
    case 'g':
    case 'G':
        shift = 30;
        break;
    case 't':
    case 'T':
        shift = 40;
        break;
    default:
        return -1;
    }
    if (*p && p[1])
        return -1;
    if (shift && v > (UINT64_MAX >> shift))
        return -1;
    *out = v << shift;
    return 0;
}

int vt_parse_u32_pair(const char *s, char sep, uint32_t min, uint32_t max, uint32_t *a, uint32_t *b)
{
    char first[16];
    const char *mid = s ? strchr(s, sep) : NULL;
    if (!mid || (size_t)(mid - s) >= sizeof first)
        return -1;
    memcpy(first, s, (size_t)(mid - s));
    first[mid - s] = '\0';
    uint32_t va, vb;
    if (vt_parse_u32(first, min, max, &va) != 0 || vt_parse_u32(mid + 1, min, max, &vb) != 0)
        return -1;
    *a = va;
    *b = vb;
    return 0;
}

int vt_check_output(const char *output, const char *const *inputs, size_t n)
{
    struct vts_error err = {0};
    if (output && vt_output_path_check(output, inputs, n, &err) != 0) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        return VT_EXIT_BAD_INPUT;
    }
    return -1;
}

int vt_refuse_terminal(const char *path, int fd, const char *what)
{
    if (!vt_output_path_is_stdio(path) || !isatty(fd))
        return -1;
    if (fd == STDIN_FILENO)
        vt_log(VT_LOG_ERROR,
               "not reading %s from a terminal: redirect standard input or give a file name", what);
    else
        vt_log(VT_LOG_ERROR,
               "not writing %s to a terminal: redirect standard output or give a file name", what);
    return VT_EXIT_USAGE;
}

void vt_print_version(FILE *f)
{
    fprintf(f, "%s (vtpipe) %s\n", tool_name, VT_VERSION_STRING);
    fprintf(f, ".vts format %d.%d (reads %d.x)\n", VTS_FORMAT_MAJOR, VTS_FORMAT_MINOR,
            VTS_FORMAT_MAJOR);
}

int vt_common_option(int c, int version_opt, const char *usage_text, char *const argv[])
{
    if (c == 'q') {
        vt_log_set_level(VT_LOG_ERROR);
    } else if (c == 'v') {
        vt_log_set_level(vt_log_get_level() + 1);
    } else if (c == 'h') {
        fputs(usage_text, stdout);
        return VT_EXIT_OK;
    } else if (c == version_opt) {
        vt_print_version(stdout);
        return VT_EXIT_OK;
    } else {
        return vt_usage_getopt_error(c, argv);
    }
    return -1;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

void vt_progress_start(struct vt_progress *p, const char *what, const char *unit, uint64_t total)
{
    *p = (struct vt_progress){.what = what, .unit = unit, .total = total};
    p->enabled = log_level >= VT_LOG_WARN && isatty(STDERR_FILENO);
    p->start_s = now_s();
    p->last_draw_s = p->start_s;
}

void vt_progress_update(struct vt_progress *p, uint64_t done)
{
    if (!p->enabled)
        return;
    double t = now_s();
    if (t - p->last_draw_s < PROGRESS_REDRAW_S)
        return;
    p->last_draw_s = t;
    double rate = (double)done / (t - p->start_s);
    unsigned long eta = 0;
    if (rate > 0 && done < p->total)
        eta = (unsigned long)((double)(p->total - done) / rate + 0.5);
    char mp[32] = "";
    if (p->megapixels_per_unit > 0)
        snprintf(mp, sizeof mp, " (%.1f MP/s)", rate * p->megapixels_per_unit);
    fprintf(stderr, "\r\033[K%s: %s %llu/%llu %s (%.0f%%), %.0f %s/s%s, ETA %lu:%02lu", tool_name,
            p->what, (unsigned long long)done, (unsigned long long)p->total, p->unit,
            p->total ? 100.0 * (double)done / (double)p->total : 100.0, rate, p->unit, mp, eta / 60,
            eta % 60);
    fflush(stderr);
    p->drawn = true;
}

void vt_progress_end(struct vt_progress *p)
{
    if (p->drawn)
        fputs("\r\033[K", stderr);
    p->drawn = false;
}
