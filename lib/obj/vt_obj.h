/* Streaming Wavefront OBJ and MTL reader (libc only). See docs/obj-reader.md.
 *
 * OBJ: the text is read line by line and never held whole; memory grows with the v/vt/vn values
 * kept (needed later to measure texel density and rewrite texcoords) and one logical line. Faces
 * are handed to a callback as they are read, with every index resolved to an absolute 0-based
 * index. MTL: read whole into a struct vt_mtl (materials are few compared with vertices). */
#ifndef VT_OBJ_H
#define VT_OBJ_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Marks a corner without texcoord or normal. */
#define VT_OBJ_NONE UINT32_MAX

/* Limits against hostile or broken input; exceeding one fails with VTS_ERR_LIMIT and file:line. */
struct vt_obj_limits {
    size_t max_line_bytes;  /* one logical line, continuations joined (default 1 MiB) */
    uint32_t max_vertices;  /* per kind: v, vt and vn each (default 2^28; at most 2^32 - 2) */
    uint32_t max_materials; /* newmtl statements in one MTL file (default 2^20) */
};

/* Fills limits with the defaults above. */
void vt_obj_limits_default(struct vt_obj_limits *limits);

/* One face corner: absolute 0-based indices into the position/texcoord/normal arrays. */
struct vt_obj_corner {
    uint32_t v;  /* position index, always valid */
    uint32_t vt; /* texcoord index or VT_OBJ_NONE */
    uint32_t vn; /* normal index or VT_OBJ_NONE */
};

/* A face as written (polygons are not triangulated: fan them if needed). Every pointer is owned by
 * the reader and valid only during the callback. */
struct vt_obj_face {
    const struct vt_obj_corner *corners;
    uint32_t corner_count; /* >= 3 */
    const char *material;  /* name from the last usemtl, "" before any */
    const char *group;     /* rest of the last g line (several names stay space-separated), "" */
    const char *object;    /* name from the last o line, "" before any */
    uint64_t line;         /* 1-based line where the f statement starts */
};

/* Callbacks (each may be NULL). Return 0 to go on; any other value stops the read, which returns
 * that value if negative (else VTS_ERR_CANCELLED). A callback may fill err to explain; if it does
 * not, the reader writes "'<file>':<line>: stopped by the <what> callback". Strings are valid only
 * during the call. The reader passed in gives access to the vertices read so far. */
struct vt_obj;
struct vt_obj_callbacks {
    /* Once per file named on an mtllib line (a line may name several), in order; mtl_path is
     * resolved against the OBJ file's directory, backslashes turned into '/'. */
    int (*mtllib)(void *user, const struct vt_obj *obj, const char *mtl_path, uint64_t line,
                  struct vts_error *err);
    /* Each usemtl statement (usemtl may come before the mtllib that defines it). */
    int (*usemtl)(void *user, const struct vt_obj *obj, const char *name, uint64_t line,
                  struct vts_error *err);
    /* Each f statement. */
    int (*face)(void *user, const struct vt_obj *obj, const struct vt_obj_face *face,
                struct vts_error *err);
    void *user;
};

/* Creates a reader with the given limits (NULL: defaults). Free with vt_obj_destroy(). Returns
 * NULL with err filled when out of memory. */
struct vt_obj *vt_obj_create(const struct vt_obj_limits *limits, struct vts_error *err);

/* Frees the reader and every array it holds. Accepts NULL. */
void vt_obj_destroy(struct vt_obj *obj);

/* Reads the OBJ file at path, calling cb (may be NULL) as statements are read. Clears the vertices
 * of any earlier read first. Returns 0, or VTS_ERR_IO, VTS_ERR_BAD_INPUT, VTS_ERR_LIMIT,
 * VTS_ERR_NOMEM (messages "'scene.obj':123: bad texture index '5/x'"), or a callback's status.
 * After a failure the arrays hold what was read up to the failing line. Not thread-safe on one
 * reader. */
int vt_obj_read(struct vt_obj *obj, const char *path, const struct vt_obj_callbacks *cb,
                struct vts_error *err);

/* As vt_obj_read() on size bytes in memory; name is used in messages and, like a path, as the base
 * for mtllib paths. */
int vt_obj_parse_memory(struct vt_obj *obj, const void *data, size_t size, const char *name,
                        const struct vt_obj_callbacks *cb, struct vts_error *err);

/* The values read so far (or by the last read). Arrays hold 3 doubles per entry; they are owned by
 * the reader and move when it grows (re-fetch after each callback). */
uint32_t vt_obj_position_count(const struct vt_obj *obj);
const double *vt_obj_positions(const struct vt_obj *obj); /* x y z (a 4th w is dropped) */
uint32_t vt_obj_texcoord_count(const struct vt_obj *obj);
const double *vt_obj_texcoords(const struct vt_obj *obj); /* u v w; missing ones are 0 */
uint32_t vt_obj_normal_count(const struct vt_obj *obj);
const double *vt_obj_normals(const struct vt_obj *obj); /* x y z */
/* How many components (1, 2 or 3) the vt line of texcoord index wrote; 0 for an index past the end.
 */
unsigned vt_obj_texcoord_components(const struct vt_obj *obj, uint32_t index);

/* Counters of the last read. */
struct vt_obj_stats {
    uint64_t lines;              /* physical lines */
    uint64_t faces;              /* f statements */
    uint64_t ignored_statements; /* known but unused: l, p, s, vp */
    uint64_t unknown_statements; /* anything else (cstype, curv...): callers may warn */
};
void vt_obj_stats(const struct vt_obj *obj, struct vt_obj_stats *stats);

/* ---- MTL ---- */

enum vt_mtl_map_kind {
    VT_MTL_MAP_KD,   /* map_Kd (diffuse) */
    VT_MTL_MAP_KA,   /* map_Ka */
    VT_MTL_MAP_KS,   /* map_Ks */
    VT_MTL_MAP_D,    /* map_d (alpha) */
    VT_MTL_MAP_BUMP, /* map_Bump, bump, map_bump (any case) */
    VT_MTL_MAP_NORM, /* norm */
    VT_MTL_MAP_DISP, /* disp */
    VT_MTL_MAP_COUNT
};

/* Which options a map statement gave (struct vt_mtl_map.options). */
enum vt_mtl_map_options {
    VT_MTL_OPT_S = 1 << 0,
    VT_MTL_OPT_O = 1 << 1,
    VT_MTL_OPT_T = 1 << 2,
    VT_MTL_OPT_CLAMP = 1 << 3,
    VT_MTL_OPT_BM = 1 << 4,
    VT_MTL_OPT_IMFCHAN = 1 << 5,
    VT_MTL_OPT_BLENDU = 1 << 6,
    VT_MTL_OPT_BLENDV = 1 << 7,
    VT_MTL_OPT_MM = 1 << 8,
    VT_MTL_OPT_TEXRES = 1 << 9,
    VT_MTL_OPT_CC = 1 << 10,
    VT_MTL_OPT_BOOST = 1 << 11,
};

/* One texture map with its options; fields not given keep the MTL defaults shown. */
struct vt_mtl_map {
    char *file;       /* as written (rest of the line after the options), '\' -> '/'; NULL: none */
    char *path;       /* file resolved against the MTL file's directory (absolute kept) */
    uint64_t line;    /* 1-based line of the statement (of the last one when repeated); 0: none */
    unsigned options; /* enum vt_mtl_map_options: which were given */
    double s[3];      /* -s scale (1 1 1) */
    double o[3];      /* -o offset (0 0 0) */
    double t[3];      /* -t turbulence (0 0 0) */
    double bm;        /* -bm bump multiplier (1) */
    double boost;     /* -boost (0) */
    double mm[2];     /* -mm base gain (0 1) */
    double texres;    /* -texres (0) */
    bool clamp;       /* -clamp (off) */
    bool blendu;      /* -blendu (on) */
    bool blendv;      /* -blendv (on) */
    bool cc;          /* -cc (off) */
    char imfchan;     /* -imfchan r|g|b|m|l|z, 0 when not given */
};

enum vt_mtl_flags {
    VT_MTL_HAS_KD = 1 << 0,
    VT_MTL_HAS_KA = 1 << 1,
    VT_MTL_HAS_KS = 1 << 2,
    VT_MTL_HAS_D = 1 << 3,
    VT_MTL_HAS_TR = 1 << 4,
    VT_MTL_HAS_ILLUM = 1 << 5,
    VT_MTL_HAS_NS = 1 << 6,
    VT_MTL_HAS_KE = 1 << 7,
};

/* vtpipe's own statement "vt_alpha none|test|blend": forces a material's alpha mode (vt-atlas
 * otherwise derives it from d, map_d and the texels of map_Kd; docs/atlas-format.md). */
enum vt_mtl_alpha {
    VT_MTL_ALPHA_AUTO, /* no vt_alpha statement */
    VT_MTL_ALPHA_NONE,
    VT_MTL_ALPHA_TEST,
    VT_MTL_ALPHA_BLEND,
};

/* One newmtl block. d and Tr are kept raw: by the MTL spec Tr = 1 - d (1 = fully transparent), but
 * MeshLab writes "Tr 1.000000" for opaque materials; callers decide which convention to trust. */
struct vt_mtl_material {
    char *name;
    uint64_t line;                     /* of the newmtl statement */
    unsigned flags;                    /* enum vt_mtl_flags: which values were given */
    double kd[3], ka[3], ks[3], ke[3]; /* as written (0 when not given) */
    double ns;                         /* specular exponent Ns as written (0 when not given) */
    double d;                          /* dissolve as written (default 1) */
    double tr;                         /* Tr as written (default 0) */
    int illum;
    unsigned alpha; /* enum vt_mtl_alpha (vt_alpha statement) */
    struct vt_mtl_map maps[VT_MTL_MAP_COUNT];
    /* vtpipe's own statement "vt_wang PACK.vts [scale S]": the diffuse comes from the virtual
     * output of a Wang pack (vt-wang) at output tile (u * S, -v * S) (docs/wang.md, "Packs in
     * scenes"). wang_path: resolved like a map's (NULL without the statement); scale > 0. */
    char *wang_path;
    double wang_scale;
};

/* A parsed MTL file; caller-owned, freed with vt_mtl_release(). */
struct vt_mtl {
    struct vt_mtl_material *materials;
    size_t material_count;
    uint64_t unknown_statements; /* statements ignored (Ni, map_Ns, refl, ...) */
};

/* Reads the MTL file at path into *mtl (overwritten; release it after success or failure).
 * limits may be NULL. Returns 0, VTS_ERR_IO, VTS_ERR_BAD_INPUT, VTS_ERR_LIMIT or VTS_ERR_NOMEM with
 * "'<file>':<line>: <reason>". */
int vt_mtl_read(const char *path, const struct vt_obj_limits *limits, struct vt_mtl *mtl,
                struct vts_error *err);

/* As vt_mtl_read() on size bytes in memory; name is used in messages and as the base for paths. */
int vt_mtl_parse_memory(const void *data, size_t size, const char *name,
                        const struct vt_obj_limits *limits, struct vt_mtl *mtl,
                        struct vts_error *err);

/* Frees what *mtl holds and zeroes it. Accepts NULL and a zeroed struct. */
void vt_mtl_release(struct vt_mtl *mtl);

/* The material named name (the last one if defined twice), or NULL. Linear search. */
const struct vt_mtl_material *vt_mtl_find(const struct vt_mtl *mtl, const char *name);

/* Resolves file against the directory of base_file: backslashes become '/', absolute paths ("/x",
 * "C:/x") are kept. Returns a malloc'ed string (free() it), or NULL when out of memory. */
char *vt_obj_resolve_path(const char *base_file, const char *file);

#ifdef __cplusplus
}
#endif
#endif
