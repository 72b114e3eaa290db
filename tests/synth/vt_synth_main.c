/* vt-synth: writes a seeded test store. Test utility, not installed. */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_synth.h"
#include "vts.h"

static void usage(FILE *f)
{
    fprintf(f, "usage: vt-synth OUT.vts [--size WxH] [--tile N] [--border B] [--layers N]\n"
               "                [--codec raw|png] [--channels 1-4] [--sample u8|u16|f16|f32]\n"
               "                [--seed N] [--empty] [--flat]\n");
}

static int parse_u32(const char *s, uint32_t *out)
{
    char *end;
    unsigned long v = strtoul(s, &end, 10);
    if (end == s || *end || v > 0xffffffffUL)
        return -1;
    *out = (uint32_t)v;
    return 0;
}

int main(int argc, char **argv)
{
    static const struct option opts[] = {
        {"size", required_argument, 0, 's'},   {"tile", required_argument, 0, 't'},
        {"border", required_argument, 0, 'b'}, {"layers", required_argument, 0, 'l'},
        {"codec", required_argument, 0, 'c'},  {"channels", required_argument, 0, 'n'},
        {"sample", required_argument, 0, 'S'}, {"seed", required_argument, 0, 'r'},
        {"empty", no_argument, 0, 'e'},        {"flat", no_argument, 0, 'f'},
        {"help", no_argument, 0, 'h'},         {0, 0, 0, 0}};
    struct vt_synth_options o;
    vt_synth_defaults(&o);
    int c, bad = 0;
    while ((c = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (c) {
        case 's':
            bad |= sscanf(optarg, "%ux%u", &o.width, &o.height) != 2;
            break;
        case 't':
            bad |= parse_u32(optarg, &o.tile_content_px);
            break;
        case 'b':
            bad |= parse_u32(optarg, &o.border_px);
            break;
        case 'l':
            bad |= parse_u32(optarg, &o.layer_count) || o.layer_count > VTS_MAX_LAYERS;
            break;
        case 'c':
            o.codec = strcmp(optarg, "png") == 0 ? VTS_CODEC_PNG : VTS_CODEC_RAW;
            break;
        case 'n':
            bad |= parse_u32(optarg, &o.channels);
            break;
        case 'S':
            o.sample = strcmp(optarg, "u16") == 0   ? VTS_SAMPLE_U16
                       : strcmp(optarg, "f16") == 0 ? VTS_SAMPLE_F16
                       : strcmp(optarg, "f32") == 0 ? VTS_SAMPLE_F32
                                                    : VTS_SAMPLE_U8;
            break;
        case 'r':
            bad |= parse_u32(optarg, &o.seed);
            break;
        case 'e':
            o.empty_tiles = true;
            break;
        case 'f':
            o.flat_left = true;
            break;
        case 'h':
            usage(stdout);
            return 0;
        default:
            bad = 1;
        }
    }
    if (bad || optind != argc - 1) {
        usage(stderr);
        return 2;
    }
    struct vts_error err = {0};
    if (vt_synth_store(argv[optind], &o, &err) != 0) {
        fprintf(stderr, "vt-synth: %s\n", err.message);
        return 1;
    }
    return 0;
}
