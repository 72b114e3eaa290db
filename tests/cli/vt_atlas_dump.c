/* vt-atlas-dump: reads an atlas.json through vt_layout_read() (so every check of the reader
 * runs) and prints it one line per entry (and its aliases) and texture, and one per material
 * (its entry, layers, constants and alpha mode), for the golden vt-atlas CLI cases. usage:
 * vt-atlas-dump atlas.json */
#include <stdio.h>

#include "vt_layout.h"

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: vt-atlas-dump atlas.json\n");
        return 2;
    }
    struct vt_layout l;
    struct vts_error err;
    if (vt_layout_read(argv[1], NULL, &l, &err)) {
        fprintf(stderr, "vt-atlas-dump: %s\n", err.message);
        vt_layout_release(&l);
        return 1;
    }
    printf("atlas %ux%u tile %u border %u\n", l.width, l.height, l.tile_content, l.border);
    for (uint32_t k = 0; k < l.layer_count; k++)
        printf("layer %s map %s colour %u\n", l.layers[k].name, l.layers[k].map,
               l.layers[k].colour);
    for (uint32_t i = 0; i < l.entry_count; i++) {
        const struct vt_layout_entry *e = &l.entries[i];
        printf("entry '%s' at %u,%u size %ux%u repeat %ux%u origin %d,%d cell %ux%u", e->name, e->x,
               e->y, e->width, e->height, e->repeat_u, e->repeat_v, e->origin_u, e->origin_v,
               e->cell_width, e->cell_height);
        if (e->cell_left || e->cell_top)
            printf(" at %u,%u", vt_layout_cell_x(e), vt_layout_cell_y(e));
        if ((uint64_t)e->crop_width * e->crop_height <
            (uint64_t)e->width * e->repeat_u * e->height * e->repeat_v)
            printf(" crop %u,%u %ux%u", e->crop_x, e->crop_y, e->crop_width, e->crop_height);
        if (e->wrap)
            printf(" wrap");
        printf(" align %u scale %g group %u\n", e->alignment, e->scale, e->group);
        if (e->alias_count) { /* each alias must find this entry */
            printf("  aliases");
            for (uint32_t a = 0; a < e->alias_count; a++)
                printf(" '%s'%s", e->aliases[a],
                       vt_layout_find(&l, e->aliases[a]) == e ? "" : " (NOT FOUND)");
            printf("\n");
        }
        for (uint32_t k = 0; k < l.layer_count; k++) {
            const struct vt_layout_texture *t = &e->textures[k];
            if (t->path)
                printf("  %s: '%s' %ux%u\n", l.layers[k].name, t->path, t->width, t->height);
            else
                printf("  %s: fill %g %g %g %g\n", l.layers[k].name, t->fill[0], t->fill[1],
                       t->fill[2], t->fill[3]);
        }
    }
    for (uint32_t i = 0; i < l.material_count; i++) {
        const struct vt_layout_material *m = &l.materials[i];
        printf("material '%s' entry '%s' alpha %s layers", m->name, l.entries[m->entry].name,
               vt_layout_alpha_name(m->alpha));
        for (uint32_t k = 0; k < l.layer_count; k++)
            if (m->layer_mask >> k & 1)
                printf(" %s", l.layers[k].name);
        printf("%s\n  Kd %g %g %g Ka %g %g %g Ks %g %g %g Ke %g %g %g Ns %g d %g illum %u\n",
               m->layer_mask ? "" : " -", m->kd[0], m->kd[1], m->kd[2], m->ka[0], m->ka[1],
               m->ka[2], m->ks[0], m->ks[1], m->ks[2], m->ke[0], m->ke[1], m->ke[2], m->ns, m->d,
               m->illum);
    }
    vt_layout_release(&l);
    return 0;
}
