/* libFuzzer target for the atlas.json reader (lib/layout/vt_layout_json.c, vt_layout.c). Invariants
 * are checked, not only crashes: a layout that loads has every cell inside the atlas with its
 * copies inside, every entry found by its name and by each of its aliases, resolved paths for every
 * texture; a failure has a status and a one-line message naming the input. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vt_layout.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define NAME "dir/atlas.json"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct vt_layout l;
    struct vts_error err = {0};
    int rc = vt_layout_parse_memory(data, size, NAME, NULL, &l, &err);
    if (rc < 0) {
        if (err.status != rc || !strstr(err.message, NAME) || strchr(err.message, '\n'))
            abort();
    } else {
        uint64_t names = 0;
        for (uint32_t i = 0; i < l.entry_count; i++) {
            const struct vt_layout_entry *e = &l.entries[i];
            if (e->cell_left > e->x || e->cell_top > e->y ||
                (uint64_t)vt_layout_cell_x(e) + e->cell_width > l.width ||
                (uint64_t)vt_layout_cell_y(e) + e->cell_height > l.height ||
                (uint64_t)e->width * e->repeat_u + e->cell_left > e->cell_width ||
                (uint64_t)e->height * e->repeat_v + e->cell_top > e->cell_height)
                abort();
            if (vt_layout_find(&l, e->name) != e)
                abort();
            for (uint32_t a = 0; a < e->alias_count; a++)
                if (!e->aliases[a][0] || vt_layout_find(&l, e->aliases[a]) != e)
                    abort();
            names += 1 + (uint64_t)e->alias_count;
            for (uint32_t k = 0; k < l.layer_count; k++)
                if (!e->textures[k].path != !e->textures[k].resolved)
                    abort();
        }
        if (names != l.name_count)
            abort();
    }
    vt_layout_release(&l);
    return 0;
}
