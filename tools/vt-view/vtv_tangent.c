/* vt-view tangent frames from UV derivatives (vtv_tangent.h). */
#include "vtv_tangent.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vts.h"

struct corner_key {
    uint32_t v, vt, vn, vertex;
};

static int cmp_key(const void *a, const void *b)
{
    const struct corner_key *x = a, *y = b;
    if (x->v != y->v)
        return x->v < y->v ? -1 : 1;
    if (x->vt != y->vt)
        return x->vt < y->vt ? -1 : 1;
    if (x->vn != y->vn)
        return x->vn < y->vn ? -1 : 1;
    return x->vertex < y->vertex ? -1 : x->vertex > y->vertex;
}

static void sub3(const float *a, const float *b, double *out)
{
    for (int k = 0; k < 3; k++)
        out[k] = (double)a[k] - b[k];
}

static double norm3(double *v)
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0)
        for (int k = 0; k < 3; k++)
            v[k] /= l;
    return l;
}

/* Triangle t's normal into missing vertex normals, and its normalised T and B into tb (6 doubles
 * per vertex; zero for UVs without area). */
static void triangle_frame(float *vtx, size_t t, double *tb)
{
    float *p[3];
    for (int j = 0; j < 3; j++)
        p[j] = vtx + (t * 3 + j) * VTV_VERTEX_FLOATS;
    double e1[3], e2[3], n[3];
    sub3(p[1], p[0], e1);
    sub3(p[2], p[0], e2);
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    norm3(n);
    for (int j = 0; j < 3; j++)
        if (p[j][5] == 0.0f && p[j][6] == 0.0f && p[j][7] == 0.0f)
            for (int k = 0; k < 3; k++)
                p[j][5 + k] = (float)n[k];
    /* v up as in the OBJ: the drawn v is 1 - v */
    double du1 = (double)p[1][3] - p[0][3], dv1 = -((double)p[1][4] - p[0][4]);
    double du2 = (double)p[2][3] - p[0][3], dv2 = -((double)p[2][4] - p[0][4]);
    double det = du1 * dv2 - du2 * dv1;
    double tt[3] = {0, 0, 0}, bb[3] = {0, 0, 0};
    if (fabs(det) > 1e-30) {
        for (int k = 0; k < 3; k++) {
            tt[k] = (e1[k] * dv2 - e2[k] * dv1) / det;
            bb[k] = (e2[k] * du1 - e1[k] * du2) / det;
        }
        norm3(tt);
        norm3(bb);
    }
    for (int j = 0; j < 3; j++) {
        memcpy(tb + (t * 3 + j) * 6, tt, sizeof(tt));
        memcpy(tb + (t * 3 + j) * 6 + 3, bb, sizeof(bb));
    }
}

/* The vertex's final tangent from the summed T and B: Gram-Schmidt against its normal, sign. */
static void finish(float *v, const double *t_sum, const double *b_sum)
{
    double n[3] = {v[5], v[6], v[7]}, t[3];
    norm3(n);
    double d = n[0] * t_sum[0] + n[1] * t_sum[1] + n[2] * t_sum[2];
    for (int k = 0; k < 3; k++)
        t[k] = t_sum[k] - n[k] * d;
    if (norm3(t) < 1e-12) { /* no UV direction: any tangent perpendicular to n */
        double a[3] = {fabs(n[0]) < 0.9 ? 1.0 : 0.0, fabs(n[0]) < 0.9 ? 0.0 : 1.0, 0.0};
        d = n[0] * a[0] + n[1] * a[1];
        for (int k = 0; k < 3; k++)
            t[k] = a[k] - n[k] * d;
        norm3(t);
    }
    double c[3] = {n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0]};
    double w = c[0] * b_sum[0] + c[1] * b_sum[1] + c[2] * b_sum[2] < 0 ? -1.0 : 1.0;
    for (int k = 0; k < 3; k++)
        v[8 + k] = (float)t[k];
    v[11] = (float)w;
}

int vtv_tangents(float *vertices, const uint32_t *keys, size_t n)
{
    if (n == 0)
        return 0;
    double *tb = malloc(n * 6 * sizeof(double));
    struct corner_key *ck = malloc(n * sizeof(*ck));
    if (!tb || !ck) {
        free(tb);
        free(ck);
        return VTS_ERR_NOMEM;
    }
    for (size_t t = 0; t < n / 3; t++)
        triangle_frame(vertices, t, tb);
    for (size_t i = 0; i < n; i++)
        ck[i] = (struct corner_key){keys[i * 3], keys[i * 3 + 1], keys[i * 3 + 2], (uint32_t)i};
    qsort(ck, n, sizeof(*ck), cmp_key);
    for (size_t i = 0; i < n;) {
        size_t j = i;
        double sum[6] = {0, 0, 0, 0, 0, 0};
        for (; j < n && ck[j].v == ck[i].v && ck[j].vt == ck[i].vt && ck[j].vn == ck[i].vn; j++)
            for (int k = 0; k < 6; k++)
                sum[k] += tb[(size_t)ck[j].vertex * 6 + k];
        for (size_t g = i; g < j; g++)
            finish(vertices + (size_t)ck[g].vertex * VTV_VERTEX_FLOATS, sum, sum + 3);
        i = j;
    }
    free(tb);
    free(ck);
    return 0;
}
