/* Writes the seed corpus of fuzz_codec_decode into a directory: for every codec and tile shape a
 * selector byte can pick (fuzz_codec_shape()), a synthetic tile encoded by that codec, prefixed
 * with the selector. Shapes whose payload exceeds 64 KiB are left out (they would raise libFuzzer's
 * -max_len for every input). Usage: make_codec_seeds DIR (created if missing) */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "vt_codec.h"
#include "vts.h"

int fuzz_codec_shape(uint8_t selector, const struct vt_codec **codec, uint32_t *edge,
                     uint32_t *channels, uint32_t *sample);

#define MAX_SEED (64u << 10)

static void fill(struct vt_image *img)
{
    for (uint32_t y = 0; y < img->height; y++) {
        unsigned char *row = vt_image_at(img, 0, y);
        for (uint32_t i = 0; i < img->width * img->channels; i++) {
            uint32_t x = i / img->channels, c = i % img->channels;
            uint32_t v = (x * 7 + y * 13 + c * 61 + ((x ^ y) & 5) * 9) & 0xff;
            if (img->sample == VTS_SAMPLE_U8) {
                row[i] = (unsigned char)v;
            } else if (img->sample == VTS_SAMPLE_U16) {
                uint16_t s = (uint16_t)(v * 257 + c);
                memcpy(row + 2 * i, &s, 2);
            } else if (img->sample == VTS_SAMPLE_F16) {
                uint16_t h = (uint16_t)(0x3800 + v * 3); /* halves in [0.5, 1) */
                memcpy(row + 2 * i, &h, 2);
            } else {
                float f = (float)v / 255.0f;
                memcpy(row + 4 * i, &f, 4);
            }
        }
    }
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: make_codec_seeds DIR\n");
        return 2;
    }
    if (mkdir(argv[1], 0777) != 0 && errno != EEXIST) {
        perror(argv[1]);
        return 1;
    }
    const struct vt_codec *seen_codec[256];
    uint32_t seen_shape[256];
    unsigned seen = 0, written = 0;
    for (unsigned sel = 0; sel < 256; sel++) {
        const struct vt_codec *c;
        uint32_t edge, channels, sample;
        if (fuzz_codec_shape((uint8_t)sel, &c, &edge, &channels, &sample) != 0)
            continue;
        uint32_t shape = edge << 8 | channels << 4 | sample;
        unsigned k = 0;
        while (k < seen && !(seen_codec[k] == c && seen_shape[k] == shape))
            k++;
        if (k < seen)
            continue;
        seen_codec[seen] = c;
        seen_shape[seen++] = shape;
        struct vts_error err = {0};
        struct vt_image img = {0};
        size_t bound = c->encoded_bound(edge, edge, channels, sample), len = 0;
        unsigned char *buf = malloc(bound + 1);
        if (!buf || vt_image_alloc(&img, edge, edge, channels, sample, &err) != 0) {
            fprintf(stderr, "make_codec_seeds: out of memory\n");
            return 1;
        }
        fill(&img);
        buf[0] = (unsigned char)sel;
        if (c->encode(&img, &(struct vt_codec_params){.quality = 80 + (int)(sel % 20)}, buf + 1,
                      bound, &len, &err) != 0) {
            fprintf(stderr, "make_codec_seeds: %s %ux%u: %s\n", c->name, edge, edge, err.message);
            return 1;
        }
        if (len + 1 <= MAX_SEED) {
            char path[4096];
            snprintf(path, sizeof path, "%s/%s-%u-%uch-%s", argv[1], c->name, edge, channels,
                     vts_sample_name(sample));
            FILE *f = fopen(path, "wb");
            if (!f || fwrite(buf, 1, len + 1, f) != len + 1 || fclose(f) != 0) {
                perror(path);
                return 1;
            }
            written++;
        }
        vt_image_release(&img);
        free(buf);
    }
    return written ? 0 : 1;
}
