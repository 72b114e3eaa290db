/* vt-info: a store described, as text or JSON (gdalinfo -json's shape for the georeferencing). */
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tool_common.h"
#include "vt_store_georef.h"
#include "vt_store_stats.h"
#include "vt_wang_pack.h"
#include "vti.h"

/* Writes the names of the set bits of flags (names[i] for bit i < 2, else "bit<i>"), space
 * separated, into out; "" when none is set. */
static void flag_names(char *out, size_t cap, uint32_t flags, const char *const names[2])
{
    size_t len = 0;
    out[0] = '\0';
    for (unsigned bit = 0; bit < 32 && len < cap; bit++) {
        const char *name = bit < 2 ? names[bit] : NULL;
        if (!(flags & (1u << bit)))
            continue;
        if (name)
            len += (size_t)snprintf(out + len, cap - len, "%s%s", len ? " " : "", name);
        else
            len += (size_t)snprintf(out + len, cap - len, "%sbit%u", len ? " " : "", bit);
    }
}

static const char *const store_flag_names[2] = {"wrap-x", "wrap-y"};
static const char *const layer_flag_names[2] = {"premultiplied", NULL};

/* Prints text from the file (a layer name, a metadata value) on one line: control characters as
 * \xHH. */
static void print_escaped(const char *s)
{
    for (; *s; s++) {
        if ((unsigned char)*s < 0x20 || *s == 0x7f)
            printf("\\x%02x", (unsigned)(unsigned char)*s);
        else
            putchar(*s);
    }
}

static void print_counts(const char *level, const char *size, const char *tiles,
                         const struct vt_tile_counts *st)
{
    printf("  %5s %13s %9s %7llu %7llu %7llu %13llu\n", level, size, tiles,
           (unsigned long long)st->stored, (unsigned long long)st->empty,
           (unsigned long long)st->shared, (unsigned long long)st->bytes);
}

static void print_layer(const struct vts_store *s, const struct vt_store_stats *st, uint32_t layer)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    const struct vts_layer *l = vts_store_layer(s, layer);
    char flags[128], codec[5], level[16], size[32], tiles[32];
    vts_codec_name(l->codec, codec);
    flag_names(flags, sizeof flags, l->flags, layer_flag_names);
    printf("layer %u '", layer);
    print_escaped(l->name);
    printf("': %s, %u channels, %s, %s, flags %s\n", codec, l->channels, vts_sample_name(l->sample),
           vts_colour_name(l->colour), flags[0] ? flags : "none");
    printf("  level          size     tiles  stored   empty  shared         bytes\n");
    for (uint32_t i = 0; i < g->level_count; i++) {
        struct vts_level L;
        vts_store_level(s, i, &L);
        snprintf(level, sizeof level, "%u", i);
        snprintf(size, sizeof size, "%ux%u", L.width, L.height);
        snprintf(tiles, sizeof tiles, "%ux%u", L.tiles_x, L.tiles_y);
        print_counts(level, size, tiles, vt_store_stats_at(st, layer, i));
    }
    const struct vt_tile_counts *total = vt_store_stats_at(st, layer, g->level_count);
    snprintf(tiles, sizeof tiles, "%llu", (unsigned long long)total->tiles);
    print_counts("total", "", tiles, total);
}

/* The long lists of a Wang pack (wang.hash, wang.order): their first entries and count. Returns
 * false for other keys. */
static bool vt_wang_print_list(const char *key, const char *value)
{
    if (strcmp(key, VT_WANG_KEY_HASH) != 0 && strcmp(key, VT_WANG_KEY_ORDER) != 0)
        return false;
    size_t n = *value != '\0', shown = 0;
    for (const char *p = value; *p; p++)
        n += *p == ' ';
    for (const char *p = value; *p && shown < 8; p++) {
        shown += *p == ' ';
        if (shown < 8)
            putchar(*p);
    }
    printf("%s (%zu entries)", n > 8 ? " ..." : "", n);
    return true;
}

/* A Wang pack's parameters (vt-wang), or a warning when its metadata is bad. */
static void print_wang(const struct vts_store *s)
{
    struct vt_wang_info info;
    struct vts_error err = {0};
    if (!vt_wang_pack_is(s))
        return;
    if (vt_wang_pack_open(s, &info, &err) == 0)
        vt_wang_pack_print(&info);
    else
        vt_log(VT_LOG_WARN, "%s", err.message);
    vt_wang_info_release(&info);
}

static json_t *json_wang(const struct vts_store *s)
{
    struct vt_wang_info i;
    struct vts_error err = {0};
    json_t *o = NULL;
    if (vt_wang_pack_open(s, &i, &err) == 0)
        o = json_pack("{s:s, s:I, s:I, s:I, s:I, s:I, s:I, s:I, s:b}", "kind",
                      i.corners ? "corner" : "edge", "kh", (json_int_t)i.kh, "kv", (json_int_t)i.kv,
                      "tile_px", (json_int_t)i.tile_px, "cols", (json_int_t)i.cols, "rows",
                      (json_int_t)i.rows, "hash_entries", (json_int_t)i.hash_n, "repeat_px",
                      (json_int_t)i.hash_n * i.tile_px, "shuffled", i.order != NULL);
    else
        vt_log(VT_LOG_WARN, "%s", err.message);
    vt_wang_info_release(&i);
    return o ? o : json_null();
}

/* ---- georeferencing (docs/geospatial.md; vt_store_georef.h) ---- */

static void print_georef(const struct vts_store *s)
{
    struct vt_georef g;
    vt_store_georef(s, 0, &g);
    const double *t = g.transform;
    if (g.has_transform)
        printf(
            "georef:            origin %.17g, %.17g; texel %.17g x %.17g; rotation %.17g, %.17g\n",
            t[0], t[3], t[1], t[5], t[2], t[4]);
    if (g.crs_wkt) {
        char name[128];
        vt_store_crs_name(g.crs_wkt, name, sizeof name);
        printf("crs:               ");
        print_escaped(name);
        putchar('\n');
    }
    if (g.nodata) {
        printf("nodata:            ");
        print_escaped(g.nodata);
        putchar('\n');
    }
}

static void print_summary(const struct vts_store *s, const struct vt_store_stats *st)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    const struct vt_tile_counts *t = &st->total;
    unsigned major, minor;
    char flags[128];
    vts_store_version(s, &major, &minor);
    flag_names(flags, sizeof flags, g->flags, store_flag_names);
    printf("file:              %s\nformat version:    %u.%u\n", vts_store_name(s), major, minor);
    printf("size:              %u x %u texels\n", g->width, g->height);
    printf("tile:              %u content + 2 x %u border = %u payload texels\n",
           g->tile_content_px, g->border_px, g->tile_payload_px);
    printf("levels:            %u\nlayers:            %u\nflags:             %s\n", g->level_count,
           g->layer_count, flags[0] ? flags : "none");
    print_georef(s);
    for (uint32_t layer = 0; layer < g->layer_count; layer++)
        print_layer(s, st, layer);
    printf("tiles:             %llu stored, %llu empty, %llu shared\n",
           (unsigned long long)t->stored, (unsigned long long)t->empty,
           (unsigned long long)t->shared);
    printf("payload bytes:     %llu\nfile size:         %llu bytes\n", (unsigned long long)t->bytes,
           (unsigned long long)vts_store_file_size(s));
    if (isnan(st->bits_per_texel))
        printf("bits per texel:    n/a\ncompression ratio: n/a\n");
    else
        printf("bits per texel:    %.3f\ncompression ratio: %.3f\n", st->bits_per_texel,
               st->compression_ratio);
    printf("metadata:          %u entries\n", vts_store_meta_count(s));
    for (uint32_t i = 0; i < vts_store_meta_count(s); i++) {
        printf("  %s=", vts_store_meta_key(s, i));
        if (!vt_wang_print_list(vts_store_meta_key(s, i), vts_store_meta_value(s, i)))
            print_escaped(vts_store_meta_value(s, i));
        putchar('\n');
    }
    print_wang(s);
}

/* A JSON string of text from the file (layer names and metadata values are not checked for
 * UTF-8): as is when valid UTF-8, else with every byte >= 0x80 replaced by '?'. */
static json_t *json_text(const char *text)
{
    json_t *j = json_string(text);
    if (j)
        return j;
    char *copy = strdup(text);
    for (char *p = copy; p && *p; p++)
        *p = (unsigned char)*p >= 0x80 ? '?' : *p;
    j = copy ? json_string(copy) : NULL;
    free(copy);
    return j;
}

/* Sets the counters of st into obj (a new object when obj is NULL) and returns obj. */
static json_t *json_counts(json_t *obj, const struct vt_tile_counts *st)
{
    if (!obj)
        obj = json_object();
    json_object_set_new(obj, "tiles", json_integer((json_int_t)st->tiles));
    json_object_set_new(obj, "stored", json_integer((json_int_t)st->stored));
    json_object_set_new(obj, "empty", json_integer((json_int_t)st->empty));
    json_object_set_new(obj, "shared", json_integer((json_int_t)st->shared));
    json_object_set_new(obj, "bytes", json_integer((json_int_t)st->bytes));
    json_object_set_new(obj, "raw_bytes", json_integer((json_int_t)st->raw_bytes));
    return obj;
}

static json_t *json_flags(uint32_t flags, const char *const names[2])
{
    char text[128];
    json_t *array = json_array();
    flag_names(text, sizeof text, flags, names);
    for (char *name = strtok(text, " "); name; name = strtok(NULL, " "))
        json_array_append_new(array, json_string(name));
    return array;
}

static json_t *json_layer(const struct vts_store *s, const struct vt_store_stats *st,
                          uint32_t layer)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    const struct vts_layer *l = vts_store_layer(s, layer);
    char codec[5];
    json_t *levels = json_array();
    for (uint32_t i = 0; i < g->level_count; i++) {
        struct vts_level L;
        vts_store_level(s, i, &L);
        json_t *j = json_pack("{s:I, s:I, s:I, s:I, s:I}", "level", (json_int_t)i, "width",
                              (json_int_t)L.width, "height", (json_int_t)L.height, "tiles_x",
                              (json_int_t)L.tiles_x, "tiles_y", (json_int_t)L.tiles_y);
        json_array_append_new(levels, json_counts(j, vt_store_stats_at(st, layer, i)));
    }
    vts_codec_name(l->codec, codec);
    return json_pack("{s:I, s:o, s:s, s:I, s:s, s:s, s:o, s:I, s:o, s:o}", "index",
                     (json_int_t)layer, "name", json_text(l->name), "codec", codec, "channels",
                     (json_int_t)l->channels, "sample", vts_sample_name(l->sample), "colour",
                     vts_colour_name(l->colour), "flags", json_flags(l->flags, layer_flag_names),
                     "codec_param", (json_int_t)l->codec_param, "levels", levels, "totals",
                     json_counts(NULL, vt_store_stats_at(st, layer, g->level_count)));
}

/* gdalinfo -json's shape: geoTransform [6], coordinateSystem {wkt}, noDataValue; true when the
 * store has any (the JSON then prints reals with 17 digits). */
static bool json_georef(const struct vts_store *s, json_t *root)
{
    struct vt_georef g;
    vt_store_georef(s, 0, &g);
    if (g.has_transform) {
        json_t *a = json_array();
        for (int i = 0; i < 6; i++)
            json_array_append_new(a, json_real(g.transform[i]));
        json_object_set_new(root, "geoTransform", a);
    }
    if (g.crs_wkt)
        json_object_set_new(root, "coordinateSystem",
                            json_pack("{s:o}", "wkt", json_text(g.crs_wkt)));
    if (g.nodata) {
        char *end;
        double v = strtod(g.nodata, &end);
        json_object_set_new(root, "noDataValue",
                            end != g.nodata && !*end && isfinite(v) ? json_real(v)
                                                                    : json_text(g.nodata));
    }
    return g.has_transform || g.crs_wkt || g.nodata;
}

static int print_json(const struct vts_store *s, const struct vt_store_stats *st)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    unsigned major, minor;
    double bpt = st->bits_per_texel, ratio = st->compression_ratio;
    json_t *layers = json_array(), *meta = json_object();
    vts_store_version(s, &major, &minor);
    for (uint32_t layer = 0; layer < g->layer_count; layer++)
        json_array_append_new(layers, json_layer(s, st, layer));
    for (uint32_t i = 0; i < vts_store_meta_count(s); i++)
        json_object_set_new(meta, vts_store_meta_key(s, i), json_text(vts_store_meta_value(s, i)));
    json_t *totals = json_counts(NULL, &st->total);
    json_object_set_new(totals, "file_size", json_integer((json_int_t)vts_store_file_size(s)));
    json_object_set_new(totals, "bits_per_texel", isnan(bpt) ? json_null() : json_real(bpt));
    json_object_set_new(totals, "compression_ratio", isnan(ratio) ? json_null() : json_real(ratio));
    json_t *root =
        json_pack("{s:o, s:I, s:I, s:I, s:I, s:I, s:I, s:I, s:I, s:I, s:o, s:o, s:o, s:o}", "file",
                  json_text(vts_store_name(s)), "format_major", (json_int_t)major, "format_minor",
                  (json_int_t)minor, "width", (json_int_t)g->width, "height", (json_int_t)g->height,
                  "tile_content_px", (json_int_t)g->tile_content_px, "border_px",
                  (json_int_t)g->border_px, "tile_payload_px", (json_int_t)g->tile_payload_px,
                  "level_count", (json_int_t)g->level_count, "layer_count",
                  (json_int_t)g->layer_count, "flags", json_flags(g->flags, store_flag_names),
                  "layers", layers, "totals", totals, "metadata", meta);
    if (root && vt_wang_pack_is(s))
        json_object_set_new(root, "wang", json_wang(s));
    int digits = root && json_georef(s, root) ? 17 : 6;
    int rc = root ? json_dumpf(root, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(digits)) : -1;
    json_decref(root);
    if (rc != 0) {
        vt_log(VT_LOG_ERROR, "'%s': cannot write the JSON summary", vts_store_name(s));
        return VT_EXIT_BAD_INPUT;
    }
    putchar('\n');
    return VT_EXIT_OK;
}

int vti_run_summary(const struct vts_store *s, bool json)
{
    struct vt_store_stats st;
    struct vts_error err = {0};
    int rc = VT_EXIT_OK;
    if (vt_store_stats_init(&st, s, &err) != 0) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        rc = VT_EXIT_BAD_INPUT;
    } else if (json) {
        rc = print_json(s, &st);
    } else {
        print_summary(s, &st);
    }
    vt_store_stats_release(&st);
    return rc;
}
