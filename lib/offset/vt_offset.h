/* The texture coordinate rewriter of vt-offset: puts the `vt` of an OBJ scene onto an atlas
 * (struct vt_layout) in double precision, streaming the text. Behaviour and reasons:
 * docs/cli/vt-offset.md and docs/real-scenes.md.
 *
 * Pass 1 counts v/vn, parses every `vt` and every face, checks each index and the material of
 * each face that has texture coordinates (it must be in the layout), and keeps the faces' indices.
 * Then (lib/chart) the faces of each material are grouped into charts, as vt-atlas groups them,
 * and each chart is moved by whole repeats so that its UV box starts in [0,1); on a "wrap" entry
 * every face crossing an integer UV line is cut there, each piece moved into [0,1], and the faces
 * next to a cut get its points as extra corners (no T-junctions). Every written coordinate is
 * checked against the UV range its entry covers. When there are cuts, one more pass reads the v
 * and vn that new vertices interpolate. Pass 2 copies the text line by line:
 *   - a `vt` used by kept faces is replaced by its atlas coordinate for the first (entry, move)
 *     that uses it, and one more `vt` line follows it for each other (entry, move) (so indices
 *     stay backward); a `vt` no kept face uses is copied unchanged;
 *   - `f` (and `l`) lines whose indices change are rewritten with the new indices, in the same
 *     style (positive or negative); position and normal indices change only when new lines were
 *     inserted before their lines;
 *   - a cut or split face is replaced by the new `v` lines it is the first to use, one `vn` and
 *     one `vt` per corner of its pieces, and one `f` line per piece (positive indices);
 *   - `usemtl X` is kept (options.material NULL) or becomes `usemtl <material>`; the first `mtllib`
 * names the new MTL, later ones are turned into comments ("# " before them); without any, an mtllib
 * line is written first;
 *   - every other line is copied byte for byte, CRLF and '\' continuations included.
 * Memory: about 28 bytes per `vt` plus 8 per extra copy, 24 bytes per face and 12 per face
 * corner (the charts), 8 per v and vn when faces are cut; never the text. */
#ifndef VT_OFFSET_H
#define VT_OFFSET_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_layout.h"
#include "vt_obj.h"

#ifdef __cplusplus
extern "C" {
#endif

#define VT_OFFSET_MATERIAL "vt_atlas"
/* vt-offset warns when the float32 round-off of a written coordinate exceeds this, in texels. */
#define VT_OFFSET_F32_WARN_TEXELS 0.125

/* The materials the faces of a rewrite use (each face after a usemtl), filled when
 * vt_offset_options.used is set; release with vt_offset_used_release(). */
struct vt_offset_used {
    uint32_t *slots; /* names of the layout's name index (by_name, sorted: with materials,
                        materials[slot] is the material), in slot order */
    uint32_t slot_count;
    char **unknown; /* names without an entry in the layout, sorted, each once: the layout's
                       pack materials (layout->wangs) and names it does not have (faces
                       without texcoords: their material is not checked) */
    uint32_t unknown_count;
};

/* Frees what *used holds and zeroes it. Accepts NULL. */
void vt_offset_used_release(struct vt_offset_used *used);

struct vt_offset_options {
    const char *layout_name;     /* the layout file, for messages ("atlas.json") */
    const char *mtllib;          /* written on the mtllib line (relative to the output OBJ) */
    const char *material;        /* written on usemtl lines (VT_OFFSET_MATERIAL); NULL: usemtl
                                    lines are copied unchanged (each face keeps its material) */
    struct vt_offset_used *used; /* NULL, or filled with the materials the faces use */
    unsigned digits;             /* decimal places of the written coordinates, 1..17; 0: default */
    struct vt_obj_limits limits; /* line length and vertex counts (vt_obj_limits_default) */
};

/* Defaults: layout_name "atlas.json", mtllib "out.mtl", material VT_OFFSET_MATERIAL, digits 0. */
void vt_offset_options_default(struct vt_offset_options *opt);

/* Decimal places that keep the rounding of written coordinates within 1e-4 level-0 texel of the
 * larger atlas edge (at least 6): 8 for 4096, 10 for 2^20, 11 for 2^24. */
unsigned vt_offset_default_digits(const struct vt_layout *layout);

/* Where the rewritten OBJ goes: write() gets the text in order, in pieces of up to 1 MiB. It
 * returns 0 or a negative status with err filled. */
struct vt_offset_sink {
    int (*write)(void *user, const void *data, size_t size, struct vts_error *err);
    void *user;
};

struct vt_offset_stats {
    uint64_t lines;            /* physical lines read */
    uint64_t vt_lines;         /* vt statements in the input */
    uint64_t vt_rewritten;     /* vt statements replaced by atlas coordinates */
    uint64_t vt_duplicated;    /* extra vt lines written for faces of other materials */
    uint64_t vt_unused;        /* vt statements no face uses (copied unchanged) */
    uint64_t vt_wang;          /* vt statements of pack materials' faces (copied as written;
                                  not in vt_rewritten) */
    uint64_t faces;            /* f statements */
    uint64_t faces_rewritten;  /* f and l statements whose texture indices changed */
    uint64_t faces_without_vt; /* f statements without any texture index (copied unchanged) */
    uint64_t charts;           /* charts of the faces with texcoords (lib/chart) */
    uint64_t charts_moved;     /* of those, moved by whole repeats */
    uint64_t faces_cut;        /* faces of wrap entries cut on integer UV lines */
    uint64_t faces_split;      /* faces next to a cut that got the cut's points as corners */
    uint64_t pieces;           /* faces written for the cut faces */
    uint64_t faces_written;    /* f lines written for cut and split faces */
    uint64_t positions_added;  /* v lines appended (points on cut edges and inside faces) */
    uint64_t vt_added;         /* vt lines written for cut and split faces */
    uint64_t vn_added;         /* vn lines written for cut and split faces */
    unsigned digits;           /* decimal places used */
    double max_error;     /* worst |written text read back as double - exact double|, in level-0
                             texels of the atlas (u errors times width, v errors times height) */
    double max_error_f32; /* the same for the text read back as float32 */
    uint64_t max_error_f32_line; /* input line of the vt with the worst float32 error (0: none) */
};

/* Rewrites the OBJ file at obj_path onto layout (read or indexed) into out. Returns 0, or
 * VTS_ERR_IO, VTS_ERR_BAD_INPUT ("'scene.obj':12: ..."), VTS_ERR_LIMIT, VTS_ERR_NOMEM or a status
 * of out->write; stats (may be NULL) is filled on success. */
int vt_offset_rewrite(const char *obj_path, const struct vt_layout *layout,
                      const struct vt_offset_options *opt, const struct vt_offset_sink *out,
                      struct vt_offset_stats *stats, struct vts_error *err);

/* As vt_offset_rewrite() on size bytes in memory; name is used in messages. */
int vt_offset_rewrite_memory(const void *data, size_t size, const char *name,
                             const struct vt_layout *layout, const struct vt_offset_options *opt,
                             const struct vt_offset_sink *out, struct vt_offset_stats *stats,
                             struct vts_error *err);

/* The MTL of a rewrite (docs/cli/vt-offset.md, "The MTL"): after header_comment (may be NULL; each
 * line gets "# "), one newmtl per material of used, with its constants from the layout's
 * materials (a layout without them, or a name it lacks: Kd 1 1 1 with maps, 0.8 grey without,
 * opaque), its alpha mode as "vt_alpha MODE", and per layer that holds a map of it the layer's
 * MTL statement naming "<store>#<layer>"; a pack material of the layout (layout->wangs) gets its
 * constants and "vt_wang PACK scale S" with PACK its pack as in wangs[i].pack (the caller makes
 * it relative to the MTL's folder; one token: white space fails with VTS_ERR_BAD_INPUT). Written
 * to out. Returns 0, VTS_ERR_NOMEM, VTS_ERR_BAD_INPUT or out's status. */
int vt_offset_write_mtl(const struct vt_layout *layout, const struct vt_offset_used *used,
                        const char *store, const char *header_comment,
                        const struct vt_offset_sink *out, struct vts_error *err);

/* True when the float32 round-off of stats exceeds VT_OFFSET_F32_WARN_TEXELS. */
bool vt_offset_f32_warning(const struct vt_offset_stats *stats);

#ifdef __cplusplus
}
#endif
#endif
