/* vt-synth-image: writes a seeded test image file (test utility used by scripts/demo, not
 * installed). usage: vt-synth-image OUT [--format tiff|png|jpeg|exr] [--size WxH] [--channels N]
 *                    [--sample u8|u16|f16|f32] [--tile N] [--seed N] [--photo]
 *                    [--alpha pattern|cutout|smooth|binary|opaque|sparse]
 * --photo: a photo-like RGB PNG (gradients, texture, hard edges, grain) instead of the pattern.
 * --alpha: the shape of the alpha channel (2 or 4 channels, u8; enum vt_synth_alpha). */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_png_file.h"
#include "vt_synth_images.h"
#include "vt_synth_photo.h"
#include "vts.h"

static int pick(const char *s, const char *const *names, int n)
{
    for (int i = 0; i < n; i++)
        if (strcmp(s, names[i]) == 0)
            return i;
    return -1;
}

int main(int argc, char **argv)
{
    static const struct option opts[] = {{"format", required_argument, 0, 'f'},
                                         {"size", required_argument, 0, 's'},
                                         {"channels", required_argument, 0, 'c'},
                                         {"sample", required_argument, 0, 'S'},
                                         {"tile", required_argument, 0, 't'},
                                         {"seed", required_argument, 0, 'r'},
                                         {"photo", no_argument, 0, 'p'},
                                         {"alpha", required_argument, 0, 'a'},
                                         {0, 0, 0, 0}};
    static const char *const alphas[] = {"pattern", "cutout", "smooth",
                                         "binary",  "opaque", "sparse"};
    static const char *const formats[] = {"tiff", "png", "jpeg", "exr"};
    static const char *const samples[] = {"u8", "u16", "f16", "f32"};
    struct vt_synth_image_options o;
    vt_synth_image_defaults(&o);
    int c, i, bad = 0, photo = 0;
    while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
        switch (c) {
        case 'f':
            i = pick(optarg, formats, 4);
            bad |= i < 0;
            o.format = (uint32_t)(i + 1);
            break;
        case 's':
            bad |= sscanf(optarg, "%ux%u", &o.width, &o.height) != 2;
            break;
        case 'c':
            o.channels = (uint32_t)atoi(optarg);
            break;
        case 'S':
            i = pick(optarg, samples, 4);
            bad |= i < 0;
            o.sample = (uint32_t)(i + 1);
            break;
        case 't':
            o.tile_w = o.tile_h = (uint32_t)atoi(optarg);
            break;
        case 'r':
            o.seed = (uint32_t)atoi(optarg);
            break;
        case 'p':
            photo = 1;
            break;
        case 'a':
            i = pick(optarg, alphas, 6);
            bad |= i < 0;
            o.alpha_shape = (uint32_t)(i < 0 ? 0 : i);
            break;
        default:
            bad = 1;
        }
    }
    if (bad || optind != argc - 1) {
        fprintf(
            stderr,
            "usage: vt-synth-image OUT [--format tiff|png|jpeg|exr] [--size WxH] [--channels N] [--sample u8|u16|f16|f32] [--tile N] [--seed N] [--photo] [--alpha pattern|cutout|smooth|binary|opaque|sparse]\n");
        return 2;
    }
    struct vts_error err = {0};
    if (photo) {
        struct vt_image img = vt_synth_photo(o.width, o.height, 3, o.seed, 0.8);
        struct vt_png_file_writer *w =
            img.pixels ? vt_png_file_writer_create(argv[optind], o.width, o.height, 3, 8, &err)
                       : NULL;
        int rc = w ? vt_png_file_writer_rows(w, img.pixels, o.height, img.stride, &err) : -1;
        if (rc == 0)
            rc = vt_png_file_writer_finish(w, &err);
        vt_png_file_writer_destroy(w);
        free(img.pixels);
        if (rc != 0) {
            fprintf(stderr, "vt-synth-image: %s\n", err.message[0] ? err.message : "failed");
            return 1;
        }
        return 0;
    }
    if (vt_synth_image_write(argv[optind], &o, &err) != 0) {
        fprintf(stderr, "vt-synth-image: %s\n", err.message);
        return 1;
    }
    return 0;
}
