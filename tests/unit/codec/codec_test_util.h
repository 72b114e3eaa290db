/* Shared by the codec tests: encode into a fresh buffer of the codec's encoded_bound() bytes. */
#ifndef CODEC_TEST_UTIL_H
#define CODEC_TEST_UTIL_H

#include <stdio.h>
#include <stdlib.h>

#include "vt_codec.h"
#include "vt_test.h"

/* Encodes img with codec into a freshly allocated buffer of encoded_bound() bytes and checks that
 * the payload fits it; NULL (and a failed check) on error. */
static inline unsigned char *encode_alloc(const struct vt_codec *codec, const struct vt_image *img,
                                          int effort, size_t *len)
{
    size_t bound = codec->encoded_bound(img->width, img->height, img->channels, img->sample);
    unsigned char *buf = malloc(bound ? bound : 1);
    struct vt_codec_params params = {.effort = effort};
    struct vts_error err = {0};
    int rc = codec->encode(img, &params, buf, bound, len, &err);
    VT_CHECK_INT_EQ(rc, 0);
    if (rc != 0) {
        fprintf(stderr, "  encode: %s\n", err.message);
        free(buf);
        return NULL;
    }
    VT_CHECK(*len <= bound);
    return buf;
}

#endif
