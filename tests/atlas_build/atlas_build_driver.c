/* vt-tiles-layout: a stand-in for `vt-tiles --layout` (same options, same exit codes) so that the
 * atlas build can be tested before vt-tiles.c calls vt_tiles_layout_run(). */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tool_common.h"
#include "vt_atomic_file.h"
#include "vt_image_input.h"
#include "vt_pool.h"
#include "vt_tiles_layout.h"

static const struct option long_options[] = {{"layout", required_argument, 0, 'L'},
                                             {"output", required_argument, 0, 'o'},
                                             {"layer", required_argument, 0, 'l'},
                                             {"export-atlas", required_argument, 0, 'E'},
                                             {"codec", required_argument, 0, 'C'},
                                             {"tile-size", required_argument, 0, 't'},
                                             {"keep", required_argument, 0, 'K'},
                                             {"border", required_argument, 0, 'b'},
                                             {"cache-mb", required_argument, 0, 'M'},
                                             {"threads", required_argument, 0, 'j'},
                                             {"quiet", no_argument, 0, 'q'},
                                             {"verbose", no_argument, 0, 'v'},
                                             {0, 0, 0, 0}};

int main(int argc, char **argv)
{
    vt_tool_init("vt-tiles");
    vt_atomic_file_cleanup_on_signals();
    struct vt_tiles_layout_options o = {.codec_name = "auto",
                                        .quality = 85,
                                        .subsampling = 420,
                                        .tile_size = 256,
                                        .threads = vt_pool_cpu_count(),
                                        .max_pixels = VT_INPUT_DEFAULT_MAX_PIXELS};
    uint32_t v;
    int c;
    opterr = 0;
    while ((c = vt_getopt_long(argc, argv, ":o:j:qv", long_options)) != -1) {
        switch (c) {
        case 'L':
            o.layout = optarg;
            break;
        case 'o':
            o.output = optarg;
            break;
        case 'l':
            o.layer = optarg;
            break;
        case 'E':
            o.export_atlas = optarg;
            break;
        case 'C':
            o.codec_name = optarg;
            break;
        case 't':
            if (vt_parse_u32(optarg, 8, 16384, &o.tile_size))
                return vt_usage_error("bad --tile-size '%s'", optarg);
            o.tile_size_set = true;
            break;
        case 'K':
            o.keep_content = strcmp(optarg, "content") == 0;
            break;
        case 'b':
            if (vt_parse_u32(optarg, 0, 64, &o.border))
                return vt_usage_error("bad --border '%s'", optarg);
            o.border_set = true;
            break;
        case 'M':
            if (vt_parse_u32(optarg, 1, 1u << 20, &v))
                return vt_usage_error("bad --cache-mb '%s'", optarg);
            o.cache_bytes = (uint64_t)v << 20;
            break;
        case 'j':
            if (vt_parse_u32(optarg, 1, 256, &v))
                return vt_usage_error("-j must be 1..256, not '%s'", optarg);
            o.threads = v;
            break;
        case 'q':
            vt_log_set_level(VT_LOG_ERROR);
            break;
        case 'v':
            vt_log_set_level(vt_log_get_level() + 1);
            break;
        default:
            return vt_usage_getopt_error(c, argv);
        }
    }
    if (!o.layout)
        return vt_usage_error("missing --layout atlas.json");
    return vt_tiles_layout_run(&o);
}
