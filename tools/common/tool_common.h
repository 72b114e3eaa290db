/* Shared by every vtpipe tool: exit codes, leveled logging to stderr, number parsing that rejects
 * junk, usage errors, --version, and a progress line for terminals. Not for lib/ or formats/ (the
 * libraries never print). */
#ifndef TOOL_COMMON_H
#define TOOL_COMMON_H

#include <getopt.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

/* Exit status of every tool. */
enum vt_exit {
    VT_EXIT_OK = 0,        /* success */
    VT_EXIT_BAD_INPUT = 1, /* an input is unreadable or corrupt, or an output cannot be written */
    VT_EXIT_USAGE = 2,     /* bad command line */
};

/* Log levels: a message is printed when its level <= the current level (default VT_LOG_WARN).
 * -q sets VT_LOG_ERROR, each -v adds one. */
enum vt_log_level {
    VT_LOG_ERROR = 0, /* why the tool fails */
    VT_LOG_WARN = 1,  /* results may not be what the user expects */
    VT_LOG_INFO = 2,  /* what was done ("verified 20 tiles") */
    VT_LOG_DEBUG = 3, /* details for developers */
};

/* Sets the name that prefixes every message ("vt-info"); call once at the start of main. */
void vt_tool_init(const char *tool_name);
const char *vt_tool_name(void);

void vt_log_set_level(int level);
int vt_log_get_level(void);

/* Messages that name 'path' (in single quotes, as every message names a file) name 'name'
 * instead, from now on: set once from main for "-" ('<stdout>') and for the spool of standard
 * input ('<stdin>', vt_stdin_spool.h), whose path means nothing to the user. At most 4. */
void vt_log_alias(const char *path, const char *name);

/* Prints "<tool>: <message>\n" to stderr when level <= the current level. */
void vt_log(int level, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Prints "<tool>: <reason>" and "try '<tool> --help'" to stderr; returns VT_EXIT_USAGE. */
int vt_usage_error(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* getopt_long() without GNU's abbreviations: "--verb" for "--verbose" is an unknown option ('?'),
 * so that adding an option never breaks a command line. Call with opterr = 0 and an optstring
 * starting with ':'; report '?' and ':' with vt_usage_getopt_error(). */
int vt_getopt_long(int argc, char *const argv[], const char *optstring,
                   const struct option *longopts);

/* Reports the vt_getopt_long() result c ('?' or ':', with opterr = 0 and an optstring starting with
 * ':') as a usage error naming the option; returns VT_EXIT_USAGE. */
int vt_usage_getopt_error(int c, char *const argv[]);

/* The options a tool's vt_getopt_long() switch ends with (its default branch): 'q' sets the log
 * level to errors only, 'v' raises it by one, 'h' prints usage_text on stdout, version_opt (the
 * tool's --version value) prints vt_print_version(); any other c is reported with
 * vt_usage_getopt_error(). Returns -1 to go on parsing, or the exit status (VT_EXIT_OK after
 * --help or --version). */
int vt_common_option(int c, int version_opt, const char *usage_text, char *const argv[]);

/* Parses a decimal integer in min..max (no sign, no junk, no empty string) into *out. Returns 0,
 * or -1 (and leaves *out alone) when s is not such a number. */
int vt_parse_u32(const char *s, uint32_t min, uint32_t max, uint32_t *out);

/* Parses "A<sep>B" (e.g. "3,1" or "300x200"), each part as vt_parse_u32. Returns 0 or -1. */
int vt_parse_u32_pair(const char *s, char sep, uint32_t min, uint32_t max, uint32_t *a,
                      uint32_t *b);

/* Default of --max-store-size: tile bytes a store may hold (2 TiB). */
#define VT_DEFAULT_MAX_STORE (2ull << 40)

/* Parses a byte size: a decimal integer with an optional binary suffix K, M, G or T (KiB...,
 * upper or lower case), e.g. "512M", "2T", "4096". Returns 0, or -1 on junk or overflow of 2^64. */
int vt_parse_size(const char *s, uint64_t *out);

/* Before any work: refuses an output that is a directory or the same file as one of the
 * inputs[0..n) (vt_output_path_check; NULL entries are skipped). Prints "<tool>: <reason>" and
 * returns VT_EXIT_BAD_INPUT, or returns -1 when the output may be written. */
int vt_check_output(const char *output, const char *const *inputs, size_t n);

/* Before any work, for a binary output (what: "a PNG", "a store") or input: when path is "-"
 * and fd (STDOUT_FILENO or STDIN_FILENO) is a terminal, prints one line ("<tool>: not writing
 * a PNG to a terminal: redirect standard output or give a file name") and returns VT_EXIT_USAGE;
 * else -1. */
int vt_refuse_terminal(const char *path, int fd, const char *what);

/* Prints "<tool> (vtpipe) <version>" and the .vts format line to f. */
void vt_print_version(FILE *f);

/* A "done/total, rate, ETA" line on stderr, redrawn at most 5 times per second, only when stderr
 * is a terminal and the log level is at least VT_LOG_WARN. Single-threaded: call from the thread
 * that owns the loop. */
struct vt_progress {
    const char *what; /* "verifying" */
    const char *unit; /* "tiles" */
    uint64_t total;
    double megapixels_per_unit; /* > 0: also show MP/s (set after vt_progress_start) */
    bool enabled;
    bool drawn;         /* a line is on screen and must be cleared */
    double start_s;     /* monotonic clock at start */
    double last_draw_s; /* monotonic clock at the last redraw */
};

void vt_progress_start(struct vt_progress *p, const char *what, const char *unit, uint64_t total);
void vt_progress_update(struct vt_progress *p, uint64_t done);
/* Clears the line; call before printing anything else and at the end. */
void vt_progress_end(struct vt_progress *p);

#endif
