/* The tile sink: encode + put, the --mode effort and the auto codec (see vt_tile_sink.h). */
#include "vt_tile_sink.h"

#include <stdlib.h>
#include <string.h>

#include "vt_error.h"

struct vt_tile_sink {
    struct vts_writer *writer;
    struct vt_tile_sink_layer *layers;
    uint32_t layer_count;
    unsigned workers;
    unsigned char **scratch; /* one buffer of `capacity` bytes per worker */
    size_t capacity;
};

int vt_tile_sink_effort(const struct vt_codec *codec, bool best)
{
    if (!best)
        return 0;
    return codec->fourcc == VTS_CODEC_PNG ? 9 : 1;
}

const char *vt_tile_sink_auto_codec(uint32_t sample, bool alpha, uint32_t colour)
{
    if (sample == VTS_SAMPLE_F16 || sample == VTS_SAMPLE_F32)
        return "raw";
    if (sample == VTS_SAMPLE_U16 || alpha || colour == VTS_COLOUR_NORMAL ||
        colour == VTS_COLOUR_DATA)
        return "png";
    return "jpeg";
}

const char *vt_tile_sink_codec_name(const char *requested, uint32_t sample, bool alpha,
                                    uint32_t colour)
{
    if (strcmp(requested, VT_TILE_SINK_AUTO) == 0)
        return vt_tile_sink_auto_codec(sample, alpha, colour);
    return requested;
}

const char *vt_tile_sink_gpu_codec(uint32_t channels, bool alpha, uint32_t colour)
{
    if (channels == 1)
        return "bc4";
    if (channels == 2 || (channels == 3 && colour == VTS_COLOUR_NORMAL))
        return "bc5";
    return alpha && channels == 4 ? "bc3" : "bc1";
}

const char *vt_tile_sink_layer_codec_name(const char *requested, uint32_t sample, uint32_t channels,
                                          bool alpha, uint32_t colour)
{
    if (strcmp(requested, VT_TILE_SINK_GPU) == 0)
        return vt_tile_sink_gpu_codec(channels, alpha, colour);
    return vt_tile_sink_codec_name(requested, sample, alpha, colour);
}

struct vt_tile_sink *vt_tile_sink_create(struct vts_writer *writer, uint32_t tile_payload_px,
                                         const struct vt_tile_sink_layer *layers,
                                         uint32_t layer_count, unsigned workers,
                                         size_t min_scratch_bytes, struct vts_error *err)
{
    if (!writer || workers == 0 || (layer_count && !layers)) {
        vt_error_set(err, VTS_ERR_ARG, "invalid tile sink arguments");
        return NULL;
    }
    struct vt_tile_sink *s = calloc(1, sizeof *s);
    if (!s)
        goto out_nomem;
    s->writer = writer;
    s->workers = workers;
    s->capacity = min_scratch_bytes;
    s->layers = calloc(layer_count ? layer_count : 1, sizeof *s->layers);
    s->scratch = calloc(workers, sizeof *s->scratch);
    if (!s->layers || !s->scratch)
        goto out_nomem;
    s->layer_count = layer_count;
    for (uint32_t i = 0; i < layer_count; i++) {
        s->layers[i] = layers[i];
        if (!layers[i].codec)
            continue;
        size_t bound = layers[i].codec->encoded_bound(tile_payload_px, tile_payload_px,
                                                      layers[i].channels, layers[i].sample);
        s->capacity = bound > s->capacity ? bound : s->capacity;
    }
    for (unsigned i = 0; i < workers; i++)
        if (!(s->scratch[i] = malloc(s->capacity ? s->capacity : 1)))
            goto out_nomem;
    return s;

out_nomem:
    vt_error_set(err, VTS_ERR_NOMEM, "out of memory for encode buffers");
    vt_tile_sink_destroy(s);
    return NULL;
}

int vt_tile_sink_put(struct vt_tile_sink *s, unsigned worker, uint32_t layer, uint32_t level,
                     uint32_t tx, uint32_t ty, const struct vt_image *tile, struct vts_error *err)
{
    if (worker >= s->workers || layer >= s->layer_count || (tile && !s->layers[layer].codec))
        return vt_error_set(err, VTS_ERR_ARG, "tile sink: no worker %u or codec for layer %u",
                            worker, layer);
    const struct vt_tile_sink_layer *l = &s->layers[layer];
    size_t len = 0;
    if (tile) {
        struct vts_error cerr = {0};
        int rc = l->codec->encode(tile, &l->params, s->scratch[worker], s->capacity, &len, &cerr);
        if (rc)
            return vt_error_set(err, rc, "cannot encode tile %u,%u of level %u: %s", tx, ty, level,
                                cerr.message);
    }
    return vts_writer_put(s->writer, layer, level, tx, ty, s->scratch[worker], len, err);
}

void *vt_tile_sink_scratch(struct vt_tile_sink *s, unsigned worker, size_t *capacity)
{
    if (worker >= s->workers)
        return NULL;
    if (capacity)
        *capacity = s->capacity;
    return s->scratch[worker];
}

void vt_tile_sink_destroy(struct vt_tile_sink *s)
{
    if (!s)
        return;
    for (unsigned i = 0; s->scratch && i < s->workers; i++)
        free(s->scratch[i]);
    free(s->scratch);
    free(s->layers);
    free(s);
}
