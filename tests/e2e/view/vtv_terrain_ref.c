/* Test helper for vt-view --terrain (run_terrain_test.sh): the elevation raster and a CPU
 * reference of the displaced grid, independent of vt-view's code.
 *   vtv_terrain_ref dem W H F32.tif U16.tif SCALE OFFSET
 *       a W x H elevation raster with the properties of a real DEM: a tilted base, rounded
 *       hills, a sharp ridge (a crease), a winding valley, a flat plateau with steep sides and a
 *       nodata hole; as 32-bit floats (hole -9999) and as u16 = round((h - OFFSET) / SCALE)
 *       (hole 0). Prints the lowest and highest valid elevation.
 *   vtv_terrain_ref render ELEV COLOUR.png OUT.png W H G SCALE OFFSET NODATA SX SZ EXAG
 *                          EX EY EZ TX TY TZ FOVY SHIFT X0 Y0 X1 Y1
 *       the terrain as docs/viewer.md ("Terrain") describes it, rendered in software: the
 *       elevation file read here (value = stored * SCALE + OFFSET, NODATA texels the lowest valid
 *       elevation), a G x G grid over SX x SZ units centred on the origin whose corners lie at
 *       (X0, Y0) and (X1, Y1) of the elevation raster (in its texels), heights times EXAG,
 *       bilinear at level 0 (texel centres at half-integers), normals by central differences;
 *       the camera of a vt-view camera line (look-at with y up, perspective of FOVY degrees),
 *       a z-buffer, texcoords and normals interpolated perspective-correctly; the colour image
 *       sampled bilinearly in linear light from its own 2 x 2 box mip levels at vt-view's level
 *       (the nearest level to log2 of the larger texcoord derivative per pixel), shifted SHIFT
 *       texels along u (0: none; a negative control); lit as vt-view's lit materials: colour *
 *       (ambient 0.15 + 0.85 * max(n . l, 0)), l = normalize(0.3, 0.8, 0.5), n turned round on
 *       back faces (a wall seen from behind), encoded sRGB.
 *       Background (26, 26, 26). Writes an RGB PNG.
 * Exit 0 on success, 1 on failure, 2 on bad use. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_image.h"
#include "vt_image_input.h"
#include "vt_png_file.h"
#include "vt_tiff_file.h"

#define PI 3.14159265358979323846

static double smooth(double e0, double e1, double x)
{
    double t = fmin(fmax((x - e0) / (e1 - e0), 0.0), 1.0);
    return t * t * (3 - 2 * t);
}

/* The elevation at texel centre (x, y) of a w x h raster; NAN inside the hole. */
static double dem_at(double x, double y, double w, double h)
{
    double u = x / w, v = y / h;
    double z = 20.0 + 40.0 * u + 15.0 * v;                                       /* tilt */
    z += 90.0 * exp(-((u - 0.25) * (u - 0.25) + (v - 0.3) * (v - 0.3)) / 0.012); /* hill */
    z += 60.0 * exp(-((u - 0.7) * (u - 0.7) + (v - 0.75) * (v - 0.75)) / 0.02);  /* hill */
    z += 25.0 * sin(x / 37.0) * cos(y / 53.0);                                   /* rolling */
    double d = fabs((u - 0.55) - 0.6 * (v - 0.2)) * w;                           /* ridge */
    z += 130.0 * fmax(0.0, 1.0 - d / 45.0) * smooth(0.05, 0.25, v) * (1 - smooth(0.7, 0.9, v));
    double c = 0.15 + 0.05 * sin(v * 9.0); /* valley */
    z -= 70.0 * exp(-((u - c) * w) * ((u - c) * w) / (2 * 25.0 * 25.0));
    double r = hypot((u - 0.8) * w, (v - 0.25) * h); /* plateau */
    double p = 1 - smooth(95.0, 105.0, r);
    z = z * (1 - p) + 200.0 * p;
    if (fabs(u - 0.45) * w < 20 && fabs(v - 0.8) * h < 15)
        return NAN;
    return z;
}

static int make_dem(int argc, char **argv)
{
    if (argc != 8)
        return 2;
    uint32_t w = (uint32_t)atoi(argv[2]), h = (uint32_t)atoi(argv[3]);
    double scale = atof(argv[6]), offset = atof(argv[7]);
    if (w < 16 || h < 16 || w > 8192 || h > 8192 || scale == 0)
        return 2;
    float *f = malloc((size_t)w * h * sizeof(float));
    uint16_t *q = malloc((size_t)w * h * sizeof(uint16_t));
    if (!f || !q)
        return 1;
    double lo = INFINITY, hi = -INFINITY;
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            double z = dem_at(x + 0.5, y + 0.5, w, h);
            size_t i = (size_t)y * w + x;
            if (isnan(z)) {
                f[i] = -9999.0f;
                q[i] = 0;
                continue;
            }
            f[i] = (float)z;
            double s = round((z - offset) / scale);
            if (s < 1 || s > 65535) {
                fprintf(stderr, "dem: %g does not fit u16 with scale %g offset %g\n", z, scale,
                        offset);
                return 1;
            }
            q[i] = (uint16_t)s;
            lo = fmin(lo, z);
            hi = fmax(hi, z);
        }
    struct vts_error err = {0};
    struct vt_tiff_file_writer *tw =
        vt_tiff_file_writer_create_sample(argv[4], w, h, 1, VTS_SAMPLE_F32, &err);
    int rc = tw ? vt_tiff_file_writer_rows(tw, f, h, (size_t)w * 4, &err) : -1;
    if (rc == 0)
        rc = vt_tiff_file_writer_finish(tw, &err);
    vt_tiff_file_writer_destroy(tw);
    tw = rc == 0 ? vt_tiff_file_writer_create_sample(argv[5], w, h, 1, VTS_SAMPLE_U16, &err) : NULL;
    rc = tw ? vt_tiff_file_writer_rows(tw, q, h, (size_t)w * 2, &err) : -1;
    if (rc == 0)
        rc = vt_tiff_file_writer_finish(tw, &err);
    vt_tiff_file_writer_destroy(tw);
    free(f);
    free(q);
    if (rc != 0) {
        fprintf(stderr, "dem: %s\n", err.message);
        return 1;
    }
    printf("%.6f %.6f\n", lo, hi);
    return 0;
}

/* A whole image read through the project's input readers. */
static int read_image(const char *path, struct vt_image *img)
{
    struct vt_source src;
    struct vts_error err = {0};
    int rc = vt_image_input_open(path, NULL, &src, &err);
    if (rc == 0)
        rc = vt_image_alloc(img, src.info.width, src.info.height, src.info.channels,
                            src.info.sample, &err);
    if (rc == 0)
        rc = vt_source_read(&src, 0, 0, img, &err);
    vt_source_close(&src);
    if (rc != 0)
        fprintf(stderr, "render: %s\n", err.message);
    return rc;
}

static double srgb_to_linear(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

static double linear_to_srgb(double c)
{
    c = fmin(fmax(c, 0.0), 1.0);
    return c <= 0.0031308 ? c * 12.92 : 1.055 * pow(c, 1 / 2.4) - 0.055;
}

struct level {
    uint32_t w, h;
    double *rgb; /* linear */
};

struct scene {
    uint32_t G;
    double *p; /* G*G*3 positions */
    double *n; /* G*G*3 normals */
    struct level mip[24];
    uint32_t levels;
    uint32_t cw, ch; /* colour level 0 */
    double shift;
};

static void mul4(const double a[16], const double b[16], double o[16]) /* column-major a*b */
{
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            double s = 0;
            for (int k = 0; k < 4; k++)
                s += a[k * 4 + r] * b[c * 4 + k];
            o[c * 4 + r] = s;
        }
}

static void norm3(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++)
        v[k] /= l;
}

/* Bilinear, clamped, at level l; t in level-0 texels. */
static void tex(const struct scene *s, uint32_t l, double tx, double ty, double out[3])
{
    const struct level *m = &s->mip[l];
    double sc = ldexp(1.0, -(int)l);
    double u = fmin(fmax(tx * sc - 0.5, 0.0), m->w - 1.0);
    double v = fmin(fmax(ty * sc - 0.5, 0.0), m->h - 1.0);
    uint32_t x0 = (uint32_t)u, y0 = (uint32_t)v;
    uint32_t x1 = x0 + 1 < m->w ? x0 + 1 : x0, y1 = y0 + 1 < m->h ? y0 + 1 : y0;
    double fx = u - x0, fy = v - y0;
    for (int k = 0; k < 3; k++) {
        double a = m->rgb[((size_t)y0 * m->w + x0) * 3 + k] * (1 - fx) +
                   m->rgb[((size_t)y0 * m->w + x1) * 3 + k] * fx;
        double b = m->rgb[((size_t)y1 * m->w + x0) * 3 + k] * (1 - fx) +
                   m->rgb[((size_t)y1 * m->w + x1) * 3 + k] * fx;
        out[k] = a * (1 - fy) + b * fy;
    }
}

static int render(int argc, char **argv)
{
    if (argc != 26)
        return 2;
    const char *elev = argv[2], *colour = argv[3], *out = argv[4];
    uint32_t W = (uint32_t)atoi(argv[5]), H = (uint32_t)atoi(argv[6]), G = (uint32_t)atoi(argv[7]);
    double scale = atof(argv[8]), offset = atof(argv[9]), nodata = atof(argv[10]);
    double sx = atof(argv[11]), sz = atof(argv[12]), exag = atof(argv[13]);
    double cam[7];
    for (int k = 0; k < 7; k++)
        cam[k] = atof(argv[14 + k]);
    double shift = atof(argv[21]);
    double win[4] = {atof(argv[22]), atof(argv[23]), atof(argv[24]), atof(argv[25])};
    if (W < 16 || H < 16 || W > 4096 || H > 4096 || G < 2 || G > 4096)
        return 2;
    struct vt_image e = {0}, c = {0};
    if (read_image(elev, &e) || read_image(colour, &c))
        return 1;
    if (e.channels != 1 || c.sample != VTS_SAMPLE_U8 || c.channels < 3) {
        fprintf(stderr, "render: unexpected image formats\n");
        return 1;
    }
    /* elevations */
    size_t ne = (size_t)e.width * e.height;
    double *hgt = malloc(ne * sizeof(double)), lo = INFINITY;
    for (uint32_t y = 0; y < e.height; y++)
        for (uint32_t x = 0; x < e.width; x++) {
            const void *px = vt_image_at(&e, x, y);
            double v = e.sample == VTS_SAMPLE_F32   ? *(const float *)px
                       : e.sample == VTS_SAMPLE_U16 ? *(const uint16_t *)px
                                                    : *(const uint8_t *)px;
            double z = v == nodata ? NAN : v * scale + offset;
            hgt[(size_t)y * e.width + x] = z;
            if (!isnan(z))
                lo = fmin(lo, z);
        }
    for (size_t i = 0; i < ne; i++)
        if (isnan(hgt[i]))
            hgt[i] = lo;
    struct scene s = {.G = G, .shift = shift, .cw = c.width, .ch = c.height};
    s.p = malloc((size_t)G * G * 3 * sizeof(double));
    s.n = malloc((size_t)G * G * 3 * sizeof(double));
    for (uint32_t j = 0; j < G; j++)
        for (uint32_t i = 0; i < G; i++) {
            double fu = (double)i / (G - 1), fv = (double)j / (G - 1);
            double ex = win[0] + fu * (win[2] - win[0]), ey = win[1] + fv * (win[3] - win[1]);
            double u = fmin(fmax(ex - 0.5, 0), e.width - 1.0);
            double v = fmin(fmax(ey - 0.5, 0), e.height - 1.0);
            uint32_t x0 = (uint32_t)u, y0 = (uint32_t)v;
            uint32_t x1 = x0 + 1 < e.width ? x0 + 1 : x0, y1 = y0 + 1 < e.height ? y0 + 1 : y0;
            double fx = u - x0, fy = v - y0;
            const double *r0 = hgt + (size_t)y0 * e.width, *r1 = hgt + (size_t)y1 * e.width;
            double z = (r0[x0] * (1 - fx) + r0[x1] * fx) * (1 - fy) +
                       (r1[x0] * (1 - fx) + r1[x1] * fx) * fy;
            double *q = s.p + ((size_t)j * G + i) * 3;
            q[0] = (fu - 0.5) * sx;
            q[1] = z * exag;
            q[2] = (fv - 0.5) * sz;
        }
    for (uint32_t j = 0; j < G; j++)
        for (uint32_t i = 0; i < G; i++) {
            const double *l = s.p + ((size_t)j * G + (i ? i - 1 : i)) * 3;
            const double *r = s.p + ((size_t)j * G + (i + 1 < G ? i + 1 : i)) * 3;
            const double *t = s.p + ((size_t)(j ? j - 1 : j) * G + i) * 3;
            const double *b = s.p + ((size_t)(j + 1 < G ? j + 1 : j) * G + i) * 3;
            double *n = s.n + ((size_t)j * G + i) * 3;
            n[0] = -(r[1] - l[1]) / (r[0] - l[0]);
            n[1] = 1;
            n[2] = -(b[1] - t[1]) / (b[2] - t[2]);
            norm3(n);
        }
    /* colour mips, linear light */
    s.mip[0].w = c.width;
    s.mip[0].h = c.height;
    s.mip[0].rgb = malloc((size_t)c.width * c.height * 3 * sizeof(double));
    for (uint32_t y = 0; y < c.height; y++)
        for (uint32_t x = 0; x < c.width; x++)
            for (int k = 0; k < 3; k++)
                s.mip[0].rgb[((size_t)y * c.width + x) * 3 + k] =
                    srgb_to_linear(((const uint8_t *)vt_image_at(&c, x, y))[k] / 255.0);
    s.levels = 1;
    while (s.levels < 24 && (s.mip[s.levels - 1].w > 1 || s.mip[s.levels - 1].h > 1)) {
        const struct level *a = &s.mip[s.levels - 1];
        struct level *b = &s.mip[s.levels];
        b->w = (a->w + 1) / 2;
        b->h = (a->h + 1) / 2;
        b->rgb = malloc((size_t)b->w * b->h * 3 * sizeof(double));
        for (uint32_t y = 0; y < b->h; y++)
            for (uint32_t x = 0; x < b->w; x++)
                for (int k = 0; k < 3; k++) {
                    double sum = 0;
                    for (uint32_t dy = 0; dy < 2; dy++)
                        for (uint32_t dx = 0; dx < 2; dx++) {
                            uint32_t xx = 2 * x + dx < a->w ? 2 * x + dx : a->w - 1;
                            uint32_t yy = 2 * y + dy < a->h ? 2 * y + dy : a->h - 1;
                            sum += a->rgb[((size_t)yy * a->w + xx) * 3 + k];
                        }
                    b->rgb[((size_t)y * b->w + x) * 3 + k] = sum / 4;
                }
        s.levels++;
    }
    /* camera: look-at (y up) and perspective, as a vt-view camera line means */
    double f[3] = {cam[3] - cam[0], cam[4] - cam[1], cam[5] - cam[2]}, up[3] = {0, 1, 0};
    norm3(f);
    double sd[3] = {f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2],
                    f[0] * up[1] - f[1] * up[0]};
    norm3(sd);
    double u[3] = {sd[1] * f[2] - sd[2] * f[1], sd[2] * f[0] - sd[0] * f[2],
                   sd[0] * f[1] - sd[1] * f[0]};
    double view[16] = {sd[0],
                       u[0],
                       -f[0],
                       0,
                       sd[1],
                       u[1],
                       -f[1],
                       0,
                       sd[2],
                       u[2],
                       -f[2],
                       0,
                       -(sd[0] * cam[0] + sd[1] * cam[1] + sd[2] * cam[2]),
                       -(u[0] * cam[0] + u[1] * cam[1] + u[2] * cam[2]),
                       f[0] * cam[0] + f[1] * cam[1] + f[2] * cam[2],
                       1};
    double tf = 1.0 / tan(cam[6] * PI / 360.0), asp = (double)W / H, zn = 1.0, zf = 1e5;
    double proj[16] = {tf / asp,
                       0,
                       0,
                       0,
                       0,
                       tf,
                       0,
                       0,
                       0,
                       0,
                       (zf + zn) / (zn - zf),
                       -1,
                       0,
                       0,
                       2 * zf * zn / (zn - zf),
                       0};
    double mvp[16];
    mul4(proj, view, mvp);
    double L[3] = {0.3, 0.8, 0.5};
    norm3(L);
    /* rasterise */
    double *zbuf = malloc((size_t)W * H * sizeof(double));
    uint8_t *img = malloc((size_t)W * H * 3);
    for (size_t i = 0; i < (size_t)W * H; i++) {
        zbuf[i] = INFINITY;
        img[i * 3] = img[i * 3 + 1] = img[i * 3 + 2] = 26;
    }
    for (uint32_t j = 0; j + 1 < G; j++)
        for (uint32_t i = 0; i + 1 < G; i++) {
            const uint32_t tri[2][3][2] = {{{i, j}, {i, j + 1}, {i + 1, j}},
                                           {{i + 1, j}, {i, j + 1}, {i + 1, j + 1}}};
            for (int t = 0; t < 2; t++) {
                double sxy[3][2], iw[3], zz[3], uv[3][2], nn[3][3];
                int ok = 1;
                for (int k = 0; k < 3; k++) {
                    size_t at = (size_t)tri[t][k][1] * G + tri[t][k][0];
                    const double *P = s.p + at * 3;
                    double clip[4];
                    for (int r = 0; r < 4; r++)
                        clip[r] =
                            mvp[r] * P[0] + mvp[4 + r] * P[1] + mvp[8 + r] * P[2] + mvp[12 + r];
                    if (clip[3] <= 1e-6)
                        ok = 0;
                    iw[k] = 1.0 / clip[3];
                    sxy[k][0] = (clip[0] * iw[k] + 1) * 0.5 * W;
                    sxy[k][1] = (1 - clip[1] * iw[k]) * 0.5 * H;
                    zz[k] = clip[2] * iw[k];
                    uv[k][0] = (double)tri[t][k][0] / (G - 1);
                    uv[k][1] = (double)tri[t][k][1] / (G - 1);
                    memcpy(nn[k], s.n + at * 3, sizeof(nn[k]));
                }
                if (!ok)
                    continue;
                double area = (sxy[1][0] - sxy[0][0]) * (sxy[2][1] - sxy[0][1]) -
                              (sxy[2][0] - sxy[0][0]) * (sxy[1][1] - sxy[0][1]);
                if (fabs(area) < 1e-12)
                    continue;
                int x0 = (int)floor(fmin(fmin(sxy[0][0], sxy[1][0]), sxy[2][0]));
                int x1 = (int)ceil(fmax(fmax(sxy[0][0], sxy[1][0]), sxy[2][0]));
                int y0 = (int)floor(fmin(fmin(sxy[0][1], sxy[1][1]), sxy[2][1]));
                int y1 = (int)ceil(fmax(fmax(sxy[0][1], sxy[1][1]), sxy[2][1]));
                x0 = x0 < 0 ? 0 : x0;
                y0 = y0 < 0 ? 0 : y0;
                x1 = x1 > (int)W - 1 ? (int)W - 1 : x1;
                y1 = y1 > (int)H - 1 ? (int)H - 1 : y1;
                for (int py = y0; py <= y1; py++)
                    for (int px = x0; px <= x1; px++) {
                        /* barycentrics at the centre and one pixel right and down */
                        double bc[3][3];
                        for (int d = 0; d < 3; d++) {
                            double qx = px + 0.5 + (d == 1), qy = py + 0.5 + (d == 2);
                            for (int k = 0; k < 3; k++) {
                                const double *a = sxy[(k + 1) % 3], *b = sxy[(k + 2) % 3];
                                bc[d][k] =
                                    ((b[0] - a[0]) * (qy - a[1]) - (b[1] - a[1]) * (qx - a[0])) /
                                    area;
                            }
                        }
                        if (bc[0][0] < 0 || bc[0][1] < 0 || bc[0][2] < 0)
                            continue;
                        double z = bc[0][0] * zz[0] + bc[0][1] * zz[1] + bc[0][2] * zz[2];
                        size_t at = (size_t)py * W + px;
                        if (z >= zbuf[at])
                            continue;
                        zbuf[at] = z;
                        double tuv[3][2], nrm[3] = {0, 0, 0};
                        for (int d = 0; d < 3; d++) {
                            double wsum = 0, su = 0, sv = 0;
                            for (int k = 0; k < 3; k++) {
                                double wk = bc[d][k] * iw[k];
                                wsum += wk;
                                su += wk * uv[k][0];
                                sv += wk * uv[k][1];
                                if (d == 0)
                                    for (int m = 0; m < 3; m++)
                                        nrm[m] += wk * nn[k][m];
                            }
                            tuv[d][0] = su / wsum * s.cw;
                            tuv[d][1] = sv / wsum * s.ch;
                        }
                        norm3(nrm);
                        if (area > 0) /* clockwise on screen (y up): a back face, lit from its
                                         side as GL's !gl_FrontFacing */
                            for (int m = 0; m < 3; m++)
                                nrm[m] = -nrm[m];
                        double gx2 = pow(tuv[1][0] - tuv[0][0], 2) + pow(tuv[1][1] - tuv[0][1], 2);
                        double gy2 = pow(tuv[2][0] - tuv[0][0], 2) + pow(tuv[2][1] - tuv[0][1], 2);
                        double lam = 0.5 * log2(fmax(fmax(gx2, gy2), 1e-20));
                        int lvl = lam <= 0.5 ? 0 : (int)ceil(lam + 0.5) - 1;
                        lvl = lvl > (int)s.levels - 1 ? (int)s.levels - 1 : lvl;
                        double col[3];
                        tex(&s, (uint32_t)lvl, tuv[0][0] + s.shift, tuv[0][1], col);
                        double ndl = fmax(nrm[0] * L[0] + nrm[1] * L[1] + nrm[2] * L[2], 0.0);
                        for (int k = 0; k < 3; k++)
                            img[at * 3 + k] = (uint8_t)lround(
                                linear_to_srgb(col[k] * (0.15 + 0.85 * ndl)) * 255.0);
                    }
            }
        }
    struct vts_error err = {0};
    struct vt_png_file_writer *pw = vt_png_file_writer_create(out, W, H, 3, 8, &err);
    int rc = pw ? vt_png_file_writer_rows(pw, img, H, (size_t)W * 3, &err) : -1;
    if (rc == 0)
        rc = vt_png_file_writer_finish(pw, &err);
    vt_png_file_writer_destroy(pw);
    if (rc != 0)
        fprintf(stderr, "render: %s\n", err.message);
    for (uint32_t l = 0; l < s.levels; l++)
        free(s.mip[l].rgb);
    free(s.p);
    free(s.n);
    free(hgt);
    free(zbuf);
    free(img);
    vt_image_release(&e);
    vt_image_release(&c);
    return rc != 0;
}

int main(int argc, char **argv)
{
    int rc = 2;
    if (argc > 1 && strcmp(argv[1], "dem") == 0)
        rc = make_dem(argc, argv);
    else if (argc > 1 && strcmp(argv[1], "render") == 0)
        rc = render(argc, argv);
    if (rc == 2)
        fprintf(stderr, "usage: vtv_terrain_ref dem W H F32.tif U16.tif SCALE OFFSET\n"
                        "       vtv_terrain_ref render ELEV COLOUR.png OUT.png W H G SCALE OFFSET "
                        "NODATA SX SZ EXAG EX EY EZ TX TY TZ FOVY SHIFT X0 Y0 X1 Y1\n");
    return rc;
}
