/* The raw logical line source of vt-offset (private to lib/offset). It reads an OBJ file
 * (in 1 MiB chunks) or a memory buffer and hands out each logical line as raw bytes: terminators,
 * '\r' and '\' continuations included, so that lines can be copied unchanged. Lines longer than
 * max_line counted bytes and lines with a NUL byte are refused with a message naming the line. */
#ifndef VT_OFFSET_SRC_H
#define VT_OFFSET_SRC_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "vt_error.h"

struct vt_offset_src {
    const char *name;
    FILE *file;                /* NULL for memory */
    const unsigned char *data; /* buf, or the caller's memory */
    unsigned char *buf;
    size_t cap, len, pos;
    bool eof;
    bool nul; /* a NUL byte was read: lines are checked for it */
    size_t max_line;
    uint64_t physical; /* physical lines consumed */
    uint64_t line;     /* first physical line of the current logical line */
};

/* Opens path (mem NULL) or the mem_size bytes at mem (path then only names it in messages; the
 * memory must outlive the source). Returns 0, VTS_ERR_IO or VTS_ERR_NOMEM. */
int vt_offset_src_open(struct vt_offset_src *s, const char *path, const void *mem, size_t mem_size,
                       size_t max_line, struct vts_error *err);

/* Closes the file and frees the buffer; s is zeroed. */
void vt_offset_src_close(struct vt_offset_src *s);

/* The next logical line as raw bytes (with its '\n'): 1, 0 at the end, or a negative status. The
 * line stays valid until the next call; s->line is its first physical line. */
int vt_offset_src_next(struct vt_offset_src *s, const unsigned char **line, size_t *line_len,
                       struct vts_error *err);

#endif
