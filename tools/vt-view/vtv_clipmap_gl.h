/* vt-view --clipmap, the GL side: one GL_TEXTURE_2D_ARRAY with a layer per level, each
 * (n * C)^2 texels (C = the store's tile_content_px), GL_REPEAT, no mipmaps; a tile's content
 * (borders dropped) written at its toroidal slot; and the draw of a mesh through it
 * (vtv_clipmap_glsl.h). Needs a current GL 3.3 core context. */
#ifndef VTV_CLIPMAP_GL_H
#define VTV_CLIPMAP_GL_H

#include <stdbool.h>
#include <stdint.h>

#include <epoxy/gl.h>

#include "vt_error.h"
#include "vts.h"
#include "vts_clipmap.h"
#include "vtv_wide.h"

struct vtv_render;
struct vtv_view;

/* Texture bytes allowed for the array (all levels): a sane limit on a software renderer. */
#define VTV_CLIPMAP_MAX_TEXTURE_BYTES (2ull << 30)

struct vtv_clipmap_gl {
    GLuint tex, prog;
    uint32_t size_px; /* S = n * C, the edge of every layer */
    uint32_t content_px, levels;
    GLenum internal, format, type; /* the texels: RGBA8 (sRGB: SRGB8_ALPHA8) or vtv_wide's */
    uint64_t tile_bytes;           /* one tile's upload: C * C * texel bytes (BC: its blocks) */
    GLenum bc_format;              /* BC blocks uploaded as stored (vtv_render_bc_format), or 0 */
    uint32_t bc_block;             /* bytes of one 4 x 4 block (8: BC1/BC4, 16: BC3/BC5) */
    bool rebuild_z;                /* BC5 of a 3-channel normal layer: z rebuilt in the shader */
    uint8_t *bc_buf;               /* one tile's content blocks, contiguous (tile_bytes) */
    int debug_offset; /* VTV_CLIPMAP_DEBUG_OFFSET=L: level L addressed one texel off (the
                         tests' wrong render), else -1 */
};

/* Creates the texture (n x n tiles of content_px per level, levels layers) of texels (what the
 * loader hands over for the layer, vtv_wide_format; an sRGB u8 layer as GL_SRGB8_ALPHA8) and the
 * program with the display features (VTV_F_RANGE, VTV_F_RAMP, VTV_F_INDEX: vtv_display.h) and
 * VTV_F_LIT (shaded as a lit material without maps: the terrain).
 * VTS_ERR_LIMIT with a one-line reason when the GL or VTV_CLIPMAP_MAX_TEXTURE_BYTES does not
 * allow it (sizes checked for overflow); VTS_ERR_UNSUPPORTED when the shader does not build. */
int vtv_clipmap_gl_init(struct vtv_clipmap_gl *g, uint32_t n, uint32_t content_px, uint32_t levels,
                        const struct vtv_texel_format *texels, bool srgb, unsigned display_features,
                        struct vts_error *err);
/* The same for a layer whose BC blocks are uploaded as stored: bc_format is the GL's compressed
 * format (vtv_render_bc_format: sRGB S3TC for an sRGB layer, RGTC for BC4/BC5), content_px a
 * multiple of 4; rebuild_z: BC5 normal xy, z rebuilt in the shader (as vt_rebuild_z does). */
int vtv_clipmap_gl_init_bc(struct vtv_clipmap_gl *g, uint32_t n, uint32_t content_px,
                           uint32_t levels, GLenum bc_format, bool rebuild_z,
                           unsigned display_features, struct vts_error *err);
void vtv_clipmap_gl_free(struct vtv_clipmap_gl *g);

/* Writes the content of one tile's payload (payload_px^2 texels with border_px borders;
 * NULL: an empty tile, zeros) at slot (slot_x, slot_y) of level's layer. With bc_format the
 * payload is the tile's BC blocks as stored (border_px a multiple of 4): the content's blocks
 * are copied out and written with glCompressedTexSubImage3D. */
void vtv_clipmap_gl_upload(struct vtv_clipmap_gl *g, uint32_t level, uint32_t slot_x,
                           uint32_t slot_y, const uint8_t *payload, uint32_t payload_px,
                           uint32_t border_px, const uint8_t *zero);

/* Draws every group of the render's mesh with view v into the render's framebuffer (colour and
 * fallback attachments), sampling the clipmap cm (fronts with the inset of the view's filter);
 * returns the fallback pixels. lod_bias: levels added to lambda. */
uint64_t vtv_clipmap_gl_draw(const struct vtv_clipmap_gl *g, const struct vts_clipmap *cm,
                             struct vtv_render *r, const struct vtv_view *v, float lod_bias);

/* The inset (texels) of a level's valid rectangle for a filter: 1 for bilinear and trilinear (the
 * bilinear footprint reaches 0.5 texel around the sample; 0.5 more for the sampler's sub-texel
 * rounding), 0.5 for nearest. */
double vtv_clipmap_gl_inset(bool nearest);

#endif
