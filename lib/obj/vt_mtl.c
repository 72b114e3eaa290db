/* MTL reader: materials with their colours and texture maps (declared in vt_obj.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "vt_checked.h"
#include "vt_error.h"
#include "vt_obj.h"
#include "vt_text.h"

/* ---- MTL ---- */

struct mtl_parse {
    struct vt_mtl *mtl;
    struct vt_text_src *src;
    const struct vt_obj_limits *limits;
    size_t cap;
};

static int mtl_bad(struct mtl_parse *p, const char *what, const char *tok, struct vts_error *err)
{
    return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: %s '%s'", p->src->name,
                        (unsigned long long)p->src->start_line, what, tok);
}

static void map_defaults(struct vt_mtl_map *m)
{
    memset(m, 0, sizeof *m);
    m->s[0] = m->s[1] = m->s[2] = 1;
    m->bm = 1;
    m->mm[1] = 1;
    m->blendu = m->blendv = true;
}

static void map_release(struct vt_mtl_map *m)
{
    free(m->file);
    free(m->path);
    map_defaults(m);
}

static int mtl_newmtl(struct mtl_parse *p, char *cur, struct vts_error *err)
{
    struct vt_mtl *mtl = p->mtl;
    if (mtl->material_count >= p->limits->max_materials)
        return vt_error_set(err, VTS_ERR_LIMIT, "'%s':%llu: more than %lu materials (the limit)",
                            p->src->name, (unsigned long long)p->src->start_line,
                            (unsigned long)p->limits->max_materials);
    if (mtl->material_count == p->cap) {
        size_t cap = p->cap ? p->cap * 2 : 16, bytes;
        struct vt_mtl_material *m;
        if (!vt_size_mul(cap, sizeof *m, &bytes) || !(m = realloc(mtl->materials, bytes)))
            return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory for materials",
                                p->src->name);
        mtl->materials = m;
        p->cap = cap;
    }
    struct vt_mtl_material *m = &mtl->materials[mtl->material_count];
    memset(m, 0, sizeof *m);
    for (int i = 0; i < VT_MTL_MAP_COUNT; i++)
        map_defaults(&m->maps[i]);
    m->d = 1;
    m->line = p->src->start_line;
    m->name = strdup(vt_text_rest(cur));
    if (!m->name)
        return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory", p->src->name);
    mtl->material_count++;
    return 0;
}

/* Kd/Ka/Ks/Ke r [g b] (one value means grey); "spectral" and "xyz" forms are counted as unknown. */
static int mtl_colour(struct mtl_parse *p, struct vt_mtl_material *m, const char *kw, char *cur,
                      struct vts_error *err)
{
    double rgb[3];
    const char *bad = NULL;
    const char *rest = vt_text_rest(cur);
    if (strncmp(rest, "spectral", 8) == 0 || strncmp(rest, "xyz", 3) == 0) {
        p->mtl->unknown_statements++;
        return 0;
    }
    int n = vt_text_numbers(&cur, rgb, 3, &bad);
    if (n < 0)
        return mtl_bad(p, "bad number", bad, err);
    if ((n != 1 && n != 3) || vt_text_token(&cur))
        return mtl_bad(p, "needs 1 or 3 numbers:", kw, err);
    if (n == 1)
        rgb[1] = rgb[2] = rgb[0];
    double *dst = kw[1] == 'd' ? m->kd : kw[1] == 'a' ? m->ka : kw[1] == 's' ? m->ks : m->ke;
    memcpy(dst, rgb, sizeof rgb);
    m->flags |= kw[1] == 'd'   ? VT_MTL_HAS_KD
                : kw[1] == 'a' ? VT_MTL_HAS_KA
                : kw[1] == 's' ? VT_MTL_HAS_KS
                               : VT_MTL_HAS_KE;
    return 0;
}

/* d [-halo] f, Tr f, Ns f, illum n. */
static int mtl_scalar(struct mtl_parse *p, struct vt_mtl_material *m, const char *kw, char *cur,
                      struct vts_error *err)
{
    char *tok = vt_text_token(&cur);
    if (tok && strcmp(kw, "d") == 0 && strcmp(tok, "-halo") == 0)
        tok = vt_text_token(&cur);
    double v;
    if (!tok)
        return mtl_bad(p, "missing value after", kw, err);
    if (!vt_text_double(tok, &v) || vt_text_token(&cur))
        return mtl_bad(p, "bad number", tok, err);
    if (kw[0] == 'd') {
        m->d = v, m->flags |= VT_MTL_HAS_D;
    } else if (kw[0] == 'N') {
        m->ns = v, m->flags |= VT_MTL_HAS_NS;
    } else if (kw[0] == 'T') {
        m->tr = v, m->flags |= VT_MTL_HAS_TR;
    } else {
        if (v != floor(v) || v < 0 || v > 100)
            return mtl_bad(p, "bad illum", tok, err);
        m->illum = (int)v, m->flags |= VT_MTL_HAS_ILLUM;
    }
    return 0;
}

/* vt_alpha none|test|blend. */
static int mtl_alpha(struct mtl_parse *p, struct vt_mtl_material *m, char *cur,
                     struct vts_error *err)
{
    static const char *const names[] = {"none", "test", "blend"};
    char *tok = vt_text_token(&cur);
    if (!tok)
        return mtl_bad(p, "missing value after", "vt_alpha", err);
    bool alone = vt_text_token(&cur) == NULL;
    for (unsigned i = 0; i < 3 && alone; i++)
        if (strcmp(tok, names[i]) == 0) {
            m->alpha = VT_MTL_ALPHA_NONE + i;
            return 0;
        }
    return mtl_bad(p, "vt_alpha must be none, test or blend, not", tok, err);
}

/* vt_wang PACK.vts [scale S]: the file name is one token (no spaces), S a finite number > 0. */
static int mtl_wang(struct mtl_parse *p, struct vt_mtl_material *m, char *cur,
                    struct vts_error *err)
{
    char *file = vt_text_token(&cur);
    if (!file)
        return mtl_bad(p, "missing pack after", "vt_wang", err);
    double scale = 1.0;
    char *opt = vt_text_token(&cur);
    if (opt) {
        char *num = strcmp(opt, "scale") == 0 ? vt_text_token(&cur) : NULL;
        char *end = NULL;
        if (!num)
            return mtl_bad(p, "vt_wang takes 'scale S' after the pack, not", opt, err);
        scale = strtod(num, &end);
        if (*end || !isfinite(scale) || scale <= 0.0)
            return mtl_bad(p, "vt_wang scale must be a number > 0, not", num, err);
        if ((opt = vt_text_token(&cur)) != NULL)
            return mtl_bad(p, "unexpected after vt_wang scale", opt, err);
    }
    char *path = vt_obj_resolve_path(p->src->name, file);
    if (!path)
        return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory", p->src->name);
    free(m->wang_path); /* a repeated statement replaces the earlier one */
    m->wang_path = path;
    m->wang_scale = scale;
    return 0;
}

static int map_kind(const char *kw)
{
    static const char *const names[] = {"map_Kd", "map_Ka",   "map_Ks", "map_d", "map_Bump",
                                        "bump",   "map_bump", "norm",   "disp"};
    static const int kinds[] = {VT_MTL_MAP_KD,   VT_MTL_MAP_KA,   VT_MTL_MAP_KS,
                                VT_MTL_MAP_D,    VT_MTL_MAP_BUMP, VT_MTL_MAP_BUMP,
                                VT_MTL_MAP_BUMP, VT_MTL_MAP_NORM, VT_MTL_MAP_DISP};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (strcasecmp(kw, names[i]) == 0)
            return kinds[i];
    return -1;
}

/* Reads 1..max numbers of an option into out (unread ones keep their value). A token that is not a
 * number ends the list (it may be the file name). */
static int map_numbers(struct mtl_parse *p, char **cur, const char *opt, double *out, int max,
                       struct vts_error *err)
{
    int n = 0;
    while (n < max) {
        char *save = *cur;
        char *tok = vt_text_token(cur);
        if (!tok || !vt_text_double(tok, &out[n])) {
            if (tok && tok + strlen(tok) < *cur)
                tok[strlen(tok)] = ' '; /* undo the split: the token belongs to the file name */
            *cur = save;
            break;
        }
        n++;
    }
    return n ? 0 : mtl_bad(p, "missing number after", opt, err);
}

static int map_onoff(struct mtl_parse *p, char **cur, const char *opt, bool *out,
                     struct vts_error *err)
{
    char *tok = vt_text_token(cur);
    if (tok && strcmp(tok, "on") == 0)
        *out = true;
    else if (tok && strcmp(tok, "off") == 0)
        *out = false;
    else
        return mtl_bad(p, "expected on or off after", opt, err);
    return 0;
}

/* One option starting at tok; fills m and sets its bit. */
static int map_option(struct mtl_parse *p, struct vt_mtl_map *m, const char *opt, char **cur,
                      struct vts_error *err)
{
    static const struct {
        const char *name;
        unsigned bit;
    } table[] = {{"-s", VT_MTL_OPT_S},           {"-o", VT_MTL_OPT_O},
                 {"-t", VT_MTL_OPT_T},           {"-clamp", VT_MTL_OPT_CLAMP},
                 {"-bm", VT_MTL_OPT_BM},         {"-imfchan", VT_MTL_OPT_IMFCHAN},
                 {"-blendu", VT_MTL_OPT_BLENDU}, {"-blendv", VT_MTL_OPT_BLENDV},
                 {"-mm", VT_MTL_OPT_MM},         {"-texres", VT_MTL_OPT_TEXRES},
                 {"-cc", VT_MTL_OPT_CC},         {"-boost", VT_MTL_OPT_BOOST}};
    unsigned bit = 0;
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)
        if (strcmp(opt, table[i].name) == 0)
            bit = table[i].bit;
    m->options |= bit;
    switch (bit) {
    case VT_MTL_OPT_S:
        return map_numbers(p, cur, opt, m->s, 3, err);
    case VT_MTL_OPT_O:
        return map_numbers(p, cur, opt, m->o, 3, err);
    case VT_MTL_OPT_T:
        return map_numbers(p, cur, opt, m->t, 3, err);
    case VT_MTL_OPT_BM:
        return map_numbers(p, cur, opt, &m->bm, 1, err);
    case VT_MTL_OPT_BOOST:
        return map_numbers(p, cur, opt, &m->boost, 1, err);
    case VT_MTL_OPT_TEXRES:
        return map_numbers(p, cur, opt, &m->texres, 1, err);
    case VT_MTL_OPT_MM:
        return map_numbers(p, cur, opt, m->mm, 2, err);
    case VT_MTL_OPT_CLAMP:
        return map_onoff(p, cur, opt, &m->clamp, err);
    case VT_MTL_OPT_BLENDU:
        return map_onoff(p, cur, opt, &m->blendu, err);
    case VT_MTL_OPT_BLENDV:
        return map_onoff(p, cur, opt, &m->blendv, err);
    case VT_MTL_OPT_CC:
        return map_onoff(p, cur, opt, &m->cc, err);
    case VT_MTL_OPT_IMFCHAN: {
        char *tok = vt_text_token(cur);
        if (!tok || strlen(tok) != 1 || !strchr("rgbmlz", tok[0]))
            return mtl_bad(p, "expected r, g, b, m, l or z after", opt, err);
        m->imfchan = tok[0];
        return 0;
    }
    default:
        return mtl_bad(p, "unknown map option", opt, err);
    }
}

/* map_* [options] file name (the rest of the line, spaces allowed). */
static int mtl_map(struct mtl_parse *p, struct vt_mtl_material *m, int kind, char *cur,
                   struct vts_error *err)
{
    struct vt_mtl_map map;
    map_defaults(&map);
    for (;;) {
        while (vt_text_is_space(*cur))
            cur++;
        if (cur[0] != '-' || (cur[1] >= '0' && cur[1] <= '9'))
            break;
        char *opt = vt_text_token(&cur);
        int rc = map_option(p, &map, opt, &cur, err);
        if (rc < 0)
            return rc;
    }
    char *rest = vt_text_rest(cur);
    if (!*rest)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s':%llu: map statement without a file name",
                            p->src->name, (unsigned long long)p->src->start_line);
    map.line = p->src->start_line;
    map.file = vt_obj_resolve_path("", rest);
    map.path = vt_obj_resolve_path(p->src->name, rest);
    if (!map.file || !map.path) {
        map_release(&map);
        return vt_error_set(err, VTS_ERR_NOMEM, "'%s': out of memory", p->src->name);
    }
    map_release(&m->maps[kind]); /* a repeated statement replaces the earlier one */
    m->maps[kind] = map;
    return 0;
}

static int mtl_statement(struct mtl_parse *p, struct vts_error *err)
{
    char *cur = p->src->line;
    char *kw = vt_text_token(&cur);
    if (!kw)
        return 0;
    if (strcmp(kw, "newmtl") == 0)
        return mtl_newmtl(p, cur, err);
    struct vt_mtl_material *m =
        p->mtl->material_count ? &p->mtl->materials[p->mtl->material_count - 1] : NULL;
    int kind = map_kind(kw);
    if (!m) {
        p->mtl->unknown_statements++; /* before any newmtl: nothing to attach it to */
        return 0;
    }
    if (kind >= 0)
        return mtl_map(p, m, kind, cur, err);
    if (strcmp(kw, "Kd") == 0 || strcmp(kw, "Ka") == 0 || strcmp(kw, "Ks") == 0 ||
        strcmp(kw, "Ke") == 0)
        return mtl_colour(p, m, kw, cur, err);
    if (strcmp(kw, "d") == 0 || strcmp(kw, "Tr") == 0 || strcmp(kw, "Ns") == 0 ||
        strcmp(kw, "illum") == 0)
        return mtl_scalar(p, m, kw, cur, err);
    if (strcmp(kw, "vt_alpha") == 0)
        return mtl_alpha(p, m, cur, err);
    if (strcmp(kw, "vt_wang") == 0)
        return mtl_wang(p, m, cur, err);
    p->mtl->unknown_statements++;
    return 0;
}

static int mtl_parse(struct vt_text_src *src, const struct vt_obj_limits *limits,
                     struct vt_mtl *mtl, struct vts_error *err)
{
    struct mtl_parse p = {mtl, src, limits, 0};
    int rc;
    while ((rc = vt_text_next_line(src, err)) == 1) {
        rc = mtl_statement(&p, err);
        if (rc < 0)
            break;
    }
    return rc < 0 ? rc : 0;
}

int vt_mtl_read(const char *path, const struct vt_obj_limits *limits, struct vt_mtl *mtl,
                struct vts_error *err)
{
    struct vt_obj_limits defaults;
    if (!limits) {
        vt_obj_limits_default(&defaults);
        limits = &defaults;
    }
    memset(mtl, 0, sizeof *mtl);
    struct vt_text_src src;
    int rc = vt_text_open(&src, path, limits->max_line_bytes, err);
    if (rc < 0)
        return rc;
    rc = mtl_parse(&src, limits, mtl, err);
    vt_text_close(&src);
    return rc;
}

int vt_mtl_parse_memory(const void *data, size_t size, const char *name,
                        const struct vt_obj_limits *limits, struct vt_mtl *mtl,
                        struct vts_error *err)
{
    struct vt_obj_limits defaults;
    if (!limits) {
        vt_obj_limits_default(&defaults);
        limits = &defaults;
    }
    memset(mtl, 0, sizeof *mtl);
    struct vt_text_src src;
    vt_text_memory(&src, data, size, name, limits->max_line_bytes);
    int rc = mtl_parse(&src, limits, mtl, err);
    vt_text_close(&src);
    return rc;
}

void vt_mtl_release(struct vt_mtl *mtl)
{
    if (!mtl)
        return;
    for (size_t i = 0; i < mtl->material_count; i++) {
        free(mtl->materials[i].name);
        free(mtl->materials[i].wang_path);
        for (int k = 0; k < VT_MTL_MAP_COUNT; k++)
            map_release(&mtl->materials[i].maps[k]);
    }
    free(mtl->materials);
    memset(mtl, 0, sizeof *mtl);
}

const struct vt_mtl_material *vt_mtl_find(const struct vt_mtl *mtl, const char *name)
{
    for (size_t i = mtl->material_count; i-- > 0;)
        if (strcmp(mtl->materials[i].name, name) == 0)
            return &mtl->materials[i];
    return NULL;
}
