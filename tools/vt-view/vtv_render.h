/* vt-view renderer: GL objects (programs, framebuffers, page table, physical texture, reference
 * texture, geometry) and the three passes: virtual texture, tile determination, reference. Needs a
 * current GL 3.3 core context. */
#ifndef VTV_RENDER_H
#define VTV_RENDER_H

#include <stdbool.h>
#include <stdint.h>

#include <epoxy/gl.h>

#include "vt_error.h"
#include "vtv_cache.h"
#include "vtv_display.h"
#include "vtv_material.h"
#include "vtv_mesh.h"
#include "vtv_shaders.h"
#include "vtv_wide.h"

/* One shader variant: the programs of one feature set (enum vtv_feature bits). */
struct vtv_variant {
    unsigned features;
    GLuint prog[VTV_PROG_KINDS]; /* 0: not compiled (not needed by this run); the feedback one is
                                    shared (owned by struct vtv_render) */
    uint64_t faces;              /* OBJ faces drawn with it */
};

#define VTV_MAX_VARIANTS 64

/* One physical texture: the layer a map kind is drawn from (vtv_render_set_cache). */
struct vtv_phys_layer {
    bool used;
    bool srgb; /* sRGB layer: GL_SRGB8_ALPHA8 (decoded to linear when sampled) */
    uint32_t
        bc_codec;   /* VTS_CODEC_BC1..BC5 blocks uploaded as stored (vtv_render_bc_format), or 0 */
    bool rebuild_z; /* bc5 blocks of a 3-channel normal layer: the shader rebuilds z from xy */
    struct vtv_texel_format texels; /* what a loaded tile holds (vtv_wide_format; 0: RGBA8) */
};

/* The light (docs/cli/vt-view.md: --light, --light-colour, --ambient); linear values. */
struct vtv_light {
    float dir[3]; /* towards the light, normalised */
    float colour[3];
    float ambient[3];
};

struct vtv_wang_scene;

struct vtv_render {
    uint32_t width, height;       /* main pass */
    uint32_t fb_width, fb_height; /* tile-determination pass */
    struct vtv_variant variants[VTV_MAX_VARIANTS];
    uint32_t variant_count;
    /* tile-determination programs, shared by variants with the same coverage features (their
       key), owned here */
    unsigned feedback_keys[VTV_MAX_VARIANTS];
    GLuint feedback_progs[VTV_MAX_VARIANTS];
    uint32_t feedback_count;
    GLuint vao, vbo;
    GLuint ebo;                          /* the mesh's index buffer (bound to vao), or 0 */
    bool indexed;                        /* the groups address the index buffer (glDrawElements) */
    const struct vtv_mesh_group *groups; /* the scene's (owned by its struct vtv_mesh) */
    uint32_t group_count;
    GLuint fbo, rb_color, rb_fallback, rb_depth;
    GLuint fb_fbo, rb_request, rb_fb_depth;
    GLuint tex_pt, tex_phys[VTV_MAP_COUNT], tex_reference;
    GLenum phys_format[VTV_MAP_COUNT]; /* GL internal format of each physical texture (0: none) */
    GLenum phys_upload[VTV_MAP_COUNT][2]; /* format and type of its texels; type 0: compressed */
    size_t slice_bytes; /* bytes of a layer in a loaded tile (vtv_loader_slice_bytes; 0: RGBA8) */
    struct vtv_display display;    /* range and ramp of the shown colour (vtv_display_choose) */
    int phys_slice[VTV_MAP_COUNT]; /* the layer's slice in a loaded tile (vtv_loader), or -1 */
    uint32_t phys_count;           /* physical textures (loader layers) */
    uint32_t phys_w, phys_h;
    /* store geometry for the uniforms */
    float virt_w, virt_h, content, border, payload;
    int max_level;
    int pt_tiles[2 * VTS_MAX_LEVELS];
    int pt_row[VTS_MAX_LEVELS];
    uint32_t payload_px;
    uint8_t *fallback_pixels; /* width * height */
    bool has_s3tc;
    bool has_srgb_s3tc;
    bool has_rgtc;      /* RGTC (BC4/BC5): GL 3.0 or ARB_texture_compression_rgtc */
    int rebuild_z_mask; /* bit k: map kind k's physical texture holds normal xy only (bc5) */
    bool srgb;        /* the frame is sRGB-encoded (the diffuse layer is sRGB): shading in linear */
    GLenum bc_format; /* the diffuse physical texture's compressed format, or 0 */
    struct vtv_light light;
    float lod_bias; /* levels added to the level of detail of both passes (vtv_stream's) */
    const struct vtv_wang_scene *wang; /* the packs of vt_wang materials (the app's), or NULL */
};

struct vtv_view {
    float mvp[16]; /* column-major */
    float eye[3];  /* camera position (specular highlights) */
    bool trilinear;
    int aniso;     /* taps at most along the footprint (1: off) */
    bool nearest;  /* no filtering: nearest level, nearest texel (a selection store's layers) */
    bool rel;      /* texcoords are level-0 texels relative to tile origin (the 2D view) */
    int origin[2]; /* with rel: that level-0 tile */
    int debug;     /* 0 none, 1 levels, 2 tiles */
};

int vtv_render_init(struct vtv_render *r, uint32_t width, uint32_t height, uint32_t fb_width,
                    uint32_t fb_height, struct vts_error *err);
void vtv_render_free(struct vtv_render *r);

/* The scene's geometry and groups (mesh must outlive the renderer's use of it), and the shader
 * variants of its feature sets for kinds (bit (1 << enum vtv_program_kind)). Returns 0 or a
 * compile error. */
/* Uploads the mesh's vertices again (same count: the 2D view's quad, clipped to the view). */
void vtv_render_update_vertices(struct vtv_render *r, const struct vtv_mesh *mesh);
int vtv_render_set_mesh(struct vtv_render *r, const struct vtv_mesh *mesh, unsigned kinds,
                        struct vts_error *err);

/* Draws group g of the mesh (vao bound): glDrawElements of its indices when the mesh has an
 * index buffer, else glDrawArrays of its vertices. */
void vtv_render_draw_group(const struct vtv_render *r, const struct vtv_mesh_group *g);

/* The variant of features (compiled for kinds when new); NULL and err on a compile error or when
 * there are more than VTV_MAX_VARIANTS. */
struct vtv_variant *vtv_render_variant(struct vtv_render *r, unsigned features, unsigned kinds,
                                       struct vts_error *err);

/* Sets a material's uniforms (colours converted to linear when the frame is sRGB) and the light
 * and eye on program p. */
void vtv_render_material_uniforms(const struct vtv_render *r, GLuint p,
                                  const struct vtv_material *m, const struct vtv_view *v);

/* Page table and physical textures for the cache, one per map kind in use (layers[k].used), all
 * with the cache's slot layout; phys_slice: each one's slice in a loaded tile. VTS_ERR_LIMIT when
 * a physical texture would be larger than GL_MAX_TEXTURE_SIZE. */
int vtv_render_set_cache(struct vtv_render *r, const struct vtv_cache *c,
                         const struct vts_geometry *g, const struct vtv_phys_layer *layers,
                         struct vts_error *err);
/* The GL format for BC payloads of codec (VTS_CODEC_BC1/BC3: S3TC, and sRGB S3TC for an sRGB
 * layer; VTS_CODEC_BC4/BC5: RGTC, not for an sRGB layer) when this GL can take them as they are
 * (payload edge a multiple of 4); 0 otherwise. */
GLenum vtv_render_bc_format(const struct vtv_render *r, uint32_t codec, bool srgb,
                            uint32_t payload_px);
/* data: one loaded tile (vtv_loader: a slice of payload_px^2 * 4 bytes per physical texture,
 * RGBA8 texels or BC blocks as stored). */
void vtv_render_upload_tile(struct vtv_render *r, const struct vtv_cache *c, uint32_t slot,
                            const uint8_t *data, size_t bytes);
/* The GL formats of a 16-bit or float layer's texels (vtv_wide.h): internal, format, type. */
void vtv_render_wide_formats(const struct vtv_texel_format *f, GLenum out[3]);
/* Bytes one tile's upload sends to the physical textures (every layer: its payload in its GL
 * format, or its BC blocks). */
size_t vtv_render_upload_bytes(const struct vtv_render *r);
/* Uploads the entries in the cache's dirty rectangles. */
void vtv_render_upload_page_table(struct vtv_render *r, const struct vtv_cache *c);

/* Binds the main pass's framebuffer and clears it (colour, fallback counts, depth), with sRGB
 * encoding as the frame's; the passes that draw into it start with this. */
void vtv_render_begin_main(const struct vtv_render *r);
/* Ends a main pass: reads back the fallback counts; returns the pixels drawn from a coarser level
 * than wanted. */
uint64_t vtv_render_end_main(struct vtv_render *r);

/* Main pass into the framebuffer; returns the number of fallback pixels. */
uint64_t vtv_render_vt(struct vtv_render *r, const struct vtv_view *v);

/* Tile-determination pass; out receives fb_width * fb_height RGBA16UI texels (x, y, level, 1;
 * zero where no geometry). jitter: sub-pixel offset in NDC. */
void vtv_render_feedback(struct vtv_render *r, const struct vtv_view *v, float jx, float jy,
                         uint16_t *out);

/* The reference: one mipmapped RGBA8 texture of w x h texels (VTS_ERR_LIMIT when too large). */
int vtv_render_set_reference(struct vtv_render *r, const uint8_t *rgba, uint32_t w, uint32_t h,
                             bool srgb, struct vts_error *err);
void vtv_render_reference(struct vtv_render *r, const struct vtv_view *v);
/* The reference pass's frame (vtv_reference.c draws its own geometry into it); end with _end(). */
void vtv_render_reference_begin(struct vtv_render *r);
void vtv_render_reference_end(void);
/* Sets the reference program p's uniforms: camera, the material m, its maps on texture units 0..3
 * (enum vtv_map order) with per-map texcoord transforms st (scale u v, offset u v on the drawn
 * texcoords; NULL: identity). */
void vtv_render_reference_uniforms(const struct vtv_render *r, GLuint p,
                                   const struct vtv_material *m, const struct vtv_view *v,
                                   const float st[VTV_MAP_COUNT][4]);
/* The attribute pointers of a VTV_VERTEX_FLOATS vertex buffer bound to GL_ARRAY_BUFFER (into the
 * bound vertex array). */
void vtv_render_vertex_layout(void);

/* The last main pass as RGBA8 rows, top row first. */
void vtv_render_read_color(struct vtv_render *r, uint8_t *rgba);

/* Copies the main pass to the default framebuffer (window) of size w x h. */
void vtv_render_present(struct vtv_render *r, uint32_t w, uint32_t h);

#endif
