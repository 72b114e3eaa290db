/* Tokens of vt-offset's raw lines (see vt_offset_tok.h). */
#include "vt_offset_tok.h"

enum vt_offset_keyword vt_offset_tok_keyword(const struct vt_offset_tok *t)
{
    switch (t->e - t->s) {
    case 1:
        return t->s[0] == 'v'   ? VT_OFFSET_KW_V
               : t->s[0] == 'f' ? VT_OFFSET_KW_F
               : t->s[0] == 'l' ? VT_OFFSET_KW_L
                                : VT_OFFSET_KW_OTHER;
    case 2:
        return vt_offset_tok_is(t, "vt", 2)   ? VT_OFFSET_KW_VT
               : vt_offset_tok_is(t, "vn", 2) ? VT_OFFSET_KW_VN
                                              : VT_OFFSET_KW_OTHER;
    case 6:
        return vt_offset_tok_is(t, "usemtl", 6)   ? VT_OFFSET_KW_USEMTL
               : vt_offset_tok_is(t, "mtllib", 6) ? VT_OFFSET_KW_MTLLIB
                                                  : VT_OFFSET_KW_OTHER;
    default:
        return VT_OFFSET_KW_OTHER;
    }
}

/* A signed decimal index in [s, e) (vt_obj's rules); false on junk or overflow. */
bool vt_offset_tok_index(const unsigned char *s, const unsigned char *e, int64_t *out)
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

/* Copies a token into buf for a message (cut at 63 bytes). */
const char *vt_offset_tok_text(const struct vt_offset_tok *t, char buf[64])
{
    size_t n = (size_t)(t->e - t->s);
    if (n > 63)
        n = 63;
    memcpy(buf, t->s, n);
    buf[n] = '\0';
    return buf;
}
