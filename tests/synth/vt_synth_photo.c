/* A seeded photo-like image: fractal value noise (smooth gradients and texture), hard-edged discs
 * and rectangles (edges), and film grain; identical on every machine. */
#include "vt_synth_photo.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>

static uint32_t photo_hash(uint32_t seed, int32_t x, int32_t y)
{
    uint32_t h = seed * 0x9e3779b1u ^ (uint32_t)x * 0x85ebca6bu ^ (uint32_t)y * 0xc2b2ae35u;
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    h *= 0x297a2d39u;
    h ^= h >> 15;
    return h;
}

/* Value noise in [0, 1] on a lattice of cell_px, smoothstep-interpolated. */
static double photo_value_noise(uint32_t seed, double x, double y, double cell_px)
{
    double fx = x / cell_px, fy = y / cell_px;
    int32_t ix = (int32_t)floor(fx), iy = (int32_t)floor(fy);
    double tx = fx - ix, ty = fy - iy;
    tx = tx * tx * (3 - 2 * tx);
    ty = ty * ty * (3 - 2 * ty);
    double v00 = photo_hash(seed, ix, iy) / 4294967295.0;
    double v10 = photo_hash(seed, ix + 1, iy) / 4294967295.0;
    double v01 = photo_hash(seed, ix, iy + 1) / 4294967295.0;
    double v11 = photo_hash(seed, ix + 1, iy + 1) / 4294967295.0;
    return (v00 + (v10 - v00) * tx) * (1 - ty) + (v01 + (v11 - v01) * tx) * ty;
}

/* Six octaves of value noise, cells of 96 to 3 texels, in [0, 1]. */
static double photo_fractal(uint32_t seed, double x, double y)
{
    double sum = 0, amp = 1, norm = 0, cell = 96;
    for (int octave = 0; octave < 6; octave++, amp *= 0.5, cell *= 0.5) {
        sum += amp * photo_value_noise(seed + (uint32_t)octave * 101u, x, y, cell);
        norm += amp;
    }
    return sum / norm;
}

static unsigned char photo_clamp(double v)
{
    return (unsigned char)(v < 0 ? 0 : v > 255 ? 255 : v + 0.5);
}

struct vt_image vt_synth_photo(uint32_t w, uint32_t h, uint32_t channels, uint32_t seed,
                               double chroma)
{
    struct vt_image img = {w, h, channels, VTS_SAMPLE_U8, (size_t)w * channels, NULL};
    img.pixels = malloc(img.stride * h);
    double disc[6][6]; /* cx, cy, r, red, green, blue */
    for (int i = 0; i < 6; i++)
        for (int k = 0; k < 6; k++)
            disc[i][k] = (photo_hash(seed + 7u, i, k) % 1000) / 1000.0;
    for (uint32_t y = 0; y < h; y++) {
        for (uint32_t x = 0; x < w; x++) {
            double lum = (photo_fractal(seed, x, y) - 0.5) * 2.2 * 255 + 128;
            double ca = (photo_fractal(seed + 1000u, x, y) - 0.5) * chroma * 2 * 255;
            double cb = (photo_fractal(seed + 2000u, x, y) - 0.5) * chroma * 2 * 255;
            double rgb[3] = {lum + ca, lum - 0.5 * ca + 0.5 * cb, lum - cb};
            for (int i = 0; i < 6; i++) {
                double dx = x - disc[i][0] * w, dy = y - disc[i][1] * h;
                double r = (0.05 + 0.15 * disc[i][2]) * (w < h ? w : h);
                bool inside = i < 4 ? dx * dx + dy * dy < r * r : fabs(dx) < r && fabs(dy) < r / 2;
                if (inside)
                    for (int k = 0; k < 3; k++)
                        rgb[k] = (0.3 + 0.7 * disc[i][3 + k]) * (0.6 * lum + 90);
            }
            unsigned char *t = (unsigned char *)img.pixels + y * img.stride + x * channels;
            int grain = (int)(photo_hash(seed + 3000u, (int32_t)x, (int32_t)y) % 7) - 3;
            if (channels == 1) {
                t[0] = photo_clamp(lum + grain);
                continue;
            }
            for (int k = 0; k < 3; k++)
                t[k] = photo_clamp(rgb[k] + grain);
            if (channels == 4) {
                double dx = x - 0.6 * w, dy = y - 0.4 * h;
                bool hole = dx * dx + dy * dy < 0.02 * w * h;
                t[3] = hole ? 0 : photo_clamp(photo_fractal(seed + 4000u, x, y) * 400 - 60);
            }
        }
    }
    return img;
}

double vt_synth_psnr_u8(const struct vt_image *a, const struct vt_image *b)
{
    double sum = 0;
    size_t row = (size_t)a->width * a->channels;
    for (uint32_t y = 0; y < a->height; y++) {
        const unsigned char *pa = (const unsigned char *)a->pixels + y * a->stride;
        const unsigned char *pb = (const unsigned char *)b->pixels + y * b->stride;
        for (size_t i = 0; i < row; i++)
            sum += (double)(pa[i] - pb[i]) * (pa[i] - pb[i]);
    }
    double mse = sum / ((double)row * a->height);
    return mse == 0 ? 99 : 10 * log10(255.0 * 255.0 / mse);
}
