/* lib/chart under allocation failures: vt_chart_label() and vt_cut() are run with their first,
 * second, ... allocation failing (malloc, calloc, realloc through -Wl,--wrap, see CMakeLists.txt)
 * until one run succeeds. Each failing run must return VTS_ERR_NOMEM with a message and leave the
 * result zeroed (leaks show in the sanitizer build); the successful run must equal an unhindered
 * one. */
#include <stdlib.h>
#include <string.h>

#include "cut_fixture.h"
#include "vt_test.h"

void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t size);
void *__real_realloc(void *p, size_t n);
void *__wrap_malloc(size_t n);
void *__wrap_calloc(size_t n, size_t size);
void *__wrap_realloc(void *p, size_t n);

static long countdown = -1; /* allocations left before the one that fails; < 0: none fails */

static int fails(void)
{
    return countdown >= 0 && countdown-- == 0;
}

void *__wrap_malloc(size_t n)
{
    return fails() ? NULL : __real_malloc(n);
}

void *__wrap_calloc(size_t n, size_t size)
{
    return fails() ? NULL : __real_calloc(n, size);
}

void *__wrap_realloc(void *p, size_t n)
{
    return fails() ? NULL : __real_realloc(p, n);
}

/* Field by field (the struct has padding). */
static bool vertices_equal(const struct vt_cut_vertex *a, const struct vt_cut_vertex *b, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++)
        if (memcmp(a[i].pos, b[i].pos, sizeof a[i].pos) || memcmp(a[i].w, b[i].w, sizeof a[i].w))
            return false;
    return true;
}

/* A cut with new positions on edges and inside faces, a split neighbour and a seam. */
static void scene(struct tmesh *t)
{
    tmesh_init(t);
    uint32_t p[5] = {tmesh_pos(t, 0, 0, 0), tmesh_pos(t, 8, 0, 0), tmesh_pos(t, 8, 4, 1),
                     tmesh_pos(t, 0, 4, 1), tmesh_pos(t, 4, -3, 0)};
    uint32_t tx[4] = {tmesh_tex(t, 0.5, 0.25), tmesh_tex(t, 6.5, 0.25), tmesh_tex(t, 6.5, 3.75),
                      tmesh_tex(t, 0.5, 3.75)};
    tmesh_face(t, 0, 3, (uint32_t[]){p[0], p[1], p[2]}, (uint32_t[]){tx[0], tx[1], tx[2]}, true);
    tmesh_face(t, 0, 4, (uint32_t[]){p[0], p[2], p[3], p[3]},
               (uint32_t[]){tx[0], tx[2], tx[3], tx[3]}, true);
    tmesh_face(t, 1, 3, (uint32_t[]){p[1], p[0], p[4]}, NULL, false);
    tmesh_shift_charts(t);
}

static void label_fails_cleanly_at_every_allocation(void)
{
    struct tmesh t;
    scene(&t);
    struct vt_chart_mesh m = tmesh_view(&t);
    uint32_t chart[3], count;
    int failures = 0;
    for (long k = 0;; k++) {
        struct vts_error err = {0};
        countdown = k;
        int rc = vt_chart_label(&m, chart, &count, &err);
        countdown = -1;
        if (rc == 0)
            break;
        failures++;
        VT_CHECK_INT_EQ(rc, VTS_ERR_NOMEM);
        VT_CHECK_INT_EQ(err.status, VTS_ERR_NOMEM);
        VT_CHECK_STR_CONTAINS(err.message, "out of memory");
        VT_CHECK_INT_EQ(count, 0);
    }
    VT_CHECK(failures >= 3);
    VT_CHECK_INT_EQ(count, 1);
    tmesh_release(&t);
}

static void cut_fails_cleanly_at_every_allocation(void)
{
    struct tmesh t;
    scene(&t);
    struct vt_chart_mesh m = tmesh_view(&t);
    struct vt_cut_result want, r;
    VT_CHECK_INT_EQ(vt_cut(&m, t.wrap, t.shift, &want, NULL), 0);
    int failures = 0;
    for (long k = 0;; k++) {
        struct vts_error err = {0};
        countdown = k;
        int rc = vt_cut(&m, t.wrap, t.shift, &r, &err);
        countdown = -1;
        if (rc == 0)
            break;
        failures++;
        VT_CHECK_INT_EQ(rc, VTS_ERR_NOMEM);
        VT_CHECK_STR_CONTAINS(err.message, "out of memory");
        VT_CHECK(!r.changed && !r.face_shift && !r.face_poly && !r.poly_start && !r.corners &&
                 !r.vertices && r.poly_count == 0 && r.corner_count == 0 && r.vertex_count == 0);
        vt_cut_release(&r);
    }
    VT_CHECK(failures >= 10);
    VT_CHECK(r.poly_count == want.poly_count && r.corner_count == want.corner_count &&
             r.vertex_count == want.vertex_count && r.pieces == want.pieces);
    VT_CHECK(vertices_equal(r.vertices, want.vertices, want.vertex_count));
    VT_CHECK_INT_EQ(cut_fixture_check_watertight(&t, &r, false, true), 0);
    vt_cut_release(&r);
    vt_cut_release(&want);
    tmesh_release(&t);
}

int main(void)
{
    VT_RUN(label_fails_cleanly_at_every_allocation);
    VT_RUN(cut_fails_cleanly_at_every_allocation);
    return vt_test_main_result();
}
