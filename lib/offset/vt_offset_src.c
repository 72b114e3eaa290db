/* The raw logical line source of vt-offset (see vt_offset_src.h). */
#include "internal/vt_offset_src.h"
#include "vt_error.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define READ_CHUNK ((size_t)1 << 20)

int vt_offset_src_open(struct vt_offset_src *s, const char *path, const void *mem, size_t mem_size,
                       size_t max_line, struct vts_error *err)
{
    memset(s, 0, sizeof *s);
    s->name = path;
    s->max_line = max_line < SIZE_MAX / 4 ? max_line : SIZE_MAX / 4;
    if (mem) {
        s->data = mem;
        s->len = mem_size;
        s->eof = true;
        s->nul = memchr(mem, '\0', mem_size) != NULL;
        return 0;
    }
    s->file = fopen(path, "rb");
    if (!s->file)
        return vt_error_set(err, VTS_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
    s->cap = READ_CHUNK;
    s->buf = malloc(s->cap);
    if (!s->buf) {
        fclose(s->file);
        s->file = NULL;
        return vt_error_set(err, VTS_ERR_NOMEM, "cannot read '%s': out of memory", path);
    }
    s->data = s->buf;
    return 0;
}

void vt_offset_src_close(struct vt_offset_src *s)
{
    if (s->file)
        fclose(s->file);
    free(s->buf);
    memset(s, 0, sizeof *s);
}

/* Keeps the unread bytes, growing the buffer when the line being read fills it, and reads more. */
static int src_fill(struct vt_offset_src *s, size_t *scan, struct vts_error *err)
{
    if (s->pos > 0) {
        memmove(s->buf, s->buf + s->pos, s->len - s->pos);
        s->len -= s->pos;
        *scan -= s->pos;
        s->pos = 0;
    }
    if (s->len == s->cap) {
        /* a line of max_line counted bytes takes at most 2 * max_line + 2 raw ones */
        if (s->len > 2 * s->max_line + 2)
            return vt_error_set(err, VTS_ERR_LIMIT,
                                "'%s':%llu: line longer than the limit of %zu bytes", s->name,
                                (unsigned long long)s->physical + 1, s->max_line);
        unsigned char *grown = realloc(s->buf, s->cap * 2);
        if (!grown)
            return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory for a line", s->name);
        s->buf = grown;
        s->data = grown;
        s->cap *= 2;
    }
    size_t got = fread(s->buf + s->len, 1, s->cap - s->len, s->file);
    if (got == 0) {
        if (ferror(s->file))
            return vt_error_set(err, VTS_ERR_IO, "cannot read '%s': %s", s->name, strerror(errno));
        s->eof = true;
    }
    if (memchr(s->buf + s->len, '\0', got))
        s->nul = true;
    s->len += got;
    return 0;
}

/* The next logical line as raw bytes (with its '\n'): 1, 0 at the end, or a negative status. */
int vt_offset_src_next(struct vt_offset_src *s, const unsigned char **line, size_t *line_len,
                       struct vts_error *err)
{
    size_t scan = s->pos, end;
    uint64_t newlines = 0;
    s->line = s->physical + 1;
    for (;;) {
        const unsigned char *nl =
            scan < s->len ? memchr(s->data + scan, '\n', s->len - scan) : NULL;
        if (nl) {
            size_t at = (size_t)(nl - s->data), b = at;
            newlines++;
            if (b > s->pos && s->data[b - 1] == '\r')
                b--;
            if (b > s->pos && s->data[b - 1] == '\\') {
                scan = at + 1;
                continue;
            }
            end = at + 1;
            break;
        }
        if (s->eof) {
            if (s->pos == s->len)
                return 0;
            end = s->len;
            break;
        }
        int rc = src_fill(s, &scan, err);
        if (rc < 0)
            return rc;
    }
    const unsigned char *p = s->data + s->pos;
    size_t n = end - s->pos;
    if (n - newlines > s->max_line)
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "'%s':%llu: line longer than the limit of %zu bytes", s->name,
                            (unsigned long long)s->line, s->max_line);
    const unsigned char *nul = s->nul ? memchr(p, '\0', n) : NULL;
    if (nul) {
        uint64_t at_line = s->line;
        for (const unsigned char *q = p; q < nul; q++)
            at_line += *q == '\n';
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: NUL byte in a text line", s->name,
                            (unsigned long long)at_line);
    }
    s->physical += newlines + (p[n - 1] != '\n');
    s->pos = end;
    *line = p;
    *line_len = n;
    return 1;
}
