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

struct vtv_render {
    uint32_t width, height;       /* main pass */
    uint32_t fb_width, fb_height; /* tile-determination pass */
    GLuint prog_vt, prog_feedback, prog_reference;
    GLuint vao, vbo, ibo;
    GLsizei index_count;
    GLuint fbo, rb_color, rb_fallback, rb_depth;
    GLuint fb_fbo, rb_request, rb_fb_depth;
    GLuint tex_pt, tex_phys, tex_reference;
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
    bool srgb;        /* sRGB layer: textures decode to linear, the frame is encoded back */
    GLenum bc_format; /* compressed physical texture (BC1/BC3 blocks uploaded as stored), or 0 */
};

struct vtv_view {
    float mvp[16]; /* column-major */
    bool trilinear;
    int debug;        /* 0 none, 1 levels, 2 tiles */
    float alpha_test; /* fragments with a lower alpha are discarded (0: none) */
};

int vtv_render_init(struct vtv_render *r, uint32_t width, uint32_t height, uint32_t fb_width,
                    uint32_t fb_height, struct vts_error *err);
void vtv_render_free(struct vtv_render *r);

/* Geometry: n vertices of 5 floats (x, y, z, u, v), index_count triangle indices. */
void vtv_render_set_mesh(struct vtv_render *r, const float *vertices, uint32_t n,
                         const uint32_t *indices, uint32_t index_count);

/* Page table and physical texture for the cache (srgb: an sRGB-encoded layer; bc_codec: a BC
 * codec whose blocks are uploaded compressed, from vtv_render_bc_format, or 0); VTS_ERR_LIMIT when
 * the physical texture would be larger than GL_MAX_TEXTURE_SIZE. */
int vtv_render_set_cache(struct vtv_render *r, const struct vtv_cache *c,
                         const struct vts_geometry *g, bool srgb, uint32_t bc_codec,
                         struct vts_error *err);
/* The GL format for BC payloads of codec (VTS_CODEC_BC1/BC3) when this GL can take them as they
 * are (S3TC, and sRGB S3TC for an sRGB layer, payload edge a multiple of 4); 0 otherwise. */
GLenum vtv_render_bc_format(const struct vtv_render *r, uint32_t codec, bool srgb,
                            uint32_t payload_px);
/* data: RGBA8 texels, or BC blocks (bytes) when the cache is compressed. */
void vtv_render_upload_tile(struct vtv_render *r, const struct vtv_cache *c, uint32_t slot,
                            const uint8_t *data, size_t bytes);
/* Uploads the entries in the cache's dirty rectangles. */
void vtv_render_upload_page_table(struct vtv_render *r, const struct vtv_cache *c);

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
/* The reference pass's frame and program, for other geometry (vtv_reference.c): texture unit 0,
 * uniforms u_mode, u_kd (vtv_shaders.c). Returns the program; end with _end(). */
GLuint vtv_render_reference_begin(struct vtv_render *r, const struct vtv_view *v);
void vtv_render_reference_end(void);

/* The last main pass as RGBA8 rows, top row first. */
void vtv_render_read_color(struct vtv_render *r, uint8_t *rgba);

/* Copies the main pass to the default framebuffer (window) of size w x h. */
void vtv_render_present(struct vtv_render *r, uint32_t w, uint32_t h);

#endif
