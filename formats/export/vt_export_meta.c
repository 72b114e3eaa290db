/* The files around the tiles of an export: the Deep Zoom descriptor (NAME.dzi), the IIIF
 * info.json, and index.html with its copy of OpenSeadragon. */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_export_impl.h"

/* A growing text buffer; after an allocation failure it stays failed. */
struct text {
    char *s;
    size_t len, cap;
    bool failed;
};

static void text_add(struct text *t, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Appends len bytes. */
static void text_bytes(struct text *t, const void *bytes, size_t len)
{
    if (t->failed)
        return;
    if (t->len + len + 1 > t->cap) {
        size_t cap = (t->len + len + 1) * 2;
        char *s = realloc(t->s, cap);
        if (!s) {
            t->failed = true;
            return;
        }
        t->s = s;
        t->cap = cap;
    }
    memcpy(t->s + t->len, bytes, len);
    t->len += len;
    t->s[t->len] = 0;
}

static void text_add(struct text *t, const char *fmt, ...)
{
    va_list ap;
    if (t->failed)
        return;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0 || t->len + (size_t)n + 1 > t->cap) {
        size_t cap = (t->len + (size_t)(n < 0 ? 0 : n) + 1) * 2;
        char *s = n < 0 ? NULL : realloc(t->s, cap);
        if (!s) {
            t->failed = true;
            return;
        }
        t->s = s;
        t->cap = cap;
    }
    va_start(ap, fmt);
    vsnprintf(t->s + t->len, t->cap - t->len, fmt, ap);
    va_end(ap);
    t->len += (size_t)n;
}

/* s as a JSON string, safe inside an HTML <script> too ('<' escaped). */
static void text_json_string(struct text *t, const char *s)
{
    text_add(t, "\"");
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            text_add(t, "\\%c", c);
        else if (c < 0x20 || c == '<' || c == '>' || c == '&')
            text_add(t, "\\u%04x", c);
        else
            text_add(t, "%c", c);
    }
    text_add(t, "\"");
}

static int text_write(struct text *t, const char *dir, const char *rel, struct vts_error *err)
{
    int rc = t->failed ? vt_error_set(err, VTS_ERR_NOMEM, "out of memory writing %s", rel)
                       : vt_export_write_file(dir, rel, t->s, t->len, err);
    free(t->s);
    *t = (struct text){0};
    return rc;
}

static void dzi_xml(struct text *t, const struct vt_export_plan *plan)
{
    text_add(t,
             "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
             "<Image xmlns=\"http://schemas.microsoft.com/deepzoom/2008\" Format=\"%s\" "
             "Overlap=\"%u\" TileSize=\"%u\">\n"
             "  <Size Width=\"%u\" Height=\"%u\"/>\n"
             "</Image>\n",
             plan->ext, plan->overlap_px, plan->tile_px, plan->width, plan->height);
}

/* info.json of the Image API 3.0, level 0: the sizes a client may ask for whole (the levels
 * that are one tile) and the tiles with their scale factors. */
static void iiif_json(struct text *t, const struct vt_export_plan *plan, const char *id)
{
    text_add(t, "{\n  \"@context\": \"http://iiif.io/api/image/3/context.json\",\n  \"id\": ");
    text_json_string(t, id);
    text_add(t,
             ",\n  \"type\": \"ImageService3\",\n  \"protocol\": \"http://iiif.io/api/image\",\n"
             "  \"profile\": \"level0\",\n  \"width\": %u,\n  \"height\": %u,\n",
             plan->width, plan->height);
    /* Level 0 promises jpg; png tiles are an extra format, and the preferred one for clients. */
    if (strcmp(plan->ext, "png") == 0)
        text_add(t, "  \"extraFormats\": [\"png\"],\n  \"preferredFormats\": [\"png\"],\n");
    text_add(t, "  \"sizes\": [");
    const char *sep = "";
    for (uint32_t j = plan->level_count; j-- > 1;) {
        if (vt_export_tiles_x(plan, j) != 1 || vt_export_tiles_y(plan, j) != 1)
            continue;
        text_add(t, "%s\n    {\"width\": %u, \"height\": %u}", sep, vt_export_level_width(plan, j),
                 vt_export_level_height(plan, j));
        sep = ",";
    }
    text_add(t, "\n  ],\n  \"tiles\": [\n    {\"width\": %u, \"height\": %u, \"scaleFactors\": [",
             plan->tile_px, plan->tile_px);
    for (uint32_t j = 0; j < plan->level_count; j++)
        text_add(t, "%s%llu", j ? ", " : "", 1ull << j);
    text_add(t, "]}\n  ]\n}\n");
}

int vt_export_write_descriptor(const struct vt_export_plan *plan, const struct vt_export_params *p,
                               const char *dir, struct vts_error *err)
{
    struct text t = {0};
    char rel[512];
    if (plan->layout == VT_EXPORT_DZI) {
        dzi_xml(&t, plan);
        snprintf(rel, sizeof rel, "%s.dzi", p->name);
    } else if (plan->layout == VT_EXPORT_IIIF) {
        iiif_json(&t, plan, p->iiif_id);
        snprintf(rel, sizeof rel, "info.json");
    } else {
        return 0;
    }
    return text_write(&t, dir, rel, err);
}

/* The tile source of the page: OpenSeadragon reads each layout from an object written here (the
 * page fetches nothing but tiles, which works from file://). */
static void html_tile_source(struct text *t, const struct vt_export_plan *plan,
                             const struct vt_export_params *p)
{
    if (plan->layout == VT_EXPORT_DZI) {
        text_add(t, "{Image: {xmlns: \"http://schemas.microsoft.com/deepzoom/2008\", Url: ");
        char url[512];
        snprintf(url, sizeof url, "%s_files/", p->name);
        text_json_string(t, url);
        text_add(t,
                 ", Format: \"%s\", Overlap: \"%u\", TileSize: \"%u\", Size: {Width: \"%u\", "
                 "Height: \"%u\"}}}",
                 plan->ext, plan->overlap_px, plan->tile_px, plan->width, plan->height);
    } else if (plan->layout == VT_EXPORT_IIIF) {
        /* info.json with the page's folder as its id, so the tiles load relative to the page. */
        struct vt_export_plan local = *plan;
        iiif_json(t, &local, ".");
    } else {
        /* XYZ: the world of zoom z is tile * 2^z texels square; the image its top-left part. */
        uint32_t top = plan->level_count - 1;
        unsigned long long world = (unsigned long long)plan->tile_px << top;
        text_add(t,
                 "{width: %llu, height: %llu, tileSize: %u, tileOverlap: 0, minLevel: 0, "
                 "maxLevel: %u, getTileUrl: function (l, x, y) { return l + \"/\" + x + \"/\" + "
                 "y + \".%s\"; }}",
                 world, world, plan->tile_px, top, plan->ext);
    }
}

static void html_page(struct text *t, const struct vt_export_plan *plan,
                      const struct vt_export_params *p, const char *title)
{
    text_add(t, "<!DOCTYPE html>\n<html>\n<head>\n<meta charset=\"utf-8\">\n<title>");
    for (const char *s = title; *s; s++) {
        if (*s == '<' || *s == '>' || *s == '&')
            text_add(t, "&#%d;", *s);
        else
            text_add(t, "%c", *s);
    }
    text_add(t, "</title>\n<style>html, body, #viewer { margin: 0; padding: 0; width: 100%%; "
                "height: 100%%; overflow: hidden; background: black; }</style>\n"
                "<script src=\"openseadragon.min.js\"></script>\n</head>\n<body>\n"
                "<div id=\"viewer\"></div>\n<script>\n"
                "/* Written by vt-export (vtpipe): the export in this folder, opened with "
                "OpenSeadragon. */\nvar viewer = OpenSeadragon({\n  id: \"viewer\",\n"
                "  drawer: \"canvas\",\n  showNavigationControl: false,\n"
                "  animationTime: 0,\n  blendTime: 0,\n  tileSources: ");
    html_tile_source(t, plan, p);
    /* Until the user moves the view, a resized window shows the whole image again (a headless
     * browser resizes the page after it has opened). */
    text_add(t, "\n});\nvar moved = false;\n"
                "viewer.addHandler(\"canvas-press\", function () { moved = true; });\n"
                "viewer.addHandler(\"canvas-scroll\", function () { moved = true; });\n"
                "viewer.addHandler(\"resize\", function () {\n"
                "  if (!moved) viewer.viewport.goHome(true);\n});\n"
                "</script>\n</body>\n</html>\n");
}

static int copy_file(const char *from, const char *dir, const char *rel, struct vts_error *err)
{
    FILE *f = fopen(from, "rb");
    struct text t = {0};
    char buf[65536];
    size_t n;
    if (!f)
        return vt_error_set(err, VTS_ERR_IO, "cannot read '%s': %s", from, strerror(errno));
    while (!t.failed && (n = fread(buf, 1, sizeof buf, f)) > 0)
        text_bytes(&t, buf, n);
    bool bad = ferror(f) != 0;
    fclose(f);
    if (bad) {
        free(t.s);
        return vt_error_set(err, VTS_ERR_IO, "cannot read '%s'", from);
    }
    return text_write(&t, dir, rel, err);
}

int vt_export_write_html(const struct vts_store *store, const struct vt_export_params *p,
                         const char *dir, const char *osd_js, struct vts_error *err)
{
    struct vt_export_plan plan;
    struct text t = {0};
    vt_export_plan_init(&plan, store, p);
    int rc = copy_file(osd_js, dir, "openseadragon.min.js", err);
    if (rc != 0)
        return rc;
    const char *title = strrchr(vts_store_name(store), '/');
    html_page(&t, &plan, p, title ? title + 1 : vts_store_name(store));
    return text_write(&t, dir, "index.html", err);
}
