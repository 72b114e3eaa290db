#include "vt_store_stats.h"
#include "vt_error.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static void counts_add(struct vt_tile_counts *sum, const struct vt_tile_counts *x)
{
    sum->tiles += x->tiles;
    sum->stored += x->stored;
    sum->empty += x->empty;
    sum->shared += x->shared;
    sum->bytes += x->bytes;
    sum->raw_bytes += x->raw_bytes;
}

struct offset_ref {
    uint64_t offset, index;
};

static int compare_offset_ref(const void *a, const void *b)
{
    const struct offset_ref *x = a, *y = b;
    if (x->offset != y->offset)
        return x->offset < y->offset ? -1 : 1;
    return x->index < y->index ? -1 : x->index > y->index;
}

/* Returns one byte per index entry, 1 where the entry is stored and an earlier entry has the same
 * payload offset (the reader checked that such entries also share length and CRC); NULL when out
 * of memory. Free with free(). */
static unsigned char *find_shared(const struct vts_store *s)
{
    uint64_t count = vts_store_tile_count(s), n = 0;
    unsigned char *shared = calloc(count ? count : 1, 1);
    struct offset_ref *refs = malloc((count ? count : 1) * sizeof *refs);
    if (!shared || !refs) {
        free(shared);
        free(refs);
        return NULL;
    }
    for (uint64_t i = 0; i < count; i++)
        if (vts_store_entry(s, i)->length > 0)
            refs[n++] = (struct offset_ref){vts_store_entry(s, i)->offset, i};
    qsort(refs, n, sizeof *refs, compare_offset_ref);
    for (uint64_t k = 1; k < n; k++)
        shared[refs[k].index] = refs[k].offset == refs[k - 1].offset;
    free(refs);
    return shared;
}

static void count_level(const struct vts_store *s, uint32_t layer, uint32_t level,
                        const unsigned char *shared, struct vt_tile_counts *c)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    uint64_t raw = vts_layer_tile_bytes(g, vts_store_layer(s, layer));
    struct vts_level L;
    vts_store_level(s, level, &L);
    uint64_t first = layer * vts_geometry_tiles_per_layer(g) + L.first_tile;
    uint64_t end = first + (uint64_t)L.tiles_x * L.tiles_y;
    for (uint64_t i = first; i < end; i++) {
        const struct vts_tile_entry *e = vts_store_entry(s, i);
        c->tiles++;
        c->empty += e->length == 0;
        c->stored += e->length > 0;
        c->shared += shared[i];
        c->bytes += shared[i] ? 0 : e->length;
        c->raw_bytes += e->length > 0 ? raw : 0;
    }
}

int vt_store_stats_init(struct vt_store_stats *st, const struct vts_store *store,
                        struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(store);
    memset(st, 0, sizeof *st);
    st->layer_count = g->layer_count;
    st->level_count = g->level_count;
    st->counts = calloc((size_t)g->layer_count * (g->level_count + 1), sizeof *st->counts);
    unsigned char *shared = find_shared(store);
    if (!st->counts || !shared) {
        free(shared);
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory counting the tiles of '%s'",
                            vts_store_name(store));
    }
    for (uint32_t layer = 0; layer < g->layer_count; layer++) {
        struct vt_tile_counts *row = st->counts + (size_t)layer * (g->level_count + 1);
        for (uint32_t level = 0; level < g->level_count; level++) {
            count_level(store, layer, level, shared, &row[level]);
            counts_add(&row[g->level_count], &row[level]);
        }
        counts_add(&st->total, &row[g->level_count]);
    }
    free(shared);
    double edge = g->tile_payload_px;
    st->bits_per_texel =
        st->total.stored ? 8.0 * (double)st->total.bytes / ((double)st->total.stored * edge * edge)
                         : NAN;
    st->compression_ratio =
        st->total.bytes ? (double)st->total.raw_bytes / (double)st->total.bytes : NAN;
    return 0;
}

void vt_store_stats_release(struct vt_store_stats *st)
{
    if (!st)
        return;
    free(st->counts);
    st->counts = NULL;
}

const struct vt_tile_counts *vt_store_stats_at(const struct vt_store_stats *st, uint32_t layer,
                                               uint32_t level)
{
    assert(layer < st->layer_count && level <= st->level_count);
    return &st->counts[(size_t)layer * (st->level_count + 1) + level];
}
