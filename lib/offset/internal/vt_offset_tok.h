/* Tokens of vt-offset's raw lines (private to lib/offset), with vt_obj's rules: whitespace
 * is space, tab, '\r', '\v', '\f', a '\n' inside a continued line and a '\' that continues the
 * line; a token starting with '#' ends the statement. The per-byte functions are inline (hot). */
#ifndef VT_OFFSET_TOK_H
#define VT_OFFSET_TOK_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

static inline bool vt_offset_tok_space(const unsigned char *p, const unsigned char *end)
{
    switch (*p) {
    case ' ':
    case '\t':
    case '\r':
    case '\n':
    case '\v':
    case '\f':
        return true;
    case '\\': {
        const unsigned char *q = p + 1;
        if (q < end && *q == '\r')
            q++;
        return q == end || *q == '\n';
    }
    default:
        return false;
    }
}

struct vt_offset_tok {
    const unsigned char *s, *e;
};

/* The next token of [*cur, end); false at the end or at a '#' comment. */
static inline bool vt_offset_tok_next(const unsigned char **cur, const unsigned char *end,
                                      struct vt_offset_tok *t)
{
    const unsigned char *p = *cur;
    while (p < end && vt_offset_tok_space(p, end))
        p++;
    if (p == end || *p == '#') {
        *cur = p;
        return false;
    }
    t->s = p;
    while (p < end && !vt_offset_tok_space(p, end))
        p++;
    t->e = p;
    *cur = p;
    return true;
}

static inline bool vt_offset_tok_is(const struct vt_offset_tok *t, const char *word, size_t n)
{
    return (size_t)(t->e - t->s) == n && memcmp(t->s, word, n) == 0;
}

enum vt_offset_keyword {
    VT_OFFSET_KW_OTHER,
    VT_OFFSET_KW_V,
    VT_OFFSET_KW_VT,
    VT_OFFSET_KW_VN,
    VT_OFFSET_KW_F,
    VT_OFFSET_KW_L,
    VT_OFFSET_KW_USEMTL,
    VT_OFFSET_KW_MTLLIB
};

/* The statement keyword of t (VT_OFFSET_KW_OTHER for any other). */
enum vt_offset_keyword vt_offset_tok_keyword(const struct vt_offset_tok *t);

/* Copies a token into buf for a message (cut at 63 bytes); returns buf. */
const char *vt_offset_tok_text(const struct vt_offset_tok *t, char buf[64]);

#endif
