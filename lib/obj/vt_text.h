/* The line source of the OBJ and MTL readers (a file or memory, '\' continuations joined, CRLF
 * stripped, line numbers kept) and their token and number helpers, which lib/offset shares so that
 * it accepts exactly what the reader accepts. Not part of the reader's API (vt_obj.h). */
#ifndef VT_TEXT_H
#define VT_TEXT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "vt_error.h"

struct vt_text_src {
    const char *name;
    FILE *file;                /* NULL when reading memory */
    const unsigned char *data; /* the memory, or buf */
    size_t len, pos;
    unsigned char *buf;
    char *line; /* the current logical line, NUL-terminated */
    size_t line_len, line_cap, max_line;
    uint64_t physical;   /* physical lines consumed */
    uint64_t start_line; /* where the current logical line starts */
};

/* Opens path for reading logical lines of at most max_line_bytes (longer ones fail with
 * VTS_ERR_LIMIT). 0, VTS_ERR_IO or VTS_ERR_NOMEM. */
int vt_text_open(struct vt_text_src *s, const char *path, size_t max_line_bytes,
                 struct vts_error *err);

/* Reads lines from caller memory (which must outlive the source); name is used in messages. */
void vt_text_memory(struct vt_text_src *s, const void *data, size_t size, const char *name,
                    size_t max_line_bytes);

/* Closes the file and frees the line buffer. */
void vt_text_close(struct vt_text_src *s);

/* Reads the next logical line into s->line (NUL-terminated, continuations joined). Returns 1 when
 * a line was read, 0 at the end, or a negative status (VTS_ERR_IO, VTS_ERR_LIMIT, VTS_ERR_NOMEM).
 */
int vt_text_next_line(struct vt_text_src *s, struct vts_error *err);

/* Splits the next whitespace-separated token out of *cur (NUL-terminating it); NULL at the end. */
char *vt_text_token(char **cur);

/* The rest of the line after leading spaces, trailing spaces removed (names with spaces). */
char *vt_text_rest(char *cur);

/* Parses a finite decimal number; false for junk, nan, inf or overflow. */
bool vt_text_double(const char *tok, double *out);

/* Parses up to max numbers from *cur; returns how many, or -1 with *bad = the bad token. */
int vt_text_numbers(char **cur, double *out, int max, const char **bad);

bool vt_text_is_space(char c);

/* Parses a signed decimal OBJ index occupying [s, e) (an optional sign, digits, at most ~2^40);
 * false on junk or overflow. Shared by the OBJ reader and vt-offset so both accept the same. */
bool vt_text_index(const char *s, const char *e, int64_t *out);

#endif
