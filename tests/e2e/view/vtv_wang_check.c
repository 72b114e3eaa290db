/* vt-view --wang checks (tests/e2e/view/run_wang_test.sh):
 *   vtv_wang_check edges A.png B.png TILES_ACROSS BAND
 * prints the PSNR (RGB) of A against B over the pixels within BAND pixels of a tile edge (the
 * frame shows TILES_ACROSS tiles across and down: edges at x = k * width / TILES_ACROSS), then the
 * PSNR over the other pixels; pixels within BAND of the frame's border are left out (the render
 * goes on into the tiles outside the extent, the reference wraps around it); exit 0, or 2 on bad
 * arguments or images of different sizes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_png_file.h"

static double edge_distance(uint32_t px, uint32_t size, double tiles)
{
    double t = (px + 0.5) * tiles / size; /* position in tiles */
    double f = t - floor(t);
    return (f < 0.5 ? f : 1 - f) * size / tiles; /* in pixels */
}

static double psnr(double se, double n)
{
    double mse = se / n;
    return mse > 0 ? 10 * log10(255.0 * 255.0 / mse) : 99.0;
}

int main(int argc, char **argv)
{
    struct vt_image a = {0}, b = {0};
    struct vts_error err = {0};
    if (argc != 6 || strcmp(argv[1], "edges") != 0) {
        fprintf(stderr, "usage: vtv_wang_check edges A.png B.png TILES_ACROSS BAND\n");
        return 2;
    }
    if (vt_png_file_read(argv[2], &a, &err) || vt_png_file_read(argv[3], &b, &err)) {
        fprintf(stderr, "vtv_wang_check: %s\n", err.message);
        return 2;
    }
    if (a.width != b.width || a.height != b.height || a.channels < 3 || b.channels < 3 ||
        a.sample != VTS_SAMPLE_U8 || b.sample != VTS_SAMPLE_U8) {
        fprintf(stderr, "vtv_wang_check: images differ in size or channels\n");
        return 2;
    }
    double tiles = atof(argv[4]), band = atof(argv[5]);
    double se_edge = 0, se_inner = 0, n_edge = 0, n_inner = 0;
    for (uint32_t y = 0; y < a.height; y++)
        for (uint32_t x = 0; x < a.width; x++) {
            if (x + 0.5 < band || y + 0.5 < band || a.width - x - 0.5 < band ||
                a.height - y - 0.5 < band)
                continue;
            bool edge =
                edge_distance(x, a.width, tiles) < band || edge_distance(y, a.height, tiles) < band;
            const uint8_t *p = vt_image_at(&a, x, y), *q = vt_image_at(&b, x, y);
            double se = 0;
            for (int c = 0; c < 3; c++)
                se += ((double)p[c] - q[c]) * ((double)p[c] - q[c]);
            *(edge ? &se_edge : &se_inner) += se;
            *(edge ? &n_edge : &n_inner) += 3;
        }
    printf("edges %.2f dB, inside %.2f dB\n", psnr(se_edge, n_edge), psnr(se_inner, n_inner));
    vt_image_release(&a);
    vt_image_release(&b);
    return 0;
}
