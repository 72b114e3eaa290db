/* Private state header of module vt_offset: the state of one rewrite, shared by its parts: the
 * driver (vt_offset.c), pass 1 (vt_offset_scan.c), pass 2 (vt_offset_write.c) and the buffered
 * output (vt_offset_run.c). */
#ifndef VT_OFFSET_IMPL_H
#define VT_OFFSET_IMPL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_cut.h"
#include "vt_error.h"
#include "vt_layout.h"
#include "vt_offset.h"
#include "vt_offset_src.h"

#define VT_OFFSET_OUT_CHUNK   ((size_t)1 << 20)
#define VT_OFFSET_NONE        UINT32_MAX       /* no material / no extra */
#define VT_OFFSET_MAT_NONE    UINT32_MAX       /* before any usemtl */
#define VT_OFFSET_MAT_MISSING (UINT32_MAX - 1) /* usemtl of a material the layout lacks */
#define VT_OFFSET_MAT_WANG                                                                         \
    (UINT32_MAX - 2) /* a pack material (layout->wangs): its faces                                 \
                        keep their texture coordinates */

struct vt_offset_extra {
    uint32_t key;  /* key index (r->keys) */
    uint32_t next; /* next extra of the same vt, or VT_OFFSET_NONE */
};

/* What a kept face's texture coordinates become: an entry and a whole-repeat move (the chart's,
 * plus the cell's on a wrap entry). Every vt gets one output copy per key its faces use. */
struct vt_offset_key {
    uint32_t entry;
    double du, dv;
};

/* The faces of the OBJ as pass 1 read them (absolute 0-based indices), for the charts and cuts
 * (lib/chart). */
struct vt_offset_faces {
    uint64_t *start; /* count + 1 offsets into the corner arrays */
    uint32_t *pos, *tex, *nrm;
    uint32_t *group; /* material name (slot in the layout's name index), VT_CHART_NONE */
    uint32_t *entry; /* layout entry, or VT_OFFSET_MAT_NONE / VT_OFFSET_MAT_MISSING */
    uint64_t *line;  /* of the f statement */
    uint32_t count;
    uint64_t corners;
    size_t face_cap, corner_cap;
};

struct vt_offset_repl {
    size_t s, e; /* bytes of the line to replace */
    int64_t value;
};

struct vt_offset_run {
    const struct vt_layout *layout;
    const struct vt_offset_options *opt;
    const struct vt_offset_sink *out;
    struct vt_offset_src src;
    const char *name; /* the input, for messages (also between the passes) */
    unsigned digits;
    /* pass 1 */
    uint64_t nv, nvn;
    uint32_t nvt, cap;
    double *uv;          /* u v per vt */
    uint32_t *first;     /* key of the first face using the vt, or VT_OFFSET_NONE */
    uint32_t *head;      /* its first extra key, or VT_OFFSET_NONE */
    uint32_t *new_index; /* 0-based index of its first copy in the output (set in pass 2) */
    struct vt_offset_extra *extra;
    uint32_t extra_count, extra_cap;
    uint32_t mat; /* current material (entry index, VT_OFFSET_MAT_NONE or VT_OFFSET_MAT_MISSING) */
    uint32_t mat_group; /* its name's slot in the layout's name index, or VT_CHART_NONE */
    uint32_t *corner;   /* the face being read: 3 indices per corner */
    uint32_t corner_cap;
    struct vt_offset_faces faces;
    /* after pass 1 (vt_offset_mesh.c) */
    struct vt_offset_key *keys;
    uint32_t key_count, key_cap;
    uint32_t *face_key; /* per face: its key (kept faces with texcoords), VT_OFFSET_NONE */
    struct vt_cut_result cut;
    bool any_changed;       /* some face is replaced: v and vn indices are renumbered */
    double *new_pos;        /* 3 per new position (cut.vertices) */
    uint32_t *normal_index; /* sorted vn indices replaced faces interpolate (NULL: none) */
    double *normals;        /* 3 per normal_index entry */
    size_t normal_count;
    uint32_t *v_out, *vn_out; /* output index of each input v / vn (any_changed only) */
    uint32_t *new_pos_out;    /* output index of each new position, VT_OFFSET_NONE: not yet */
    uint64_t in_v, in_vn, out_v, out_vn; /* pass 2 counters */
    uint32_t in_face;
    char *mat_name;        /* name on the current usemtl line */
    uint64_t mat_line;     /* its line */
    bool *slot_used;       /* per name slot: some face uses it (opt->used only) */
    uint64_t unknown_line; /* usemtl line of the last name added to opt->used->unknown */
    uint32_t unknown_cap;
    bool any_mtllib;
    char *clean; /* a line as vt_obj sees it (usemtl, mtllib) */
    size_t clean_cap;
    /* pass 2 */
    uint32_t in_vt;  /* vt statements copied so far */
    uint64_t out_vt; /* vt lines written so far */
    bool mtllib_written;
    struct vt_offset_repl *repl;
    size_t repl_cap;
    unsigned char *obuf;
    size_t olen;
    struct vt_offset_stats stats;
};

/* Writes the buffered output (r->obuf) to r->out. */
int vt_offset_run_flush(struct vt_offset_run *r, struct vts_error *err);

/* Appends n bytes to the output (buffered in VT_OFFSET_OUT_CHUNK pieces). */
int vt_offset_run_put(struct vt_offset_run *r, const void *data, size_t n, struct vts_error *err);

/* Appends a string to the output. */
int vt_offset_run_str(struct vt_offset_run *r, const char *s, struct vts_error *err);

/* The name on a usemtl (or mtllib) line as vt_obj reads it (the rest of the line, trimmed) in
 * *name, which points into r->clean and stays valid until the next call. */
int vt_offset_run_usemtl_name(struct vt_offset_run *r, const unsigned char *line, size_t n,
                              char **name, struct vts_error *err);

/* The entry index of material name in the layout, VT_OFFSET_MAT_WANG for a pack material, or
 * VT_OFFSET_MAT_MISSING. */
uint32_t vt_offset_run_material(const struct vt_offset_run *r, const char *name);

/* The slot of name in the layout's name index (a number per material name, entries and aliases
 * alike: what the charts are grouped by, as vt-atlas groups them), or VT_CHART_NONE. */
uint32_t vt_offset_run_name_slot(const struct vt_offset_run *r, const char *name);

/* True when every layer of e is a constant fill (see vt_offset_run.c). */
bool vt_offset_run_constant_entry(const struct vt_layout *l, const struct vt_layout_entry *e);

/* VTS_ERR_IO: the file changed between the passes (at the current line). */
int vt_offset_run_changed_error(struct vt_offset_run *r, struct vts_error *err);

/* ---- pass 1 (vt_offset_scan.c): counts v and vn, parses every vt and face, checks each index,
 * the material of each face with texture coordinates (it must be in the layout) and that each
 * coordinate lies in the UV range its material covers, and records for every vt the materials of
 * the faces that use it. ---- */

/* Scans one raw logical line (r->src.line is its number). Returns 0 or a negative status. */
int vt_offset_scan_line(struct vt_offset_run *r, const unsigned char *line, size_t n,
                        struct vts_error *err);

/* ---- after pass 1 (vt_offset_mesh.c): the faces kept for the charts, the charts and their
 * moves, the cuts on wrap entries, the keys of every vt, and the values of the v and vn that new
 * positions and normals interpolate (read by one more pass over the file when there are cuts).
 * ---- */

/* Pass 1 keeps the face it just read (line r->src.line, the current material): corner_count
 * corners of 3 absolute indices each (v, vt, vn; VT_OFFSET_NONE when missing). */
int vt_offset_mesh_add_face(struct vt_offset_run *r, const uint32_t *corners, uint32_t corner_count,
                            struct vts_error *err);

/* After pass 1: charts, moves, cuts, keys and coverage checks; reads the positions and normals
 * the cuts need (path/mem: the input, as for the passes). */
int vt_offset_mesh_resolve(struct vt_offset_run *r, const char *path, const void *mem, size_t size,
                           struct vts_error *err);

/* Frees what the mesh stage holds. */
void vt_offset_mesh_release(struct vt_offset_run *r);

/* The atlas coordinate of texture coordinate (u, v) (already moved) on entry e. */
void vt_offset_map(const struct vt_offset_run *r, uint32_t entry, double u, double v, double *au,
                   double *av);

/* ---- pass 2 (vt_offset_write.c): copies the OBJ text line by line to the output, replacing used
 * vt by their atlas coordinates (one more vt line per extra material), renumbering the texture
 * indices of f and l lines and renaming usemtl and mtllib (see vt_offset.h). ---- */

/* Writes the rewrite of one raw logical line. Returns 0 or a negative status. */
int vt_offset_write_line(struct vt_offset_run *r, const unsigned char *line, size_t n,
                         struct vts_error *err);

#endif
