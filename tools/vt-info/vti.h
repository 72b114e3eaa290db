/* vt-info's parts (docs/cli/vt-info.md): the options (vti_main.c parses and checks them) and the
 * four things it does with a store, each in its own file: describe it (vti_describe.c: text or
 * JSON), check its tiles (vti_check.c: --verify, --stats), extract a level, tile or Wang region
 * (vti_extract.c). */
#ifndef VTI_H
#define VTI_H

#include <stdbool.h>
#include <stdint.h>

#include "vts.h"

struct options {
    const char *store_path;
    const char *out_path; /* -o */
    bool json, verify, extract, stats, has_tile, has_layer;
    uint32_t level, tile_x, tile_y, layer; /* --extract, --tile, --layer */
    bool wang_region;                      /* --wang-region X,Y,W,H */
    uint64_t wang_x, wang_y;
    uint32_t wang_w, wang_h;
};

/* Each returns the process's exit status. */
int vti_run_summary(const struct vts_store *s, bool json);
int vti_run_verify(const struct vts_store *s);
int vti_run_stats(const struct vts_store *s, const struct options *o);
int vti_run_extract(const struct vts_store *s, const struct options *o);

/* True when --extract's output path names a TIFF (.tif, .tiff), else it writes PNG. */
bool vti_wants_tiff(const char *path);

#endif
