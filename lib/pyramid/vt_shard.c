#include "vt_shard.h"

#include <stdio.h>
#include <string.h>

#include "vt_image.h"

int vt_shard_parse(const char *text, uint32_t *index, uint32_t *count)
{
    unsigned i = 0, n = 0;
    int used = 0;
    if (!text || text[0] < '0' || text[0] > '9' || sscanf(text, "%u/%u%n", &i, &n, &used) != 2 ||
        text[used] != '\0' || strchr(text, '+') || strchr(text, '-') || n == 0 ||
        n > VT_SHARD_MAX_COUNT || (n & (n - 1)) != 0 || i < 1 || i > n)
        return -1;
    *index = i;
    *count = n;
    return 0;
}

void vt_shard_build_format(const struct vt_shard_build *b, char *out, size_t cap)
{
    snprintf(out, cap,
             "levels-per-pass=%u channels=%u alpha=%u premultiplied=%u subsampling=%u effort=%u "
             "carry=%s",
             b->levels_per_pass, b->channels, b->has_alpha ? 1u : 0u, b->premultiplied ? 1u : 0u,
             b->subsampling, b->effort, b->seams ? "seams" : "level");
}

int vt_shard_build_parse(const char *text, struct vt_shard_build *out)
{
    unsigned k, ch, alpha, premul, sub, effort;
    char carry[8];
    int used = 0;
    if (!text ||
        sscanf(text,
               "levels-per-pass=%u channels=%u alpha=%u premultiplied=%u subsampling=%u effort=%u "
               "carry=%7[a-z]%n",
               &k, &ch, &alpha, &premul, &sub, &effort, carry, &used) != 7 ||
        text[used] != '\0' || k < 1 || k > 6 || ch < 1 || ch > 4 || alpha > 1 || premul > 1 ||
        effort > 9 || (strcmp(carry, "seams") != 0 && strcmp(carry, "level") != 0))
        return -1;
    *out = (struct vt_shard_build){
        k, ch, alpha == 1, premul == 1, sub, effort, strcmp(carry, "seams") == 0};
    return 0;
}

static void put_le32(unsigned char *d, float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    d[0] = (unsigned char)u;
    d[1] = (unsigned char)(u >> 8);
    d[2] = (unsigned char)(u >> 16);
    d[3] = (unsigned char)(u >> 24);
}

static float get_le32(const unsigned char *s)
{
    uint32_t u = (uint32_t)s[0] | (uint32_t)s[1] << 8 | (uint32_t)s[2] << 16 | (uint32_t)s[3] << 24;
    float f;
    memcpy(&f, &u, 4);
    return f;
}

void vt_shard_pack(unsigned char *payload, const float *texels, uint32_t width, uint32_t height,
                   uint32_t channels, size_t stride)
{
    size_t row_floats = (size_t)width * channels;
    for (uint32_t y = 0; y < height; y++) {
        const float *s = texels + (size_t)y * stride;
        unsigned char *d = payload + (size_t)y * row_floats * 4;
        if (vt_host_is_little_endian())
            memcpy(d, s, row_floats * 4);
        else
            for (size_t i = 0; i < row_floats; i++)
                put_le32(d + 4 * i, s[i]);
    }
}

void vt_shard_unpack_row(const unsigned char *payload, uint32_t width, uint32_t channels,
                         uint32_t row, float *out)
{
    size_t row_floats = (size_t)width * channels;
    const unsigned char *s = payload + (size_t)row * row_floats * 4;
    if (vt_host_is_little_endian())
        memcpy(out, s, row_floats * 4);
    else
        for (size_t i = 0; i < row_floats; i++)
            out[i] = get_le32(s + 4 * i);
}
