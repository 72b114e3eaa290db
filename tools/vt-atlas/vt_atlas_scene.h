/* vt-atlas input scanning: the materials a scene's faces use (from OBJ + MTL files), or the
 * textures of a --textures list or a --grid, each with its texture files per layer (sizes read
 * from the image headers only), its Kd/Ks/Ka/d constants, its UV range and the areas used for
 * texel density. Also the list of every file read (for --deps). */
#ifndef VT_ATLAS_SCENE_H
#define VT_ATLAS_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"

/* Atlas layers in layout order; a scene gets only those its used materials have textures for. */
enum vt_atlas_kind {
    VT_ATLAS_DIFFUSE,  /* map_Kd */
    VT_ATLAS_NORMAL,   /* norm, map_Bump, bump */
    VT_ATLAS_SPECULAR, /* map_Ks */
    VT_ATLAS_ALPHA,    /* map_d */
    VT_ATLAS_AMBIENT,  /* map_Ka */
    VT_ATLAS_DISP,     /* disp */
    VT_ATLAS_KIND_COUNT
};

/* Layer name ("diffuse"), MTL statement ("map_Kd") and enum vts_colour of a kind. */
const char *vt_atlas_kind_name(unsigned kind);
const char *vt_atlas_kind_map(unsigned kind);
uint32_t vt_atlas_kind_colour(unsigned kind);

/* One texture file. Two paths that name the same file (same device and inode: "tex/a.png" and
 * "./tex/../tex/a.png", a link, MTL files in two directories) are one texture, so that the
 * materials using it can share one atlas entry. */
struct vt_atlas_texture {
    char *path; /* as first read (resolved against the MTL or list file's directory) */
    char *id;   /* "device:inode" of the file */
    uint32_t width, height, channels;
};

struct vt_atlas_material {
    char *name;
    const char *obj;                      /* first file whose faces use it (for messages) */
    uint64_t first_line;                  /* of the first face using it */
    bool defined;                         /* found in an MTL (else constant grey) */
    double fill[VT_ATLAS_KIND_COUNT][4];  /* constant of each layer when it has no texture */
    int32_t texture[VT_ATLAS_KIND_COUNT]; /* index into textures (one per file), or -1 */
    bool has_uv;                          /* some face corner has a texcoord */
    double umin, umax, vmin, vmax;        /* texcoord range of its faces */
    double uv_area, world_area;           /* summed over its triangles with texcoords */
};

struct vt_atlas_scan_options {
    uint32_t max_textures; /* distinct texture files */
    uint64_t max_pixels;   /* per input image */
    size_t max_line_bytes; /* OBJ/MTL logical line */
    bool missing_skip;     /* a missing texture is a warning (layer falls back to a fill) */
    void (*warn)(const char *message); /* warnings (may be NULL) */
};

struct vt_atlas_scene {
    struct vt_atlas_material *materials; /* in order of first use */
    uint32_t material_count;
    struct vt_atlas_texture *textures;
    uint32_t texture_count;
    char **deps; /* every file read, in order, once each */
    size_t dep_count;
    void *index; /* private lookup tables */
};

/* Each reads into *scene (zero it first; it may be filled by several calls of the same kind and
 * must be released after success or failure). Return 0 or a negative status with a message
 * naming the file and line ("'a.mtl':12: map_Kd 'x.png': No such file or directory"). */
int vt_atlas_scan_obj(struct vt_atlas_scene *scene, const char *obj_path,
                      const struct vt_atlas_scan_options *o, struct vts_error *err);
/* One entry per line of list_path (blank lines and '#' comments skipped), named by the line. */
int vt_atlas_scan_list(struct vt_atlas_scene *scene, const char *list_path,
                       const struct vt_atlas_scan_options *o, struct vts_error *err);
/* One entry per file, named by its path. */
int vt_atlas_scan_files(struct vt_atlas_scene *scene, char *const *paths, uint32_t count,
                        const struct vt_atlas_scan_options *o, struct vts_error *err);

void vt_atlas_scene_release(struct vt_atlas_scene *scene);

#endif
