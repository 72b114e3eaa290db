/* vt-view cameras and camera files. */
#include "vtv_camera.h"
#include "vt_error.h"

#define VTV_PI 3.14159265358979323846

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int vtv_camera_path_read(struct vtv_camera_path *p, const char *path, unsigned values,
                         struct vts_error *err)
{
    memset(p, 0, sizeof(*p));
    FILE *f = fopen(path, "r");
    if (!f)
        return vt_error_set(err, VTS_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
    char line[512];
    unsigned lineno = 0;
    int st = 0;
    size_t cap = 0;
    while (fgets(line, sizeof(line), f)) {
        lineno++;
        char *hash = strchr(line, '#');
        if (hash)
            *hash = '\0';
        struct vtv_camera c = {{0}};
        char *s = line, *end;
        unsigned n = 0;
        while (n < values) {
            double d = strtod(s, &end);
            if (end == s || !isfinite(d))
                break;
            c.v[n++] = d;
            s = end;
        }
        while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n')
            s++;
        if (n == 0 && *s == '\0')
            continue;
        if (n != values || *s != '\0') {
            st = vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s' line %u: expected %u numbers", path,
                              lineno, values);
            break;
        }
        if (values == 3 && !(c.v[2] > 0)) {
            st = vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s' line %u: zoom must be > 0", path,
                              lineno);
            break;
        }
        if (p->count == cap) {
            cap = cap ? cap * 2 : 16;
            struct vtv_camera *nf = realloc(p->frames, cap * sizeof(*nf));
            if (!nf) {
                st = vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
                break;
            }
            p->frames = nf;
        }
        p->frames[p->count++] = c;
    }
    fclose(f);
    if (st == 0 && p->count == 0)
        st = vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': no camera in the file", path);
    if (st != 0)
        vtv_camera_path_free(p);
    return st;
}

void vtv_camera_path_free(struct vtv_camera_path *p)
{
    free(p->frames);
    memset(p, 0, sizeof(*p));
}

const struct vtv_camera *vtv_camera_path_at(const struct vtv_camera_path *p, uint64_t frame)
{
    return &p->frames[frame < p->count ? frame : p->count - 1];
}

void vtv_camera_matrix_2d(const struct vtv_camera *c, uint32_t w, uint32_t h, float out[16])
{
    double sx = 2.0 * c->v[2] / w, sy = -2.0 * c->v[2] / h;
    memset(out, 0, 16 * sizeof(float));
    out[0] = (float)sx;
    out[5] = (float)sy;
    out[10] = 1.0f;
    out[12] = (float)(-c->v[0] * sx);
    out[13] = (float)(-c->v[1] * sy);
    out[15] = 1.0f;
}

static void normalize(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0)
        for (int i = 0; i < 3; i++)
            v[i] /= l;
}

static void cross(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

void vtv_camera_matrix_3d(const struct vtv_camera *c, uint32_t w, uint32_t h, double near_z,
                          double far_z, float out[16])
{
    const double *eye = c->v, *tgt = c->v + 3;
    double f[3] = {tgt[0] - eye[0], tgt[1] - eye[1], tgt[2] - eye[2]};
    normalize(f);
    double up[3] = {0, 1, 0};
    if (fabs(f[1]) > 0.999) {
        up[1] = 0;
        up[2] = 1;
    }
    double s[3], u[3];
    cross(f, up, s);
    normalize(s);
    cross(s, f, u);
    double view[16] = {s[0],
                       u[0],
                       -f[0],
                       0,
                       s[1],
                       u[1],
                       -f[1],
                       0,
                       s[2],
                       u[2],
                       -f[2],
                       0,
                       -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]),
                       -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]),
                       f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2],
                       1};
    double t = 1.0 / tan(c->v[6] * VTV_PI / 360.0), a = (double)w / h;
    double proj[16] = {t / a,
                       0,
                       0,
                       0,
                       0,
                       t,
                       0,
                       0,
                       0,
                       0,
                       (far_z + near_z) / (near_z - far_z),
                       -1,
                       0,
                       0,
                       2 * far_z * near_z / (near_z - far_z),
                       0};
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) {
            double sum = 0;
            for (int k = 0; k < 4; k++)
                sum += proj[k * 4 + row] * view[col * 4 + k];
            out[col * 4 + row] = (float)sum;
        }
}

void vtv_camera_orbit(const double lo[3], const double hi[3], uint64_t i, uint64_t n,
                      struct vtv_camera *out)
{
    double ctr[3], r = 0;
    for (int k = 0; k < 3; k++) {
        ctr[k] = 0.5 * (lo[k] + hi[k]);
        r += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    r = 0.5 * sqrt(r);
    if (r <= 0)
        r = 1;
    double a = 2 * VTV_PI * (double)i / (double)(n ? n : 1);
    double d = r / sin(30.0 * VTV_PI / 180.0) * 1.1;
    out->v[0] = ctr[0] + d * cos(a) * 0.9;
    out->v[1] = ctr[1] + d * 0.4;
    out->v[2] = ctr[2] + d * sin(a) * 0.9;
    memcpy(out->v + 3, ctr, sizeof(ctr));
    out->v[6] = 60.0;
}
