/* Atlas layout (atlas.json): where every texture of a scene lies in one virtual texture, per layer.
 * Written by vt-atlas, read by vt-offset (texture coordinates) and vt-tiles --layout (texels).
 * The schema is documented in docs/atlas-format.md; this reader checks every field and every
 * rectangle, so a layout that loads is safe to use without further checks.
 *
 * Coordinates: level-0 texels of the atlas, x to the right, y DOWN (row 0 is the top row, as in
 * the store and in image files). OBJ texture coordinates have v UP (v = 0 is the bottom row of an
 * image). An entry's material coordinate (u, v) maps to the atlas coordinate (U, V), also v up:
 *
 *   U = (x + (u - origin_u) * width) / atlas_width
 *   V = 1 - (y + (repeat_v - (v - origin_v)) * height) / atlas_height
 *
 * so texel (i, j) of a texture (j from the top) whose centre is u = (i + 0.5) / width,
 * v = 1 - (j + 0.5) / height lands on the centre of atlas texel (x + i, y + j) when scale is 1
 * and there is one copy. With wrap replication the texture is copied repeat_u x repeat_v times
 * side by side from (x, y), and origin_u/origin_v is the integer part of the smallest u/v the
 * material uses, so its whole UV range [origin, origin + repeat] lands inside the copies.
 *
 * Crop (vt-atlas packs only the texels the charts of a material use): the copies form a block of
 * width * repeat_u x height * repeat_v texels, and the entry holds only the rectangle
 * [crop_x, crop_x + crop_width) x [crop_y, crop_y + crop_height) of that block (crop_y counted from
 * the block's top row), placed at (x, y). The formula becomes
 *
 *   U = (x - crop_x + (u - origin_u) * width) / atlas_width
 *   V = 1 - (y - crop_y + (repeat_v - (v - origin_v)) * height) / atlas_height
 *
 * and the covered UV range is origin_u + crop_x / width .. origin_u + (crop_x + crop_width) / width
 * (v: origin_v + repeat_v - (crop_y + crop_height) / height .. origin_v + repeat_v - crop_y /
 * height). Without "crop" in the file the entry holds the whole block (crop 0, 0, width * repeat_u,
 * height * repeat_v), as before.
 *
 * Wrap (vt-atlas --wrap split and the automatic choice for large repeats, and every entry that
 * holds its whole texture for materials without -clamp on): the entry holds one whole copy of a
 * texture the scene repeats; vt-offset moved every face into its unit cell and cut the faces
 * that cross integer UV lines, each piece moved into [0,1]. Its gutter, its cell padding and the
 * tile borders at its edges repeat the texture's opposite edge (texel -1 is texel width - 1), and
 * its mip chain is filtered with wrap-around, so that bilinear and trilinear filtering across a cut
 * read what the repeating texture shows there. A wrap entry has repeat 1 and no crop.
 *
 * The entry's cell may start before (x, y) (cell_left/cell_top, "cell_x"/"cell_y" in the file):
 * vt-atlas --gutter leaves texels around a texture that shares a tile, which the compositor
 * fills with the texture's own edge so that filtering never reads a neighbour. */
#ifndef VT_LAYOUT_H
#define VT_LAYOUT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"

#ifdef __cplusplus
extern "C" {
#endif

#define VT_LAYOUT_FORMAT     "vtpipe-atlas"
#define VT_LAYOUT_VERSION    1
#define VT_LAYOUT_MAX_LAYERS 16

/* One layer of the atlas (diffuse, normal, specular...): one store layer. */
struct vt_layout_layer {
    char *name;      /* unique, 1..63 bytes [A-Za-z0-9_-]: "diffuse", "normal", "specular"... */
    char *map;       /* the MTL statement it comes from: "map_Kd", "norm", "map_Ks", "map_d"... */
    uint32_t colour; /* enum vts_colour of the layer: srgb, linear, normal or data */
};

/* What one entry shows in one layer: a texture file, or a constant colour. */
struct vt_layout_texture {
    char *path;             /* as written in the layout; NULL: a constant fill */
    char *resolved;         /* path resolved against the layout file's directory; NULL with path */
    uint32_t width, height; /* pixel size of the file (vt-tiles checks it when it opens it) */
    double fill[4];         /* RGBA in 0..1 when path is NULL (e.g. Kd for diffuse) */
};

/* One material (or one texture of a --textures/--grid list) and its place in the atlas. All the
 * layers of an entry share its rectangle. */
struct vt_layout_entry {
    char *name;     /* material name, unique among all names and aliases */
    char **aliases; /* other material names that use this entry (materials with the
                       same textures in every layer and the same scale share one
                       cell); NULL when alias_count is 0. Unique like names */
    uint32_t alias_count;
    uint32_t x, y;               /* top-left texel of the first copy */
    uint32_t width, height;      /* one copy of the texture in the atlas, in texels (>= 1) */
    uint32_t repeat_u, repeat_v; /* copies side by side (wrap replication); 1 when not wrapped */
    int32_t origin_u, origin_v;  /* integer UV origin of the copies (see the formula above) */
    uint32_t cell_width;         /* exclusive cell at (x - cell_left, y - cell_top): no other */
    uint32_t cell_height;        /* entry's cell overlaps it; it holds every copy */
    uint32_t cell_left;          /* texels of the cell before x and above y: the gutter (0 by */
    uint32_t cell_top;           /* default; atlas.json "cell_x" = x - cell_left, "cell_y") */
    uint32_t alignment;          /* power of two dividing x, y, the cell's corner and its size */
    double scale;                /* atlas texels per source pixel: a power of two 2^-16..2^16
                                    (density rescaling; 1 normally). width = ceil(source width *
                                    scale) for scale < 1 (the source's own mip level), source
                                    width * scale for scale >= 1 (texels replicated) */
    uint32_t crop_x, crop_y;     /* first texel of the block of copies the entry holds (0) */
    uint32_t crop_width;         /* texels of the block it holds (file "crop": [x, y, w, h]); */
    uint32_t crop_height;        /* 0 in a layout built in memory means the whole block:
                                    vt_layout_index() and the reader fill in width * repeat_u,
                                    height * repeat_v. The cell holds crop_width x crop_height
                                    texels at (x, y) */
    bool wrap;                   /* one copy of a repeating texture: gutter, padding, borders and
                                    mips wrap around (file "wrap": true); repeat 1, no crop */
    uint32_t group;              /* 0: a texture of its own. Entries sharing a non-zero group are
                                    one continuous surface laid edge to edge (vt-atlas --grid
                                    terrain pieces): borders and mip filtering cross between them
                                    and clamp only at the outer edge of the group */
    struct vt_layout_texture *textures; /* one per layer, in layer order */
};

/* A material's alpha mode (atlas.json "alpha"): how a renderer draws its coverage. */
enum vt_layout_alpha {
    VT_LAYOUT_ALPHA_NONE,  /* "none": opaque (alpha, if any, is not coverage) */
    VT_LAYOUT_ALPHA_TEST,  /* "test": cut-out (map_d, or binary alpha in map_Kd): discard below
                              0.5, no sorting */
    VT_LAYOUT_ALPHA_BLEND, /* "blend": d < 1: blended, drawn sorted after the opaque faces */
};

/* What one material needs to be drawn (atlas.json "materials"; docs/atlas-format.md): its entry,
 * which layers hold a real map of it, its MTL constants and its alpha mode. Several materials
 * may share an entry (aliases) and differ here. */
struct vt_layout_material {
    char *name;          /* the material name: its entry's name or one of its aliases */
    uint32_t entry;      /* index into entries (file: "entry", the entry's name) */
    uint32_t layer_mask; /* bit k: layer k holds a texture of it (not a fill) (file: "layers",
                            their names in layer order) */
    double kd[3], ka[3], ks[3], ke[3]; /* finite, >= 0 */
    double ns;                         /* specular exponent, finite, >= 0 */
    double d;                          /* opacity 0..1 */
    uint32_t illum;                    /* MTL illumination model 0..100 */
    uint32_t alpha;                    /* enum vt_layout_alpha */
};

/* A material whose diffuse is a Wang pack (the MTL statement "vt_wang PACK.vts [scale S]",
 * docs/wang.md): it has no entry and no atlas space (atlas.json "wang_materials"); vt-offset keeps
 * its faces' texture coordinates and writes the statement. m holds its constants (m.entry and
 * m.layer_mask unused: 0). Its name is none of the entries' names or aliases. */
struct vt_layout_wang {
    struct vt_layout_material m; /* m.name: the material name */
    char *pack;                  /* the pack as written (relative to atlas.json unless absolute) */
    char *resolved;              /* pack resolved against the layout file's directory */
    double scale;                /* output tiles per texture coordinate unit, finite, > 0 */
};

/* One name of the name index: entries[entry].name when alias is 0, else
 * entries[entry].aliases[alias - 1]. */
struct vt_layout_name {
    uint32_t entry, alias;
};

/* A whole layout; caller-owned, freed with vt_layout_release(). */
struct vt_layout {
    uint32_t width, height; /* atlas level-0 size in texels */
    uint32_t tile_content;  /* tile content edge vt-tiles must use (a power of two) */
    uint32_t border;        /* tile border vt-tiles must use */
    char *generator;        /* "vt-atlas 0.1.0" or NULL */
    struct vt_layout_layer *layers;
    uint32_t layer_count; /* 1..VT_LAYOUT_MAX_LAYERS */
    struct vt_layout_entry *entries;
    uint32_t entry_count;
    struct vt_layout_name *by_name; /* every entry name and alias, sorted (filled by the reader
                                       and by vt_layout_index()); used by vt_layout_find() */
    size_t name_count;              /* entries plus aliases */
    struct vt_layout_material *materials; /* NULL (material_count 0: a layout written before
                                             materials existed, or built without them), or one
                                             per name of by_name, in the same order: sorted by
                                             name, so materials[i] is the material of by_name[i] */
    uint32_t material_count;
    struct vt_layout_wang *wangs; /* pack materials, sorted by name (byte order); NULL when none */
    uint32_t wang_count;
};

/* Limits against hostile files; exceeding one fails with VTS_ERR_LIMIT and a message. */
struct vt_layout_limits {
    uint64_t max_file_bytes; /* size of atlas.json (default 1 GiB) */
    uint32_t max_entries;    /* textures/materials: entries, and entries plus aliases (default
                                2^20) */
    uint32_t max_edge;       /* atlas width and height (default 2^24) */
};
void vt_layout_limits_default(struct vt_layout_limits *limits);

/* Reads and validates the layout at path into *layout (overwritten: release it after success or
 * failure). limits may be NULL (defaults). Checks: format and version, every field's type and
 * range, layer names unique, entry names and aliases all unique and non-empty, the crop inside the
 * block of copies, a wrap entry with repeat 1 and its whole texture, the crop (without one every
 * copy) inside its cell, every cell inside the atlas, alignment a power of two dividing x/y/cell
 * sizes, no two cells overlapping, texture sizes non-zero. An entry without "crop" gets the whole
 * block (crop 0, 0, width * repeat_u, height * repeat_v). Returns 0, VTS_ERR_IO, VTS_ERR_BAD_INPUT
 * ("'atlas.json': entries[3].x: ..."), VTS_ERR_LIMIT or VTS_ERR_NOMEM. */
int vt_layout_read(const char *path, const struct vt_layout_limits *limits,
                   struct vt_layout *layout, struct vts_error *err);

/* As vt_layout_read() on size bytes in memory; name is used in messages and as the base of
 * relative texture paths. */
int vt_layout_parse_memory(const void *data, size_t size, const char *name,
                           const struct vt_layout_limits *limits, struct vt_layout *layout,
                           struct vts_error *err);

/* Checks a layout built in memory (the same checks as the reader) and builds its name index.
 * Call before vt_layout_write() or vt_layout_find() on a layout that was not read. An entry whose
 * crop_width or crop_height is 0 gets the whole block of copies as its crop (filled in). */
int vt_layout_index(struct vt_layout *layout, struct vts_error *err);

/* As vt_layout_index(), with messages naming name ("'atlas.json': the cells of 'a' and 'b'
 * overlap"). */
int vt_layout_check(struct vt_layout *layout, const char *name, struct vts_error *err);

/* Writes the layout as JSON to path atomically (temporary file + rename). Texture paths are
 * written as they are in texture.path (make them relative to the output's directory first if
 * the layout should move with it). Calls vt_layout_index() first. */
int vt_layout_write(const char *path, struct vt_layout *layout, struct vts_error *err);

/* Frees everything *layout holds (strings, arrays) and zeroes it. Accepts NULL. */
void vt_layout_release(struct vt_layout *layout);

/* The entry named name (its name or one of its aliases), or NULL. O(log n) after
 * vt_layout_read() or vt_layout_index(). */
const struct vt_layout_entry *vt_layout_find(const struct vt_layout *layout, const char *name);

/* Top-left texel of the entry's cell (x - cell_left, y - cell_top). */
static inline uint32_t vt_layout_cell_x(const struct vt_layout_entry *e)
{
    return e->x - e->cell_left;
}
static inline uint32_t vt_layout_cell_y(const struct vt_layout_entry *e)
{
    return e->y - e->cell_top;
}

/* Index of the layer named name, or -1. */
int vt_layout_layer_index(const struct vt_layout *layout, const char *name);

/* Maps a material coordinate (u, v) of entry e to atlas coordinates (*au, *av) in double precision
 * with the formula at the top of this file (with the crop). Does not check that (u, v) lies in the
 * crop (vt_layout_uv_covered()). */
void vt_layout_map_uv(const struct vt_layout *layout, const struct vt_layout_entry *e, double u,
                      double v, double *au, double *av);

/* True when (u, v) lies inside the UV range e covers (with its crop; see the top of this file),
 * bounds included. */
bool vt_layout_uv_covered(const struct vt_layout_entry *e, double u, double v);

/* The material named name, or NULL (also when the layout has no materials). O(log n). */
const struct vt_layout_material *vt_layout_material_find(const struct vt_layout *layout,
                                                         const char *name);

/* The pack material named name, or NULL. O(log n) (wangs sorted by name: vt_layout_check() checks
 * it, vt_layout_sort_materials() sorts them). */
const struct vt_layout_wang *vt_layout_wang_find(const struct vt_layout *layout, const char *name);

/* Allocates layout->wangs: count zeroed pack materials (each d 1, scale 1), replacing any earlier
 * ones. Strings are strdup()ed by the caller and freed by vt_layout_release(). Returns 0 or
 * VTS_ERR_NOMEM. */
int vt_layout_alloc_wangs(struct vt_layout *layout, uint32_t count, struct vts_error *err);

/* The atlas.json name of a layer colour (enum vts_colour: "srgb", "linear", "normal", "data"; "?"
 * out of range). */
const char *vt_layout_colour_name(uint32_t colour);

/* The name of alpha mode a ("none", "test", "blend"; "?" out of range). */
const char *vt_layout_alpha_name(uint32_t alpha);

/* Sorts layout->materials by name (writers fill them in any order; the checks want them sorted).
 */
void vt_layout_sort_materials(struct vt_layout *layout);

/* The materials as one compact JSON array, the same objects as atlas.json's "materials" (name,
 * entry, layers, Kd, Ka, Ks, Ke, Ns, d, illum, alpha), for the store's metadata key
 * VT_LAYOUT_MATERIALS_KEY (vt-tiles --layout). "[]" for a layout without materials. Returns a
 * malloc'ed string (free() it), or NULL with err filled: VTS_ERR_NOMEM, or VTS_ERR_LIMIT when the
 * text would exceed max_bytes (the store's metadata limit: the caller passes what is left). */
char *vt_layout_materials_meta(const struct vt_layout *layout, size_t max_bytes,
                               struct vts_error *err);

/* The store metadata key of vt_layout_materials_meta(). */
#define VT_LAYOUT_MATERIALS_KEY "materials"

/* Allocation helpers for writers (vt-atlas, tests): zeroed arrays of count layers/entries, and
 * per entry layer_count textures. Return 0 or VTS_ERR_NOMEM. Strings are strdup()ed by the
 * caller and freed by vt_layout_release(), as are aliases (a malloc()ed array of strdup()ed
 * strings). */
int vt_layout_alloc(struct vt_layout *layout, uint32_t layer_count, uint32_t entry_count,
                    struct vts_error *err);

/* Allocates layout->materials: count zeroed materials (each d 1), replacing any earlier ones.
 * Names are strdup()ed by the caller and freed by vt_layout_release(). Returns 0 or
 * VTS_ERR_NOMEM. */
int vt_layout_alloc_materials(struct vt_layout *layout, uint32_t count, struct vts_error *err);

#ifdef __cplusplus
}
#endif
#endif
