/* The libvips reference of scripts/bench/layout-vs-vips: an atlas composited the libvips way, a
 * black canvas with every photo inserted at its place (one lazy vips_insert chain), streamed into
 * vips_dzsave (PNG tiles). Not built by CMake (libvips-dev is a bench extra): the script compiles
 * it. Usage: vips_atlas_dz PLACES OUT TILE OVERLAP, PLACES = "W H ..." then "x y path" lines. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <vips/vips.h>

static int fail(void)
{
    fprintf(stderr, "vips_atlas_dz: %s\n", vips_error_buffer());
    return 1;
}

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: vips_atlas_dz PLACES OUT TILE OVERLAP\n");
        return 2;
    }
    if (VIPS_INIT(argv[0]))
        return fail();
    FILE *f = fopen(argv[1], "r");
    char line[4096];
    int w, h;
    if (!f || !fgets(line, sizeof line, f) || sscanf(line, "%d %d", &w, &h) != 2) {
        fprintf(stderr, "vips_atlas_dz: cannot read '%s'\n", argv[1]);
        return 1;
    }
    VipsImage *canvas;
    if (vips_black(&canvas, w, h, "bands", 3, NULL))
        return fail();
    VipsImage *u8;
    if (vips_cast_uchar(canvas, &u8, NULL))
        return fail();
    g_object_unref(canvas);
    canvas = u8;
    int x, y;
    char path[4000];
    while (fgets(line, sizeof line, f) && sscanf(line, "%d %d %3999s", &x, &y, path) == 3) {
        VipsImage *photo, *rgb, *out;
        if (!(photo = vips_image_new_from_file(path, "access", VIPS_ACCESS_SEQUENTIAL, NULL)))
            return fail();
        /* grey photos become RGB, alpha is flattened: the canvas is RGB */
        if (vips_colourspace(photo, &rgb, VIPS_INTERPRETATION_sRGB, NULL))
            return fail();
        g_object_unref(photo);
        if (rgb->Bands == 4) {
            VipsImage *flat;
            if (vips_flatten(rgb, &flat, NULL))
                return fail();
            g_object_unref(rgb);
            rgb = flat;
        }
        if (vips_insert(canvas, rgb, &out, x, y, NULL))
            return fail();
        g_object_unref(rgb);
        g_object_unref(canvas);
        canvas = out;
    }
    fclose(f);
    if (vips_dzsave(canvas, argv[2], "tile_size", atoi(argv[3]), "overlap", atoi(argv[4]), "depth",
                    VIPS_FOREIGN_DZ_DEPTH_ONETILE, "suffix", ".png", NULL))
        return fail();
    g_object_unref(canvas);
    vips_shutdown();
    return 0;
}
