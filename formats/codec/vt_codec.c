/* The const registry of the codecs compiled into this build. */
#include <string.h>

#include "internal/vt_codec_impl.h"
#include "vt_codec.h"

/* Stable order (vt-info and --help list codecs in it). A new codec is one line here. */
static const struct vt_codec *const vt_codecs[] = {
    &vt_codec_raw, &vt_codec_png, &vt_codec_jpeg, &vt_codec_bc1,
    &vt_codec_bc3, &vt_codec_bc4, &vt_codec_bc5,
};

#define VT_CODEC_COUNT (sizeof vt_codecs / sizeof vt_codecs[0])

const struct vt_codec *vt_codec_find(const char *name)
{
    if (!name)
        return NULL;
    for (size_t i = 0; i < VT_CODEC_COUNT; i++)
        if (strcmp(vt_codecs[i]->name, name) == 0)
            return vt_codecs[i];
    return NULL;
}

const struct vt_codec *vt_codec_by_fourcc(uint32_t fourcc)
{
    for (size_t i = 0; i < VT_CODEC_COUNT; i++)
        if (vt_codecs[i]->fourcc == fourcc)
            return vt_codecs[i];
    return NULL;
}

const struct vt_codec *const *vt_codec_list(size_t *count)
{
    if (count)
        *count = VT_CODEC_COUNT;
    return vt_codecs;
}
