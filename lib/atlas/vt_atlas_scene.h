/* The scene scan of vt-atlas: the materials a scene's faces use (from OBJ + MTL files, read with
 * lib/obj), or the textures of a list file or of a file list, each with its texture files per
 * layer (sizes from the image headers, which the caller opens), its Kd/Ks/Ka/d constants, its UV
 * range and the areas used for texel density. Also the list of every file read (for make
 * dependencies). Never prints: warnings go to a callback. */
#ifndef VT_ATLAS_SCENE_H
#define VT_ATLAS_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_atlas_alpha.h"
#include "vt_atlas_kind.h"
#include "vt_error.h"
#include "vt_layout.h"
#include "vt_source.h"

/* One texture file. Two paths that name the same file (same device and inode: "tex/a.png" and
 * "./tex/../tex/a.png", a link, MTL files in two directories) are one texture, so that the
 * materials using it can share one atlas entry. */
struct vt_atlas_texture {
    char *path; /* as first read (resolved against the MTL or list file's directory) */
    char *id;   /* "device:inode" of the file */
    uint32_t width, height, channels;
    bool has_alpha;                     /* the file has an alpha channel */
    bool alpha_scanned;                 /* alpha holds its counts (a map_Kd with alpha) */
    struct vt_atlas_alpha_counts alpha; /* vt_atlas_alpha_scan() of the file */
};

/* Why a material got its alpha mode (for -v). */
enum vt_atlas_alpha_reason {
    VT_ATLAS_ALPHA_BY_DEFAULT, /* none: no d < 1, no map_d, no cut-out map_Kd */
    VT_ATLAS_ALPHA_BY_MTL,     /* the MTL's vt_alpha statement */
    VT_ATLAS_ALPHA_BY_D,       /* blend: d < 1 */
    VT_ATLAS_ALPHA_BY_MAP_D,   /* test: a map_d texture */
    VT_ATLAS_ALPHA_BY_TEXELS,  /* test or none: the map_Kd's alpha texels */
};

struct vt_atlas_material {
    char *name;
    const char *obj;                      /* first file whose faces use it (for messages; one of
                                             the scene's deps) */
    uint64_t first_line;                  /* of the first face using it */
    bool defined;                         /* found in an MTL (else constant grey) */
    double fill[VT_ATLAS_KIND_COUNT][4];  /* constant of each layer when it has no texture */
    int32_t texture[VT_ATLAS_KIND_COUNT]; /* index into textures (one per file), or -1 */
    bool has_uv;                          /* some face corner has a texcoord */
    double umin, umax, vmin, vmax;        /* union of its charts' texcoord boxes, each chart
                                             moved by whole repeats to start in [0,1)
                                             (lib/chart/vt_chart.h): what the atlas must hold */
    double raw_umin, raw_umax;            /* texcoord range of its faces as written (for */
    double raw_vmin, raw_vmax;            /* messages) */
    bool clamp;                           /* a map of it says -clamp on (no wrap gutter) */
    uint32_t charts;                      /* charts of its faces (over every OBJ) */
    uint32_t moved_charts;                /* of those, charts moved by a non-zero repeat */
    double uv_area, world_area;           /* summed over its triangles with texcoords */
    struct vt_layout_material features;   /* its constants and alpha mode (name, entry and
                                             layer_mask unset: vt_atlas_place fills them) */
    enum vt_atlas_alpha_reason alpha_reason;
    const char *wang;  /* "vt_wang PACK.vts [scale S]" (docs/wang.md): the pack (one of the
                          scene's deps, resolved like a map), else NULL. Such a material has no
                          textures and gets no entry (atlas.json "wang_materials") */
    double wang_scale; /* S (> 0) */
};

/* Opens the texture file at path as a source; the scan keeps its size and channels and closes it
 * at once. A map_Kd texture with an alpha channel is opened a second time and its alpha read in
 * bands (vt_atlas_alpha_scan(): the cut-out detection), once per file. lib/ does not read image
 * files itself: tools pass vt_image_input_open() through this (with their pixel limit), tests a
 * fake. Fills err naming the file on failure (the scan prefixes the MTL statement: "'a.mtl':4:
 * map_Kd: <err>"). Called once per distinct texture file. */
typedef int (*vt_atlas_scene_open_fn)(void *user, const char *path, struct vt_source *out,
                                      struct vts_error *err);

/* Receives one warning, a line without the tool's prefix ("'a.obj':7: material 'x' is not defined
 * in any mtllib: constant grey"). */
typedef void (*vt_atlas_scene_warn_fn)(void *user, const char *message);

struct vt_atlas_scene_options {
    uint32_t max_textures; /* distinct texture files (more fail with VTS_ERR_LIMIT) */
    size_t max_line_bytes; /* OBJ/MTL/list logical line */
    bool missing_skip;     /* a missing texture is a warning (the layer falls back to a fill) */
    vt_atlas_scene_open_fn open; /* required */
    void *open_user;
    vt_atlas_scene_warn_fn warn; /* may be NULL: warnings are dropped */
    void *warn_user;
};

struct vt_atlas_scene_index; /* private lookup tables */

/* Zero it before the first scan; release it after success or failure. */
struct vt_atlas_scene {
    struct vt_atlas_material *materials; /* in order of first use */
    uint32_t material_count;
    struct vt_atlas_texture *textures;
    uint32_t texture_count;
    char **deps; /* every file read (OBJ, MTL, list, textures), in order, once each */
    size_t dep_count;
    struct vt_atlas_scene_index *index;
};

/* Each adds to *scene, which several calls of the same kind may fill. Return 0 or a negative
 * status (VTS_ERR_IO, VTS_ERR_BAD_INPUT, VTS_ERR_LIMIT, VTS_ERR_NOMEM or the open callback's) with
 * a message naming the file and line ("'a.mtl':12: map_Kd 'x.png': No such file or directory").
 * Not thread-safe on one scene. */

/* The materials the faces of obj_path use, resolved against the MTL files its mtllib lines name
 * (a material first used by an earlier OBJ keeps what that OBJ's libraries gave it). */
int vt_atlas_scene_scan_obj(struct vt_atlas_scene *scene, const char *obj_path,
                            const struct vt_atlas_scene_options *o, struct vts_error *err);

/* One entry per line of list_path (blank lines and '#' comments skipped), named by the line, with
 * the file (resolved against list_path's directory) as its diffuse texture. */
int vt_atlas_scene_scan_list(struct vt_atlas_scene *scene, const char *list_path,
                             const struct vt_atlas_scene_options *o, struct vts_error *err);

/* One entry per file, named by its path. */
int vt_atlas_scene_scan_files(struct vt_atlas_scene *scene, char *const *paths, uint32_t count,
                              const struct vt_atlas_scene_options *o, struct vts_error *err);

/* Frees everything *scene holds and zeroes it. Accepts NULL and a zeroed scene. */
void vt_atlas_scene_release(struct vt_atlas_scene *scene);

#endif
