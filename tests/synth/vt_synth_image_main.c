/* vt-synth-image: writes a seeded test image file (test utility used by scripts/demo, not
 * installed). usage: vt-synth-image OUT [--format tiff|png|jpeg|exr] [--size WxH] [--channels N]
 *                    [--sample u8|u16|f16|f32] [--tile N] [--seed N] */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_synth_images.h"
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
                                         {0, 0, 0, 0}};
    static const char *const formats[] = {"tiff", "png", "jpeg", "exr"};
    static const char *const samples[] = {"u8", "u16", "f16", "f32"};
    struct vt_synth_image_options o;
    vt_synth_image_defaults(&o);
    int c, i, bad = 0;
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
        default:
            bad = 1;
        }
    }
    if (bad || optind != argc - 1) {
        fprintf(stderr, "usage: vt-synth-image OUT [--format tiff|png|jpeg|exr] [--size WxH] "
                        "[--channels N] [--sample u8|u16|f16|f32] [--tile N] [--seed N]\n");
        return 2;
    }
    struct vt_error err = {0};
    if (vt_synth_image_write(argv[optind], &o, &err) != 0) {
        fprintf(stderr, "vt-synth-image: %s\n", err.message);
        return 1;
    }
    return 0;
}
