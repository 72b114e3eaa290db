/* vt-view application: set-up and frame loop. */
#include "vtv_app.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tool_common.h"
#include "vt_error.h"
#include "vtv_camera.h"
#include "vtv_clipmap.h"
#include "vtv_context.h"
#include "vtv_display.h"
#include "vtv_mesh.h"
#include "vtv_output.h"
#include "vtv_reference.h"
#include "vtv_render.h"
#include "vtv_select.h"
#include "vtv_stream.h"
#include "vtv_terrain.h"
#include "vtv_wang_scene.h"

void vtv_options_default(struct vtv_options *o)
{
    memset(o, 0, sizeof(*o));
    o->width = 1024;
    o->height = 768;
    o->feedback_div = 4;
    o->aniso = 1;
    o->nearest = -1;
    o->cache_tiles = 256;
    o->uploads = 32;
    o->threads = 2;
    o->ram_tiles = UINT32_MAX; /* as many as the physical cache */
    o->prefetch = true;
    o->auto_lod = true;
    o->ramp = -1;
    o->index = -1;
    o->terrain_grid = VTV_TERRAIN_GRID_DEFAULT;
    o->terrain_exaggeration = 1.0;
    o->budget = 4u << 20;
    const float dir[3] = {0.3f, 0.8f, 0.5f}, colour[3] = {0.85f, 0.85f, 0.85f},
                ambient[3] = {0.15f, 0.15f, 0.15f};
    memcpy(o->light_dir, dir, sizeof(dir));
    memcpy(o->light_colour, colour, sizeof(colour));
    memcpy(o->ambient, ambient, sizeof(ambient));
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

static int find_layer(const struct vts_store *s, const char *name, uint32_t *out)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    *out = 0;
    if (!name)
        return 0;
    for (uint32_t i = 0; i < g->layer_count; i++)
        if (strcmp(vts_store_layer(s, i)->name, name) == 0) {
            *out = i;
            return 0;
        }
    if (vt_parse_u32(name, 0, g->layer_count - 1, out) == 0)
        return 0;
    return -1;
}

/* The 2D camera that shows the whole texture. */
static void fit_2d(const struct vts_geometry *g, uint32_t w, uint32_t h, struct vtv_camera *c)
{
    c->v[0] = g->width / 2.0;
    c->v[1] = g->height / 2.0;
    c->v[2] = fmin((double)w / g->width, (double)h / g->height);
}

struct app {
    const struct vtv_options *o;
    struct vts_store *store;
    struct vtv_context *ctx;
    struct vtv_render render;
    struct vtv_stream stream;
    struct vtv_clipmap clip; /* --clipmap: instead of the stream */
    bool clip_bc;            /* --clipmap uploads the layer's BC blocks as stored */
    struct vtv_mesh mesh;
    struct vtv_reference_scene ref_scene;
    struct vtv_wang_scene wang; /* packs named by vt_wang materials */
    struct vtv_camera_path path;
    struct vtv_camera cam; /* interactive / default */
    struct vtv_frame_stats *stats;
    uint16_t *feedback;
    uint8_t *shot;
    bool three_d, trilinear;
    uint32_t aniso; /* 1: off */
    bool nearest;   /* no filtering (--filtering nearest, or a selection store) */
    bool select;    /* the store is a selection store and is shown unfiltered at start (key F) */
    char filtering[16];
    int debug;
    uint32_t layers[VTV_MAP_COUNT];  /* store layer per map kind, UINT32_MAX: none */
    struct vtv_terrain_info terrain; /* with --terrain */
};

/* The store layer of each map kind the scene's materials name (the shown layer for a map naming
 * the store alone); at least the diffuse one (the shown layer when no material maps anything). */
static int map_layers(struct app *a, uint32_t shown, struct vts_error *err)
{
    static const char *const stmt[VTV_MAP_COUNT] = {"map_Kd", "norm/bump", "map_Ks", "map_d"};
    bool any = false;
    for (int k = 0; k < VTV_MAP_COUNT; k++) {
        const char *name = a->mesh.layers[k];
        a->layers[k] = UINT32_MAX;
        if (!name)
            continue;
        any = true;
        if (!name[0]) {
            a->layers[k] = shown;
            continue;
        }
        const struct vts_geometry *g = vts_store_geometry(a->store);
        for (uint32_t i = 0; i < g->layer_count && a->layers[k] == UINT32_MAX; i++)
            if (strcmp(vts_store_layer(a->store, i)->name, name) == 0)
                a->layers[k] = i;
        if (a->layers[k] == UINT32_MAX)
            return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                "%s: no layer '%s' (the %s maps of the scene '%s' name it)",
                                a->o->store_path, name, stmt[k], a->o->obj_path);
    }
    if (!any)
        a->layers[VTV_MAP_DIFFUSE] = shown;
    return 0;
}

static void set_light(struct vtv_render *r, const struct vtv_options *o)
{
    double l = 0;
    for (int k = 0; k < 3; k++)
        l += (double)o->light_dir[k] * o->light_dir[k];
    l = sqrt(l);
    for (int k = 0; k < 3; k++) {
        r->light.dir[k] = (float)(o->light_dir[k] / l);
        r->light.colour[k] = o->light_colour[k];
        r->light.ambient[k] = o->ambient[k];
    }
}

static const char *filtering_name(struct app *a)
{
    if (a->nearest)
        return "nearest";
    if (!a->trilinear)
        return "bilinear";
    if (a->aniso <= 1)
        return "trilinear";
    snprintf(a->filtering, sizeof(a->filtering), "aniso%u", a->aniso);
    return a->filtering;
}

/* The 2D view in split coordinates (item 7 of issue 16): the texture's quad clipped to the view
 * on the CPU in double, positions relative to the camera centre and texcoords in level-0 texels
 * relative to the level-0 tile under the centre, so that no float holds a coordinate of the size
 * of the virtual texture (2^20 texels: 1/16 texel in float32). */
static void quad_2d(struct app *a, const struct vtv_camera *cam, struct vtv_view *v)
{
    const struct vts_geometry *g = vts_store_geometry(a->store);
    double s = cam->v[2], cx = cam->v[0], cy = cam->v[1];
    double hw = a->o->width / (2 * s), hh = a->o->height / (2 * s);
    double x0 = fmax(0, cx - hw), x1 = fmin(g->width, cx + hw);
    double y0 = fmax(0, cy - hh), y1 = fmin(g->height, cy + hh);
    x1 = fmax(x0, x1);
    y1 = fmax(y0, y1);
    double c = g->tile_content_px;
    double tx = fmin(fmax(floor(cx / c), 0), ceil(g->width / c) - 1);
    double ty = fmin(fmax(floor(cy / c), 0), ceil(g->height / c) - 1);
    v->rel = true;
    v->origin[0] = (int)tx;
    v->origin[1] = (int)ty;
    const double corner[4][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    const int order[6] = {0, 1, 2, 0, 2, 3};
    for (int i = 0; i < 6; i++) {
        float *p = a->mesh.vertices + i * VTV_VERTEX_FLOATS;
        const double *k = corner[order[i]];
        p[0] = (float)(k[0] - cx);
        p[1] = (float)(k[1] - cy);
        p[3] = (float)(k[0] - tx * c);
        p[4] = (float)(k[1] - ty * c);
    }
    vtv_render_update_vertices(&a->render, &a->mesh);
    struct vtv_camera centred = *cam;
    centred.v[0] = centred.v[1] = 0;
    vtv_camera_matrix_2d(&centred, a->o->width, a->o->height, v->mvp);
}

/* The camera of a frame: the path's, the orbit's, else the interactive one. */
static void frame_camera(const struct app *a, uint64_t frame, struct vtv_camera *cam)
{
    *cam = a->cam;
    if (a->path.count)
        *cam = *vtv_camera_path_at(&a->path, frame);
    else if (a->o->orbit)
        vtv_camera_orbit(a->mesh.lo, a->mesh.hi, frame, a->o->orbit, cam);
}

static void frame_view(struct app *a, uint64_t frame, struct vtv_view *v)
{
    const struct vtv_options *o = a->o;
    struct vtv_camera cam;
    v->rel = false;
    v->origin[0] = v->origin[1] = 0;
    frame_camera(a, frame, &cam);
    if (a->three_d) {
        double d = 0;
        for (int k = 0; k < 3; k++)
            d += (a->mesh.hi[k] - a->mesh.lo[k]) * (a->mesh.hi[k] - a->mesh.lo[k]);
        d = sqrt(d) + 1e-6;
        vtv_camera_matrix_3d(&cam, o->width, o->height, d * 1e-3, d * 10, v->mvp);
    } else if (!o->reference) {
        quad_2d(a, &cam, v);
    } else {
        vtv_camera_matrix_2d(&cam, o->width, o->height, v->mvp);
    }
    v->trilinear = a->trilinear;
    v->aniso = a->trilinear ? (int)a->aniso : 1;
    v->nearest = a->nearest;
    v->debug = a->debug;
    for (int k = 0; k < 3; k++)
        v->eye[k] = a->three_d ? (float)cam.v[k] : 0.0f;
}

static void apply_input(struct app *a, const struct vtv_input *in)
{
    if (in->toggle_filter && a->select)
        a->nearest = !a->nearest; /* a selection store: unfiltered and --filtering's default */
    else if (in->toggle_filter)
        a->trilinear = !a->trilinear;
    if (in->cycle_debug)
        a->debug = (a->debug + 1) % 3;
    if (a->three_d) {
        double *e = a->cam.v, *t = a->cam.v + 3;
        double dx = e[0] - t[0], dz = e[2] - t[2];
        double ang = -in->orbit_x * 0.01, r = sqrt(dx * dx + dz * dz);
        double na = atan2(dz, dx) + ang;
        e[0] = t[0] + r * cos(na) * (1.0 / in->zoom);
        e[2] = t[2] + r * sin(na) * (1.0 / in->zoom);
        e[1] += in->orbit_y * 0.01 * r;
    } else {
        a->cam.v[0] -= in->pan_x / a->cam.v[2];
        a->cam.v[1] -= in->pan_y / a->cam.v[2];
        a->cam.v[2] *= in->zoom;
    }
}

/* --clipmap: the clipmap instead of the page table's stream (docs/viewer.md, "Clipmap mode"). */
static int setup_clipmap(struct app *a, uint32_t shown, bool srgb, struct vts_error *err)
{
    const struct vtv_options *o = a->o;
    struct vtv_clipmap_options co = {.n = o->clipmap,
                                     .budget = o->budget,
                                     .sync = o->sync,
                                     .threads = o->threads,
                                     .centre_fixed = o->clipmap_centre_set,
                                     .centre = {o->clipmap_centre[0], o->clipmap_centre[1]},
                                     .frames_cap = o->frames};
    a->render.srgb = srgb;
    const struct vts_layer *info = vts_store_layer(a->store, shown);
    const struct vts_geometry *g = vts_store_geometry(a->store);
    bool aligned = g->tile_content_px % 4 == 0 && g->border_px % 4 == 0;
    GLenum bc = o->no_bc_upload || !aligned
                    ? 0
                    : vtv_render_bc_format(&a->render, info->codec, srgb, g->tile_payload_px);
    co.bc_format = bc;
    co.rebuild_z = bc && info->codec == VTS_CODEC_BC5 && info->channels == 3;
    a->clip_bc = bc != 0;
    bool is_bc = info->codec == VTS_CODEC_BC1 || info->codec == VTS_CODEC_BC3 ||
                 info->codec == VTS_CODEC_BC4 || info->codec == VTS_CODEC_BC5;
    if (is_bc)
        vt_log(VT_LOG_INFO, "clipmap: layer '%s': %s%s", info->name,
               bc                ? "blocks uploaded compressed"
               : o->no_bc_upload ? "decoded on the CPU (--bc-upload off)"
               : !aligned        ? "decoded on the CPU (tile content or border not a multiple of 4)"
                                 : "decoded on the CPU (this GL cannot take the blocks)",
               co.rebuild_z ? " (normal xy, z rebuilt in the shader)" : "");
    /* the terrain's material is lit: the clipmap's program shades it as the page table's does */
    unsigned features = a->render.display.features | (o->terrain ? VTV_F_LIT : 0u);
    return vtv_clipmap_init(&a->clip, a->store, shown, &co, features, err);
}

static int setup(struct app *a, struct vts_error *err)
{
    const struct vtv_options *o = a->o;
    a->store = vts_open(o->store_path, err);
    if (!a->store)
        return err->status;
    uint32_t layer;
    if (find_layer(a->store, o->layer_name, &layer) != 0)
        return vt_error_set(err, VTS_ERR_ARG, "%s: no layer '%s'", o->store_path, o->layer_name);
    const struct vts_geometry *g = vts_store_geometry(a->store);
    a->three_d = o->obj_path != NULL || o->terrain != NULL;
    /* a selection store is sampled unfiltered unless --filtering asks otherwise */
    char why[64];
    bool sel = vtv_select_store(a->store, why, sizeof(why)) != 0;
    a->nearest = o->nearest > 0 || (o->nearest < 0 && sel);
    a->select = sel && a->nearest;
    if (a->select)
        vt_log(VT_LOG_INFO, "%s: %s: sampled without filtering (nearest level, nearest texel)",
               o->store_path, why);
    else if (sel)
        vt_log(VT_LOG_WARN, "%s: %s: its values are not to be mixed, but --filtering %s mixes them",
               o->store_path, why,
               !o->trilinear  ? "bilinear"
               : o->aniso > 1 ? "anisoN"
                              : "trilinear");
    /* anisoN's taps reach N/2 texels past the footprint's centre: the border must hold them */
    a->aniso = o->aniso;
    if (a->aniso > 1 && a->aniso > 2 * g->border_px) {
        uint32_t n = 2 * g->border_px;
        vt_log(VT_LOG_WARN, "%s: border %u px holds anisotropic taps up to %u, not %u: %s",
               o->store_path, g->border_px, n < 2 ? 1 : n, a->aniso,
               n < 2 ? "filtering trilinear" : "clamped");
        a->aniso = n < 2 ? 1 : n;
    }
    /* materials: 3D, unless --layer asks for one layer as it is, or the plain reference (the
     * store's level 0 through the scene) is drawn */
    bool materials = a->three_d && !o->layer_name && !(o->reference && !o->reference_scene);
    struct vtv_terrain_options to = {o->terrain, o->terrain_grid, o->terrain_exaggeration};
    int st = o->terrain
                 ? vtv_terrain_build(a->store, o->store_path, &to, &a->mesh, &a->terrain, err)
             : a->three_d ? vtv_mesh_read_obj(&a->mesh, o->obj_path, materials, err)
                          : vtv_mesh_quad(&a->mesh, g->width, g->height, err);
    if (st == 0)
        st = vtv_wang_scene_open(&a->wang, a->mesh.wang_paths, a->mesh.wang_count, err);
    if (st != 0)
        return st;
    st = map_layers(a, layer, err);
    if (st != 0)
        return st;
    if (o->camera_path) {
        st = vtv_camera_path_read(&a->path, o->camera_path, a->three_d ? 7 : 3, err);
        if (st != 0)
            return st;
    }
    if (a->three_d)
        vtv_camera_orbit(a->mesh.lo, a->mesh.hi, 0, 1, &a->cam);
    else
        fit_2d(g, o->width, o->height, &a->cam);
    a->ctx = o->headless ? vtv_context_headless(err)
                         : vtv_context_window(o->width, o->height, "vt-view", err);
    if (!a->ctx)
        return err->status;
    uint32_t fw = (o->width + o->feedback_div - 1) / o->feedback_div;
    uint32_t fh = (o->height + o->feedback_div - 1) / o->feedback_div;
    st = vtv_render_init(&a->render, o->width, o->height, fw, fh, err);
    if (st == 0)
        st = vtv_wang_scene_upload(&a->wang, err);
    if (st != 0)
        return st;
    a->render.wang = &a->wang;
    set_light(&a->render, o);
    st = vtv_display_choose(
        a->store, a->layers[VTV_MAP_DIFFUSE] != UINT32_MAX ? a->layers[VTV_MAP_DIFFUSE] : layer,
        o->has_range ? o->range : NULL, o->ramp, &a->render.display, err);
    if (st != 0)
        return st;
    vtv_select_display(
        a->store, a->layers[VTV_MAP_DIFFUSE] != UINT32_MAX ? a->layers[VTV_MAP_DIFFUSE] : layer,
        o->index, &a->render.display);
    if (!o->reference_scene) {
        st = vtv_render_set_mesh(&a->render, &a->mesh,
                                 o->clipmap     ? 0u /* its own program (vtv_clipmap_gl) */
                                 : o->reference ? 1u << VTV_PROG_REFERENCE
                                                : (1u << VTV_PROG_VT) | (1u << VTV_PROG_FEEDBACK),
                                 err);
        if (st != 0)
            return st;
    }
    uint32_t shown = a->layers[VTV_MAP_DIFFUSE] != UINT32_MAX ? a->layers[VTV_MAP_DIFFUSE] : layer;
    bool srgb = vts_store_layer(a->store, shown)->colour == VTS_COLOUR_SRGB;
    if (o->reference_scene) {
        a->render.srgb = srgb; /* the frame encodes as the virtual-texture pass's would */
        st = vtv_reference_scene_load(&a->ref_scene, &a->render, o->reference_scene, srgb, err);
    } else if (o->clipmap) {
        st = setup_clipmap(a, shown, srgb, err);
    } else if (o->reference) {
        uint8_t *img = vtv_stream_level0(a->store, layer, err);
        if (!img)
            return err->status;
        st = vtv_render_set_reference(&a->render, img, g->width, g->height, srgb, err);
        free(img);
    } else {
        struct vtv_stream_options so = {.ram_tiles = o->ram_tiles == UINT32_MAX ? o->cache_tiles
                                                                                : o->ram_tiles,
                                        .prefetch = o->prefetch,
                                        .reads = o->reads,
                                        .auto_lod = o->auto_lod,
                                        .lod_bias = o->lod_bias};
        st = vtv_stream_init(&a->stream, a->store, a->layers, o->cache_tiles, o->threads, o->sync,
                             o->uploads, !o->no_bc_upload, &so, &a->render, err);
        /* the frame encodes as the reference's: by the diffuse layer, else the shown one */
        a->render.srgb = srgb;
    }
    if (st != 0)
        return st;
    a->feedback = malloc((size_t)fw * fh * 8);
    a->shot = malloc((size_t)o->width * o->height * 4);
    a->stats = calloc(o->frames ? o->frames : 1, sizeof(*a->stats));
    if (!a->feedback || !a->shot || !a->stats)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    a->trilinear = o->trilinear;
    a->debug = o->debug;
    return 0;
}

/* A clipmap frame: paging around the paging centre (--clipmap-centre, else the 2D camera's centre,
 * or the terrain's colour texel under the eye: docs/viewer.md "Terrain in clipmap mode"), uploads
 * within the budget, the draw; no tile-determination pass. */
static int frame_clipmap(struct app *a, uint64_t i, const struct vtv_view *v,
                         struct vtv_frame_stats *st, struct vts_error *err)
{
    struct vtv_camera cam;
    frame_camera(a, i, &cam);
    double cx = cam.v[0], cy = cam.v[1];
    if (a->o->terrain) /* the ground point below the eye (x, z), in the colour's texels */
        vtv_terrain_texel(&a->terrain, cam.v[0], cam.v[2], &cx, &cy);
    struct vtv_clipmap_frame f;
    if (vtv_clipmap_update(&a->clip, cx, cy, &f) != 0)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    st->uploads = f.tiles;
    st->bytes_uploaded = f.bytes;
    st->reads = f.reads;
    st->loaded = f.tiles;
    st->failed = a->clip.failed;
    st->lod_bias = a->o->auto_lod ? 0.0f : a->o->lod_bias;
    st->fallback_pixels =
        vtv_clipmap_gl_draw(&a->clip.gl, &a->clip.cm, &a->render, v, st->lod_bias);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "OpenGL error 0x%x in frame %" PRIu64,
                            (unsigned)e, i);
    return 0;
}

/* One frame; returns 0 or a negative status. */
static int frame(struct app *a, uint64_t i, struct vtv_frame_stats *st, struct vts_error *err)
{
    struct vtv_view v;
    frame_view(a, i, &v);
    if (a->o->reference_scene) {
        vtv_reference_scene_draw(&a->render, &a->ref_scene, &v);
        return 0;
    }
    if (a->o->reference) {
        vtv_render_reference(&a->render, &v);
        return 0;
    }
    if (a->o->clipmap)
        return frame_clipmap(a, i, &v, st, err);
    vtv_stream_update(&a->stream, st);
    st->bytes_uploaded = st->uploads * vtv_render_upload_bytes(&a->render);
    st->fallback_pixels = vtv_render_vt(&a->render, &v);
    /* Jitter the low-resolution pass over the K x K sub-pixel positions so that thin slivers of a
     * tile are found within K^2 frames. */
    uint32_t k = a->o->feedback_div, j = (uint32_t)(i % ((uint64_t)k * k));
    float jx = (((float)(j % k) + 0.5f) / (float)k - 0.5f) * 2.0f / (float)a->render.fb_width;
    float jy = (((float)(j / k) + 0.5f) / (float)k - 0.5f) * 2.0f / (float)a->render.fb_height;
    vtv_render_feedback(&a->render, &v, jx, jy, a->feedback);
    if (vtv_stream_request(&a->stream, a->feedback,
                           (size_t)a->render.fb_width * a->render.fb_height, st) != 0)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    GLenum e = glGetError();
    if (e != GL_NO_ERROR)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "OpenGL error 0x%x in frame %" PRIu64,
                            (unsigned)e, i);
    return 0;
}

static int loop(struct app *a, struct vts_error *err)
{
    const struct vtv_options *o = a->o;
    uint64_t n = 0, last_fallback = 0;
    double title_t = 0;
    for (uint64_t i = 0; o->frames == 0 || i < o->frames; i++) {
        struct vtv_frame_stats st = {0};
        double t0 = now_s();
        int s = frame(a, i, &st, err);
        if (s != 0)
            return s;
        st.ms = (now_s() - t0) * 1e3;
        last_fallback = st.fallback_pixels;
        if (i < o->frames)
            a->stats[i] = st;
        n = i + 1;
        if (vtv_context_is_window(a->ctx)) {
            vtv_render_present(&a->render, o->width, o->height);
            struct vtv_input in;
            uint32_t w = o->width, h = o->height;
            vtv_context_frame(a->ctx, &in, &w, &h);
            if (in.quit)
                break;
            apply_input(a, &in);
            if (now_s() - title_t > 0.25) {
                char title[256];
                snprintf(title, sizeof(title),
                         "vt-view %s | %s%s | req %" PRIu64 " res %" PRIu64 " up %" PRIu64
                         " fallback %" PRIu64 " px | %.1f ms",
                         o->store_path, filtering_name(a),
                         a->debug == 1   ? " levels"
                         : a->debug == 2 ? " tiles"
                                         : "",
                         st.requested, st.resident, st.uploads, st.fallback_pixels, st.ms);
                vtv_context_set_title(a->ctx, title);
                title_t = now_s();
            }
        }
        vt_log(VT_LOG_DEBUG,
               "frame %" PRIu64 ": requested %" PRIu64 ", loaded %" PRIu64 ", resident %" PRIu64
               ", uploads %" PRIu64 ", fallback %" PRIu64 " px",
               i, st.requested, st.loaded, st.resident, st.uploads, st.fallback_pixels);
    }
    if (o->screenshot) {
        vtv_render_read_color(&a->render, a->shot);
        int s = vtv_write_screenshot(o->screenshot, a->shot, o->width, o->height, err);
        if (s != 0)
            return s;
        /* without --sync the loader may still be behind at the last frame */
        if (!o->reference && last_fallback > 0)
            vt_log(VT_LOG_WARN,
                   "the screenshot's frame shows %" PRIu64
                   " fallback pixels (coarser levels while tiles load): %s",
                   last_fallback,
                   o->sync ? (o->clipmap ? "give more --frames or a larger --budget"
                                         : "give more --frames or a larger --uploads")
                           : "use --sync (or more --frames) for a complete frame");
    }
    if (o->stats) {
        struct vtv_run_info info = {
            .store = o->store_path,
            .mode = a->three_d ? "3d" : "2d",
            .filtering = filtering_name(a),
            .renderer = o->reference ? "reference"
                        : o->clipmap ? "clipmap"
                                     : "virtual",
            .clip = o->clipmap ? &a->clip : NULL,
            .width = o->width,
            .height = o->height,
            .feedback_width = a->render.fb_width,
            .feedback_height = a->render.fb_height,
            .cache_tiles = o->cache_tiles,
            .uploads_per_frame = o->uploads,
            .sync = o->sync,
            .variants = a->render.variants,
            .variant_count = a->render.variant_count,
            .physical_format = o->reference                             ? "none"
                               : a->render.bc_format != 0 || a->clip_bc ? "bc"
                               : a->render.phys_upload[VTV_MAP_DIFFUSE][1] == GL_UNSIGNED_SHORT
                                   ? "u16"
                               : a->render.phys_upload[VTV_MAP_DIFFUSE][1] == GL_HALF_FLOAT ? "f16"
                               : a->render.phys_upload[VTV_MAP_DIFFUSE][1] == GL_FLOAT      ? "f32"
                               : a->render.srgb ? "srgb8_alpha8"
                                                : "rgba8",
            .terrain = o->terrain ? &a->terrain : NULL,
        };
        size_t count = n < o->frames ? n : o->frames;
        int s = vtv_write_stats(o->stats, &info, a->stats, count, err);
        if (s != 0)
            return s;
    }
    if (n > 0 && !o->reference) {
        const struct vtv_frame_stats *l = &a->stats[(n < o->frames ? n : o->frames) - 1];
        vt_log(VT_LOG_INFO,
               "%" PRIu64 " frames; last: requested %" PRIu64 ", resident %" PRIu64
               ", fallback %" PRIu64 " px",
               n, l->requested, l->resident, l->fallback_pixels);
    }
    return 0;
}

int vtv_app_run(const struct vtv_options *o)
{
    struct app a;
    memset(&a, 0, sizeof(a));
    a.o = o;
    struct vts_error err = {0};
    int st = setup(&a, &err);
    if (st == 0)
        st = loop(&a, &err);
    if (st != 0)
        vt_log(VT_LOG_ERROR, "%s", err.message);
    if (a.ctx) {
        if (o->clipmap)
            vtv_clipmap_free(&a.clip);
        else if (!o->reference)
            vtv_stream_free(&a.stream);
        vtv_reference_scene_free(&a.ref_scene);
        vtv_wang_scene_free(&a.wang);
        vtv_render_free(&a.render);
        vtv_context_destroy(a.ctx);
    }
    if (!a.ctx)
        vtv_wang_scene_free(&a.wang);
    vtv_mesh_free(&a.mesh);
    vtv_camera_path_free(&a.path);
    vts_close(a.store);
    free(a.feedback);
    free(a.shot);
    free(a.stats);
    if (st == 0)
        return VT_EXIT_OK;
    return st == VTS_ERR_ARG ? VT_EXIT_USAGE : VT_EXIT_BAD_INPUT;
}
