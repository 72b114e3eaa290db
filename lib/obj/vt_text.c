/* The line source and token helpers of the OBJ and MTL readers (see vt_text.h). */
#include "vt_text.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vt_checked.h"
#include "vt_error.h"

#define READ_CHUNK (64 * 1024)

/* ---- line source ---- */

/* Makes input available at s->pos: 1, 0 at the end, or -2 on a read error. */
static int src_fill(struct vt_text_src *s)
{
    if (s->pos < s->len)
        return 1;
    if (!s->file)
        return 0;
    s->len = fread(s->buf, 1, READ_CHUNK, s->file);
    s->pos = 0;
    if (s->len == 0)
        return ferror(s->file) ? -2 : 0;
    return 1;
}

/* Appends n bytes to the line, keeping room for a terminator; the limit counts the raw bytes of the
 * physical lines (continuation '\' and '\r' included). */
static int line_append(struct vt_text_src *s, const unsigned char *bytes, size_t n,
                       struct vts_error *err)
{
    if (n > s->max_line - s->line_len)
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "'%s':%llu: line longer than the limit of %zu bytes", s->name,
                            (unsigned long long)s->start_line, s->max_line);
    if (s->line_len + n + 1 > s->line_cap) {
        size_t cap = s->line_cap ? s->line_cap : 256;
        while (cap < s->line_len + n + 1)
            cap *= 2;
        if (cap > s->max_line + 1)
            cap = s->max_line + 1;
        char *p = realloc(s->line, cap);
        if (!p)
            return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory for a line", s->name);
        s->line = p;
        s->line_cap = cap;
    }
    memcpy(s->line + s->line_len, bytes, n);
    s->line_len += n;
    return 0;
}

/* Ends a physical line: drops a '\r' before the '\n'; returns true when a '\' continues it. */
static bool line_end_physical(struct vt_text_src *s)
{
    s->physical++;
    if (s->line_len && s->line[s->line_len - 1] == '\r')
        s->line_len--;
    if (s->line_len && s->line[s->line_len - 1] == '\\') {
        s->line[s->line_len - 1] = ' ';
        return true;
    }
    return false;
}

/* Reads one logical line into s->line (NUL-terminated). Returns 1, 0 at the end of input, or a
 * negative status. */
int vt_text_next_line(struct vt_text_src *s, struct vts_error *err)
{
    s->line_len = 0;
    s->start_line = s->physical + 1;
    bool any = false;
    for (;;) {
        int rc = src_fill(s);
        if (rc == -2)
            return vt_error_set(err, VTS_ERR_IO, "cannot read '%s': %s", s->name, strerror(errno));
        if (rc == 0) {
            if (!any)
                return 0;
            line_end_physical(s);
            break;
        }
        any = true;
        const unsigned char *start = s->data + s->pos;
        const unsigned char *nl = memchr(start, '\n', s->len - s->pos);
        size_t n = nl ? (size_t)(nl - start) : s->len - s->pos;
        if (memchr(start, '\0', n))
            return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: NUL byte in a text line",
                                s->name, (unsigned long long)s->physical + 1);
        rc = line_append(s, start, n, err);
        if (rc < 0)
            return rc;
        s->pos += n + (nl != NULL);
        if (nl && !line_end_physical(s))
            break;
    }
    if (!s->line) { /* an empty last line: no buffer yet */
        s->line = malloc(1);
        if (!s->line)
            return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory for a line", s->name);
        s->line_cap = 1;
    }
    s->line[s->line_len] = '\0';
    return 1;
}

int vt_text_open(struct vt_text_src *s, const char *path, size_t max_line_bytes,
                 struct vts_error *err)
{
    memset(s, 0, sizeof *s);
    s->name = path;
    s->max_line = max_line_bytes < SIZE_MAX / 4 ? max_line_bytes : SIZE_MAX / 4;
    s->buf = malloc(READ_CHUNK);
    if (!s->buf)
        return vt_error_set(err, VTS_ERR_NOMEM, "cannot read '%s': out of memory", path);
    s->data = s->buf;
    s->file = fopen(path, "rb");
    if (!s->file) {
        int rc = vt_error_set(err, VTS_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
        free(s->buf);
        s->buf = NULL;
        return rc;
    }
    return 0;
}

void vt_text_memory(struct vt_text_src *s, const void *data, size_t size, const char *name,
                    size_t max_line_bytes)
{
    memset(s, 0, sizeof *s);
    s->name = name;
    s->max_line = max_line_bytes < SIZE_MAX / 4 ? max_line_bytes : SIZE_MAX / 4;
    s->data = data;
    s->len = size;
}

void vt_text_close(struct vt_text_src *s)
{
    if (s->file)
        fclose(s->file);
    free(s->buf);
    free(s->line);
}

/* ---- tokens and numbers ---- */

bool vt_text_is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* Splits the next whitespace-separated token off *cur (NUL-terminating it); NULL at the end or at a
 * token starting with '#' (an inline comment). */
char *vt_text_token(char **cur)
{
    char *p = *cur;
    while (vt_text_is_space(*p))
        p++;
    if (*p == '\0' || *p == '#') {
        *cur = p;
        return NULL;
    }
    char *start = p;
    while (*p && !vt_text_is_space(*p))
        p++;
    if (*p)
        *p++ = '\0';
    *cur = p;
    return start;
}

/* The rest of the line with surrounding whitespace trimmed (in place). */
char *vt_text_rest(char *cur)
{
    while (vt_text_is_space(*cur))
        cur++;
    size_t n = strlen(cur);
    while (n && vt_text_is_space(cur[n - 1]))
        cur[--n] = '\0';
    return cur;
}

/* A finite decimal number (digits, sign, point, exponent; no nan/inf/hex), the whole token. */
bool vt_text_double(const char *tok, double *out)
{
    if (!*tok || strspn(tok, "0123456789+-.eE") != strlen(tok))
        return false;
    char *end;
    double v = strtod(tok, &end);
    if (end == tok || *end || !isfinite(v))
        return false;
    *out = v;
    return true;
}

/* Parses up to max numbers from *cur into out; returns how many, or -1 on a token that is not one.
 */
int vt_text_numbers(char **cur, double *out, int max, const char **bad)
{
    int n = 0;
    char *tok;
    while (n < max && (tok = vt_text_token(cur)) != NULL) {
        if (!vt_text_double(tok, &out[n])) {
            *bad = tok;
            return -1;
        }
        n++;
    }
    return n;
}

bool vt_text_index(const char *s, const char *e, int64_t *out)
{
    bool neg = false;
    if (s < e && (*s == '-' || *s == '+'))
        neg = *s++ == '-';
    if (s == e)
        return false;
    int64_t v = 0;
    for (; s < e; s++) {
        if (*s < '0' || *s > '9' || v > (INT64_C(1) << 40))
            return false;
        v = v * 10 + (*s - '0');
    }
    *out = neg ? -v : v;
    return true;
}
