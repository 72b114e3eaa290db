/* Tokens of vt-offset's raw lines (see vt_offset_tok.h). */
#include "internal/vt_offset_tok.h"

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
