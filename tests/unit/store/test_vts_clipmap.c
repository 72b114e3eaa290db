/* include/vts/vts_clipmap.h against a brute-force model written here (sets of tiles, integer
 * arithmetic on quarter-tile centres), exhaustively for small stores: every geometry of a set
 * (levels of 1..40 tiles, partial last tiles, non-square, one-level stores, C = 3, 4, 5, 8) with
 * n = 1..6. Windows against the snapping formula for every quarter-tile centre and random
 * sub-tile offsets; strips for every pair of windows (a tile set equality, the documented order);
 * random walks of the centres with budgets of k = 1..7 tiles per step, moves before the previous
 * one completed and jumps with no overlap: every plan is exactly the target's tiles not in their
 * slot, in order, the front is always a rectangle of loaded tiles, every walk converges in
 * ceil(pending / k) steps. Each checker is also run on a corrupted input to show it fails. */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>

#include "vt_test.h"
#include "vts_clipmap.h"

static const struct {
    uint32_t width, height, content_px, levels; /* levels 0: the full pyramid */
} geometries[] = {
    {1, 1, 4, 0},     /* one texel: one level of one partial tile */
    {16, 16, 4, 0},   /* 4x4 tiles */
    {160, 160, 4, 0}, /* 40x40 tiles down to 1 */
    {157, 93, 4, 0},  /* 40x24, partial last tiles, non-square */
    {37, 150, 4, 3},  /* 10x38, three levels only */
    {64, 8, 8, 1},    /* 8x1 tiles, one level */
    {300, 20, 8, 0},  /* 38x3, partial */
    {23, 23, 5, 0},   /* 5x5, C = 5, partial */
    {97, 41, 3, 0},   /* 33x14, C = 3 */
    {40, 120, 8, 1},  /* 5x15, one level */
};
#define GEOMETRY_COUNT (sizeof geometries / sizeof geometries[0])
#define MAX_N          6u

static struct vts_geometry geometry_of(size_t i)
{
    struct vts_geometry g = {geometries[i].width,
                             geometries[i].height,
                             geometries[i].content_px,
                             0,
                             geometries[i].content_px,
                             geometries[i].levels,
                             1,
                             0};
    if (!g.level_count)
        g.level_count = vts_full_level_count(g.width, g.height, g.tile_content_px);
    return g;
}

static uint64_t rng_state = 0x9e3779b97f4a7c15ull;

static uint32_t rnd(uint32_t bound)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (uint32_t)((rng_state >> 16) % bound);
}

static int64_t floor_div(int64_t a, int64_t b)
{
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

static bool rect_empty(const struct vts_tile_rect *r)
{
    return r->x0 >= r->x1 || r->y0 >= r->y1;
}

static bool rect_eq(const struct vts_tile_rect *a, const struct vts_tile_rect *b)
{
    return a->x0 == b->x0 && a->y0 == b->y0 && a->x1 == b->x1 && a->y1 == b->y1;
}

static bool rect_has(const struct vts_tile_rect *r, uint32_t x, uint32_t y)
{
    return x >= r->x0 && x < r->x1 && y >= r->y0 && y < r->y1;
}

/* ---- the model: windows from quarter-tile centres, slots as plain arrays ---- */

/* First tile of the window on one axis for a centre of q quarter tiles: n odd, the tile under the
 * centre is the middle one; n even, the tile corner nearest the centre (halves up) is the middle.
 */
typedef uint32_t (*start_fn)(int64_t q, uint32_t n, uint32_t tiles);

static uint32_t model_start(int64_t q, uint32_t n, uint32_t tiles)
{
    if (tiles <= n)
        return 0;
    int64_t s = n % 2 ? floor_div(q, 4) - (n - 1) / 2 : floor_div(q + 2, 4) - n / 2;
    return s < 0 ? 0 : s > tiles - n ? tiles - n : (uint32_t)s;
}

/* A wrong model (the negative control): the centre not rounded to the nearest corner for n even. */
static uint32_t unrounded_start(int64_t q, uint32_t n, uint32_t tiles)
{
    if (tiles <= n)
        return 0;
    int64_t s = floor_div(q, 4) - n / 2;
    return s < 0 ? 0 : s > tiles - n ? tiles - n : (uint32_t)s;
}

static struct vts_tile_rect model_window(start_fn start, int64_t qx, int64_t qy, uint32_t n,
                                         uint32_t tiles_x, uint32_t tiles_y)
{
    struct vts_tile_rect r;
    r.x0 = start(qx, n, tiles_x);
    r.y0 = start(qy, n, tiles_y);
    r.x1 = r.x0 + n < tiles_x ? r.x0 + n : tiles_x;
    r.y1 = r.y0 + n < tiles_y ? r.y0 + n : tiles_y;
    return r;
}

/* Mismatches between the library's windows and a model's over every quarter-tile centre from two
 * tiles before the level to two after it (with a random sub-quarter offset each). */
static unsigned check_windows(const struct vts_clipmap *c, uint32_t level, start_fn start)
{
    const struct vts_clipmap_level *cl = &c->levels[level];
    unsigned bad = 0;
    int64_t qmax = 4 * (int64_t)cl->tiles_x + 8;
    for (int64_t qx = -8; qx <= qmax; qx++) {
        int64_t qy = (qx * 7) % (4 * (int64_t)cl->tiles_y + 16) - 8;
        struct vts_tile_rect want = model_window(start, qx, qy, c->n, cl->tiles_x, cl->tiles_y);
        double u = rnd(1000) / 1000.0, v = rnd(1000) / 1000.0;
        double cx = (qx + u) * c->content_px / 4.0, cy = (qy + v) * c->content_px / 4.0;
        struct vts_tile_rect got, at_quarter;
        bad += vts_clipmap_window(c, level, cx, cy, &got) != 0;
        bad += vts_clipmap_window(c, level, qx * c->content_px / 4.0, qy * c->content_px / 4.0,
                                  &at_quarter) != 0;
        bad += !rect_eq(&got, &want) || !rect_eq(&at_quarter, &want);
    }
    return bad;
}

/* Windows constant over a snapping cell (a move of less than the snapping step changes none):
 * cells are [4k, 4k + 4) quarter tiles for n odd, [4k - 2, 4k + 2) for n even; and a move from a
 * cell to the next changes the window unless it is clamped. Returns the violations. */
static unsigned check_snapping(const struct vts_clipmap *c, uint32_t level)
{
    const struct vts_clipmap_level *cl = &c->levels[level];
    double C = c->content_px;
    unsigned bad = 0;
    for (int64_t k = -1; k <= (int64_t)cl->tiles_x + 1; k++) {
        double cell = (c->n % 2 ? 4.0 * k : 4.0 * k - 2) * C / 4.0, y = cl->height / 2.0;
        struct vts_tile_rect first, w;
        vts_clipmap_window(c, level, cell, y, &first);
        for (int i = 0; i < 8; i++) {
            double offset = i == 7 ? C * (1 - 1e-9) : rnd(1000) / 1000.0 * C;
            vts_clipmap_window(c, level, cell + offset, y, &w);
            bad += !rect_eq(&w, &first);
        }
        vts_clipmap_window(c, level, cell + C, y, &w);
        bool clamped = cl->tiles_x <= c->n || first.x0 == 0 || first.x0 == cl->tiles_x - c->n;
        bad += !clamped && w.x0 != first.x0 + 1;
    }
    return bad;
}

/* Strips of `to` minus `from` against the tile sets: each tile of to \ from in exactly one strip,
 * no other tile in any; no empty strip; the documented order: column strips over the rows shared
 * with `from` (left, then right) before whole-width row strips (above, then below), so that the
 * front grows as a rectangle after every strip. Returns the violations. */
static unsigned check_strips(const struct vts_tile_rect *from, const struct vts_tile_rect *to,
                             const struct vts_tile_rect *strips, uint32_t count, uint32_t tiles_x,
                             uint32_t tiles_y)
{
    unsigned bad = count > 4;
    if (count > 4)
        return bad;
    /* a strip reaching outside `to` is wrong; inside it, count the strips over each tile */
    unsigned char hits[MAX_N * MAX_N] = {0};
    uint32_t tw = to->x1 - to->x0, th = to->y1 - to->y0;
    if (rect_empty(to))
        return bad + (count != 0);
    if (tw > MAX_N || th > MAX_N)
        return bad + 1;
    for (uint32_t s = 0; s < count; s++) {
        const struct vts_tile_rect *r = &strips[s];
        bad += rect_empty(r) || r->x1 > tiles_x || r->y1 > tiles_y;
        bad += r->x0 < to->x0 || r->y0 < to->y0 || r->x1 > to->x1 || r->y1 > to->y1;
        for (uint32_t y = r->y0; y < r->y1; y++)
            for (uint32_t x = r->x0; x < r->x1; x++)
                if (rect_has(to, x, y))
                    hits[(y - to->y0) * tw + x - to->x0]++;
    }
    for (uint32_t y = to->y0; y < to->y1; y++)
        for (uint32_t x = to->x0; x < to->x1; x++)
            bad += hits[(y - to->y0) * tw + x - to->x0] != (rect_has(from, x, y) ? 0 : 1);
    /* the order: the loaded part stays a rectangle; columns (to's rows not all spanned) first */
    struct vts_tile_rect in = {
        from->x0 > to->x0 ? from->x0 : to->x0, from->y0 > to->y0 ? from->y0 : to->y0,
        from->x1 < to->x1 ? from->x1 : to->x1, from->y1 < to->y1 ? from->y1 : to->y1};
    if (rect_empty(from) || rect_empty(&in))
        return bad + (count != (rect_empty(to) ? 0u : 1u)) +
               (count == 1 && !rect_eq(&strips[0], to));
    struct vts_tile_rect f = in;
    bool rows_started = false;
    for (uint32_t s = 0; s < count; s++) {
        const struct vts_tile_rect *r = &strips[s];
        bool column = r->y0 == in.y0 && r->y1 == in.y1 && (r->x1 == f.x0 || r->x0 == f.x1);
        bool row = r->x0 == to->x0 && r->x1 == to->x1 && (r->y1 == f.y0 || r->y0 == f.y1);
        bad += !(column && !rows_started) && !row;
        rows_started |= row && !column;
        /* grow f by r: it must stay a rectangle */
        if (r->x1 == f.x0 && r->y0 == f.y0 && r->y1 == f.y1)
            f.x0 = r->x0;
        else if (r->x0 == f.x1 && r->y0 == f.y0 && r->y1 == f.y1)
            f.x1 = r->x1;
        else if (r->y1 == f.y0 && r->x0 == f.x0 && r->x1 == f.x1)
            f.y0 = r->y0;
        else if (r->y0 == f.y1 && r->x0 == f.x0 && r->x1 == f.x1)
            f.y1 = r->y1;
        else
            bad++;
        /* left before right, above before below */
        if (s > 0) {
            const struct vts_tile_rect *p = &strips[s - 1];
            bad += p->y0 == r->y0 && p->y1 == r->y1 && p->x0 > r->x0;
            bad += p->x0 == r->x0 && p->x1 == r->x1 && p->y0 > r->y0;
        }
    }
    return bad + !rect_eq(&f, to);
}

/* The model's state of one clipmap: per level the target and what each slot holds. */
struct model {
    uint32_t n, level_count;
    uint32_t tiles_x[VTS_MAX_LEVELS], tiles_y[VTS_MAX_LEVELS];
    struct vts_tile_rect target[VTS_MAX_LEVELS];
    int64_t slot[VTS_MAX_LEVELS][MAX_N * MAX_N]; /* tile id (y * tiles_x + x) or -1 */
};

static bool model_in_slot(const struct model *m, uint32_t l, uint32_t x, uint32_t y)
{
    return m->slot[l][(y % m->n) * m->n + x % m->n] == (int64_t)y * m->tiles_x[l] + x;
}

static uint64_t model_pending(const struct model *m)
{
    uint64_t count = 0;
    for (uint32_t l = 0; l < m->level_count; l++)
        for (uint32_t y = m->target[l].y0; y < m->target[l].y1; y++)
            for (uint32_t x = m->target[l].x0; x < m->target[l].x1; x++)
                count += !model_in_slot(m, l, x, y);
    return count;
}

/* A plan against the model: exactly the target tiles not in their slot (no duplicate, none
 * missing, none extra), right slots, coarsest level first, within a level by strip of the
 * library's front and back (vts_clipmap_strips, checked above) then row by row. Returns the
 * violations. */
static unsigned check_plan(const struct vts_clipmap *c, const struct model *m,
                           const struct vts_clipmap_tile *plan, uint32_t count)
{
    unsigned bad = 0;
    unsigned char *seen[VTS_MAX_LEVELS] = {0};
    for (uint32_t l = 0; l < m->level_count; l++)
        seen[l] = calloc((size_t)m->tiles_x[l] * m->tiles_y[l], 1);
    uint64_t prev_key = 0;
    uint32_t prev_level = UINT32_MAX;
    for (uint32_t i = 0; i < count; i++) {
        const struct vts_clipmap_tile *t = &plan[i];
        if (t->level >= m->level_count || !rect_has(&m->target[t->level], t->x, t->y)) {
            bad++;
            continue;
        }
        bad += model_in_slot(m, t->level, t->x, t->y);
        bad += seen[t->level][(size_t)t->y * m->tiles_x[t->level] + t->x]++ != 0;
        bad += t->slot_x != t->x % m->n || t->slot_y != t->y % m->n;
        struct vts_tile_rect strips[4];
        const struct vts_clipmap_level *cl = &c->levels[t->level];
        uint32_t ns = vts_clipmap_strips(&cl->front, &cl->back, strips), s = 0;
        while (s < ns && !rect_has(&strips[s], t->x, t->y))
            s++;
        bad += s == ns;
        uint64_t key = ((uint64_t)s << 40) | ((uint64_t)t->y << 20) | t->x;
        if (t->level == prev_level)
            bad += key <= prev_key;
        else
            bad += prev_level != UINT32_MAX && t->level > prev_level;
        prev_level = t->level;
        prev_key = key;
    }
    for (uint32_t l = 0; l < m->level_count; l++)
        free(seen[l]);
    return bad + (count != model_pending(m));
}

/* The library's state against the model's: targets, slots; every front a rectangle within the
 * target of tiles in their slots; complete == (front == target); valid texels = the front's,
 * clipped to the level, inset where the front ends inside the level. Returns the violations. */
static unsigned check_state(const struct vts_clipmap *c, const struct model *m)
{
    unsigned bad = 0;
    for (uint32_t l = 0; l < m->level_count; l++) {
        const struct vts_clipmap_level *cl = &c->levels[l];
        bad += !rect_eq(&cl->back, &m->target[l]);
        for (uint32_t s = 0; s < m->n * m->n; s++)
            bad += cl->slot_tile[s] != (m->slot[l][s] < 0 ? UINT64_MAX : (uint64_t)m->slot[l][s]);
        const struct vts_tile_rect *f = &cl->front;
        bool empty = rect_empty(f);
        bad += !empty && (f->x0 < cl->back.x0 || f->x1 > cl->back.x1 || f->y0 < cl->back.y0 ||
                          f->y1 > cl->back.y1);
        for (uint32_t y = f->y0; !empty && y < f->y1; y++)
            for (uint32_t x = f->x0; x < f->x1; x++)
                bad += !model_in_slot(m, l, x, y);
        bool target_empty = rect_empty(&m->target[l]);
        bad += vts_clipmap_complete(c, l) != (!target_empty && rect_eq(f, &m->target[l]));
        double C = c->content_px, inset = (double)(l % 3) / 2, x0, y0, x1, y1;
        vts_clipmap_valid(c, l, inset, &x0, &y0, &x1, &y1);
        if (empty) {
            bad += !(x0 >= x1);
            continue;
        }
        double wx0 = f->x0 * C + (f->x0 > 0 ? inset : 0);
        double wy0 = f->y0 * C + (f->y0 > 0 ? inset : 0);
        double wx1 = f->x1 * C >= cl->width ? cl->width : f->x1 * C - inset;
        double wy1 = f->y1 * C >= cl->height ? cl->height : f->y1 * C - inset;
        if (wx0 >= wx1 || wy0 >= wy1)
            bad += !(x0 >= x1 || y0 >= y1);
        else
            bad += x0 != wx0 || y0 != wy0 || x1 != wx1 || y1 != wy1;
    }
    return bad;
}

/* ---- tests ---- */

static void windows_follow_the_snapping_formula(void)
{
    unsigned windows = 0;
    for (size_t gi = 0; gi < GEOMETRY_COUNT; gi++)
        for (uint32_t n = 1; n <= MAX_N; n++) {
            struct vts_geometry g = geometry_of(gi);
            struct vts_clipmap c;
            VT_CHECK_INT_EQ(vts_clipmap_init(&c, &g, n, NULL), 0);
            for (uint32_t l = 0; l < c.level_count; l++) {
                VT_CHECK_INT_EQ(check_windows(&c, l, model_start), 0);
                VT_CHECK_INT_EQ(check_snapping(&c, l), 0);
                windows += 4 * c.levels[l].tiles_x + 17;
                /* the negative control: a centre not rounded to the nearest corner is caught
                 * wherever n is even and the level has room to move */
                if (n % 2 == 0 && c.levels[l].tiles_x > n + 1)
                    VT_CHECK(check_windows(&c, l, unrounded_start) > 0);
            }
            vts_clipmap_free(&c);
        }
    fprintf(stderr, "  %u centres checked against the window formula\n", windows);
}

/* Whether level l's window (in level-0 texels, clipped to the store) lies within level l + 1's:
 * where the finer level is loaded, the coarser one it falls back to is too. */
static bool nested(const struct vts_clipmap *c, uint32_t l, const struct vts_tile_rect *fine,
                   const struct vts_tile_rect *coarse)
{
    uint64_t C = c->content_px, w = c->levels[0].width, h = c->levels[0].height;
    uint64_t f[4] = {fine->x0 * C << l, fine->y0 * C << l, fine->x1 * C << l, fine->y1 * C << l};
    uint64_t g[4] = {coarse->x0 * C << (l + 1), coarse->y0 * C << (l + 1),
                     coarse->x1 * C << (l + 1), coarse->y1 * C << (l + 1)};
    f[2] = f[2] < w ? f[2] : w, g[2] = g[2] < w ? g[2] : w;
    f[3] = f[3] < h ? f[3] : h, g[3] = g[3] < h ? g[3] : h;
    return g[0] <= f[0] && g[1] <= f[1] && f[2] <= g[2] && f[3] <= g[3];
}

static void windows_of_one_centre_nest(void)
{
    unsigned pairs = 0, caught = 0;
    for (size_t gi = 0; gi < GEOMETRY_COUNT; gi++)
        for (uint32_t n = 1; n <= MAX_N; n++) {
            struct vts_geometry g = geometry_of(gi);
            struct vts_clipmap c;
            VT_CHECK_INT_EQ(vts_clipmap_init(&c, &g, n, NULL), 0);
            for (int64_t q = -8; q <= 4 * (int64_t)g.width + 8; q++) {
                double cx = q * g.tile_content_px / 4.0 + 0.125;
                double cy = (double)((q * 5) % (4 * (int64_t)g.height + 16) - 8);
                for (uint32_t l = 0; l + 1 < c.level_count; l++) {
                    struct vts_tile_rect fine, coarse;
                    vts_clipmap_window(&c, l, cx / (1u << l), cy / (1u << l), &fine);
                    vts_clipmap_window(&c, l + 1, cx / (2u << l), cy / (2u << l), &coarse);
                    VT_CHECK(nested(&c, l, &fine, &coarse));
                    pairs++;
                    /* the negative control: the coarse level given the fine level's centre
                     * (not halved) */
                    vts_clipmap_window(&c, l + 1, cx / (1u << l), cy / (1u << l), &coarse);
                    caught += !nested(&c, l, &fine, &coarse);
                }
            }
            vts_clipmap_free(&c);
        }
    VT_CHECK(caught > 1000);
    fprintf(stderr, "  %u level pairs nested, %u windows of an unhalved centre caught\n", pairs,
            caught);
}

static void strips_cover_exactly_the_new_tiles_in_order(void)
{
    unsigned pairs = 0, controls = 0;
    for (size_t gi = 0; gi < GEOMETRY_COUNT; gi++)
        for (uint32_t n = 1; n <= MAX_N; n++) {
            struct vts_geometry g = geometry_of(gi);
            struct vts_clipmap c;
            VT_CHECK_INT_EQ(vts_clipmap_init(&c, &g, n, NULL), 0);
            const struct vts_clipmap_level *cl = &c.levels[0];
            /* every window of level 0 (and the empty one) as `from`, every window as `to` */
            uint32_t sx = cl->tiles_x > n ? cl->tiles_x - n + 1 : 1;
            uint32_t sy = cl->tiles_y > n ? cl->tiles_y - n + 1 : 1;
            uint32_t wn = n < cl->tiles_x ? n : cl->tiles_x, hn = n < cl->tiles_y ? n : cl->tiles_y;
            for (uint32_t f = 0; f <= sx * sy; f++)
                for (uint32_t t = 0; t < sx * sy; t++) {
                    struct vts_tile_rect from = {0}, to, out[4];
                    if (f < sx * sy)
                        from = (struct vts_tile_rect){f % sx, f / sx, f % sx + wn, f / sx + hn};
                    to = (struct vts_tile_rect){t % sx, t / sx, t % sx + wn, t / sx + hn};
                    /* every overlapping pair, one in 16 of the others (no overlap: one case) */
                    bool near = from.x0 < to.x1 + 1 && to.x0 < from.x1 + 1 && from.y0 < to.y1 + 1 &&
                                to.y0 < from.y1 + 1;
                    if (!near && f < sx * sy && (f + t) % 16 != 0)
                        continue;
                    uint32_t count = vts_clipmap_strips(&from, &to, out);
                    VT_CHECK_INT_EQ(check_strips(&from, &to, out, count, cl->tiles_x, cl->tiles_y),
                                    0);
                    pairs++;
                    /* negative controls on the first overlapping pair with several strips */
                    if (count >= 2 && pairs % 97 == 0) {
                        struct vts_tile_rect wrong[4];
                        controls++;
                        memcpy(wrong, out, sizeof wrong);
                        wrong[0].x1++; /* one tile too many */
                        VT_CHECK(check_strips(&from, &to, wrong, count, cl->tiles_x, cl->tiles_y) >
                                 0);
                        memcpy(wrong, out, sizeof wrong);
                        wrong[0] = out[count - 1], wrong[count - 1] = out[0]; /* order */
                        VT_CHECK(check_strips(&from, &to, wrong, count, cl->tiles_x, cl->tiles_y) >
                                 0);
                        VT_CHECK(check_strips(&from, &to, out, count - 1, cl->tiles_x,
                                              cl->tiles_y) > 0); /* one missing */
                    }
                }
            vts_clipmap_free(&c);
        }
    VT_CHECK(controls > 10);
    fprintf(stderr, "  %u window pairs checked, %u corrupted strip lists caught\n", pairs,
            controls);
}

struct walk_stats {
    unsigned walks, moves, steps, loads, plans;
};

/* Level l's centre in quarter tiles from level 0's (or its own one, sometimes). */
static int64_t level_centre(int64_t q0, uint32_t l)
{
    return floor_div(q0, (int64_t)1 << l);
}

/* One move of every level's target to the windows of a new centre (a sub-tile step, a short
 * move, or a jump anywhere, also outside the level), checked against the model. */
static void walk_move(struct vts_clipmap *c, struct model *m, int64_t *qx, int64_t *qy)
{
    const struct vts_clipmap_level *l0 = &c->levels[0];
    uint32_t kind = rnd(8);
    if (kind < 3) { /* sub-tile */
        *qx += (int64_t)rnd(7) - 3;
        *qy += (int64_t)rnd(7) - 3;
    } else if (kind < 7) { /* up to two windows' width */
        *qx += (int64_t)rnd(16 * m->n + 1) - 8 * m->n;
        *qy += (int64_t)rnd(16 * m->n + 1) - 8 * m->n;
    } else { /* a jump */
        *qx = (int64_t)rnd(4 * l0->tiles_x + 17) - 8;
        *qy = (int64_t)rnd(4 * l0->tiles_y + 17) - 8;
    }
    bool own = rnd(4) == 0; /* each level its own centre */
    for (uint32_t l = 0; l < m->level_count; l++) {
        int64_t lx = own ? (int64_t)rnd(4 * m->tiles_x[l] + 9) - 4 : level_centre(*qx, l);
        int64_t ly = own ? (int64_t)rnd(4 * m->tiles_y[l] + 9) - 4 : level_centre(*qy, l);
        struct vts_tile_rect w,
            want = model_window(model_start, lx, ly, m->n, m->tiles_x[l], m->tiles_y[l]);
        VT_CHECK_INT_EQ(
            vts_clipmap_window(c, l, lx * c->content_px / 4.0, ly * c->content_px / 4.0, &w), 0);
        VT_CHECK(rect_eq(&w, &want));
        struct vts_tile_rect old_front = c->levels[l].front;
        VT_CHECK_INT_EQ(vts_clipmap_move(c, l, &w), 0);
        m->target[l] = w;
        /* the front keeps what stays (and may grow over tiles already loaded) */
        const struct vts_tile_rect *f = &c->levels[l].front;
        for (uint32_t y = old_front.y0; y < old_front.y1; y++)
            for (uint32_t x = old_front.x0; x < old_front.x1; x++)
                if (rect_has(&w, x, y) && !rect_has(f, x, y))
                    VT_CHECK(!"a tile left the front while it stays in the target");
    }
    VT_CHECK_INT_EQ(check_state(c, m), 0);
}

/* One step with a budget of k tiles: the full plan and the limited one checked, the k tiles
 * loaded. Returns the tiles loaded. */
static uint32_t walk_step(struct vts_clipmap *c, struct model *m, uint32_t k,
                          struct vts_clipmap_tile *plan, uint32_t plan_cap, bool negatives)
{
    uint64_t pending = model_pending(m);
    VT_CHECK_INT_EQ(vts_clipmap_pending(c), pending);
    uint32_t full = vts_clipmap_plan(c, plan, plan_cap);
    VT_CHECK_INT_EQ(check_plan(c, m, plan, full), 0);
    if (negatives && full >= 2) {
        /* one tile too many (a tile already loaded or a duplicate), one missing, two swapped */
        struct vts_clipmap_tile keep = plan[full - 1];
        VT_CHECK(check_plan(c, m, plan, full - 1) > 0);
        plan[full] = plan[0];
        VT_CHECK(check_plan(c, m, plan, full + 1) > 0);
        plan[full - 1] = plan[full - 2], plan[full - 2] = keep;
        VT_CHECK(check_plan(c, m, plan, full) > 0);
        full = vts_clipmap_plan(c, plan, plan_cap);
    }
    struct vts_clipmap_tile step[8];
    uint32_t count = vts_clipmap_plan(c, step, k);
    VT_CHECK_INT_EQ(count, pending < k ? pending : k);
    for (uint32_t i = 0; i < count && i < full; i++)
        VT_CHECK(memcmp(&step[i], &plan[i], sizeof step[i]) == 0);
    for (uint32_t i = 0; i < count; i++) {
        VT_CHECK_INT_EQ(vts_clipmap_loaded(c, &step[i]), 0);
        const struct vts_clipmap_tile *t = &step[i];
        m->slot[t->level][(t->y % m->n) * m->n + t->x % m->n] =
            (int64_t)t->y * m->tiles_x[t->level] + t->x;
        VT_CHECK_INT_EQ(check_state(c, m), 0);
    }
    return count;
}

static void walk(size_t gi, uint32_t n, uint32_t k, uint32_t moves, struct walk_stats *st)
{
    struct vts_geometry g = geometry_of(gi);
    struct vts_clipmap c;
    VT_CHECK_INT_EQ(vts_clipmap_init(&c, &g, n, NULL), 0);
    struct model m = {.n = n, .level_count = c.level_count};
    for (uint32_t l = 0; l < c.level_count; l++) {
        m.tiles_x[l] = c.levels[l].tiles_x;
        m.tiles_y[l] = c.levels[l].tiles_y;
        for (uint32_t s = 0; s < n * n; s++)
            m.slot[l][s] = -1;
    }
    uint32_t plan_cap = c.level_count * n * n + 1;
    struct vts_clipmap_tile *plan = calloc(plan_cap, sizeof *plan);
    int64_t qx = 2 * (int64_t)c.levels[0].width / c.content_px, qy = 0;
    VT_CHECK_INT_EQ(check_state(&c, &m), 0);
    for (uint32_t mv = 0; mv < moves; mv++) {
        walk_move(&c, &m, &qx, &qy);
        st->moves++;
        uint64_t pending = model_pending(&m), steps = 0;
        /* half the moves run to completion, the others stop part way (the next move comes
         * before this one completed) */
        bool finish = rnd(2) == 0;
        uint64_t limit = finish ? UINT64_MAX : rnd((uint32_t)(pending / k) + 2);
        while (steps < limit && vts_clipmap_pending(&c) > 0) {
            st->loads += walk_step(&c, &m, k, plan, plan_cap, st->plans % 211 == 0);
            st->plans++;
            steps++;
        }
        st->steps += (unsigned)steps;
        if (finish) {
            VT_CHECK_INT_EQ(steps, (pending + k - 1) / k);
            VT_CHECK_INT_EQ(vts_clipmap_plan(&c, plan, plan_cap), 0);
            for (uint32_t l = 0; l < c.level_count; l++) {
                VT_CHECK(vts_clipmap_complete(&c, l));
                VT_CHECK(rect_eq(&c.levels[l].front, &m.target[l]));
                for (uint32_t y = m.target[l].y0; y < m.target[l].y1; y++)
                    for (uint32_t x = m.target[l].x0; x < m.target[l].x1; x++)
                        VT_CHECK(model_in_slot(&m, l, x, y));
            }
        }
    }
    free(plan);
    vts_clipmap_free(&c);
    st->walks++;
}

/* The state checker's negative controls: a front reaching over a tile not loaded, a slot of the
 * front overwritten, a target the model does not have: each is reported. */
static void state_checker_catches_a_wrong_front(void)
{
    struct vts_geometry g = geometry_of(2); /* 40x40 tiles */
    struct vts_clipmap c;
    VT_CHECK_INT_EQ(vts_clipmap_init(&c, &g, 5, NULL), 0);
    struct model m = {.n = 5, .level_count = c.level_count};
    for (uint32_t l = 0; l < c.level_count; l++) {
        m.tiles_x[l] = c.levels[l].tiles_x;
        m.tiles_y[l] = c.levels[l].tiles_y;
        for (uint32_t s = 0; s < 25; s++)
            m.slot[l][s] = -1;
    }
    struct vts_tile_rect w = {10, 12, 15, 17};
    VT_CHECK_INT_EQ(vts_clipmap_move(&c, 0, &w), 0);
    m.target[0] = w;
    struct vts_clipmap_tile plan[12];
    uint32_t count = vts_clipmap_plan(&c, plan, 12); /* two rows and two tiles of the third */
    VT_CHECK_INT_EQ(count, 12);
    for (uint32_t i = 0; i < count; i++) {
        VT_CHECK_INT_EQ(vts_clipmap_loaded(&c, &plan[i]), 0);
        m.slot[0][plan[i].slot_y * 5 + plan[i].slot_x] = (int64_t)plan[i].y * 40 + plan[i].x;
    }
    struct vts_tile_rect two_rows = {10, 12, 15, 14};
    VT_CHECK(rect_eq(&c.levels[0].front, &two_rows));
    VT_CHECK_INT_EQ(check_state(&c, &m), 0);
    c.levels[0].front.y1++; /* the third row is not all loaded */
    VT_CHECK(check_state(&c, &m) > 0);
    c.levels[0].front.y1--;
    /* slot (0, 2) holds the front's tile (10, 12): overwritten by tile (15, 12), outside it */
    uint64_t *slot = &c.levels[0].slot_tile[2 * 5 + 0], keep = *slot;
    VT_CHECK_INT_EQ(keep, 12 * 40 + 10);
    *slot = 12 * 40 + 15;
    VT_CHECK(check_state(&c, &m) > 0);
    m.slot[0][2 * 5 + 0] = 12 * 40 + 15; /* even where the model agrees: the front is wrong */
    VT_CHECK(check_state(&c, &m) > 0);
    m.slot[0][2 * 5 + 0] = 12 * 40 + 10;
    *slot = keep;
    m.target[0].x1--;
    VT_CHECK(check_state(&c, &m) > 0);
    m.target[0].x1++;
    VT_CHECK_INT_EQ(check_state(&c, &m), 0);
    vts_clipmap_free(&c);
}

static void walks_load_exactly_the_missing_tiles(void)
{
    struct walk_stats st = {0};
    for (size_t gi = 0; gi < GEOMETRY_COUNT; gi++)
        for (uint32_t n = 1; n <= MAX_N; n++)
            for (uint32_t k = 1; k <= 7; k++)
                walk(gi, n, k, 40, &st);
    fprintf(stderr, "  %u walks, %u moves, %u steps, %u plans, %u tiles loaded\n", st.walks,
            st.moves, st.steps, st.plans, st.loads);
}

/* Hand-checked cases: the documented strips of a diagonal move, a partial last tile's valid
 * rectangle, n = 1, the seeding of an empty front. */
static void known_answers(void)
{
    struct vts_tile_rect from = {2, 3, 6, 7}, to = {3, 1, 7, 5}, out[4];
    VT_CHECK_INT_EQ(vts_clipmap_strips(&from, &to, out), 2);
    struct vts_tile_rect right = {6, 3, 7, 5}, above = {3, 1, 7, 3};
    VT_CHECK(rect_eq(&out[0], &right) && rect_eq(&out[1], &above));
    struct vts_tile_rect far = {10, 10, 14, 14};
    VT_CHECK_INT_EQ(vts_clipmap_strips(&from, &far, out), 1);
    VT_CHECK(rect_eq(&out[0], &far));
    VT_CHECK_INT_EQ(vts_clipmap_strips(&from, &from, out), 0);

    /* 10 x 10 texels in 4 px tiles: 3 x 3 tiles, the last ones 2 texels wide */
    struct vts_geometry g = {10, 10, 4, 0, 4, 1, 1, 0};
    struct vts_clipmap c;
    VT_CHECK_INT_EQ(vts_clipmap_init(&c, &g, 2, NULL), 0);
    struct vts_tile_rect w;
    VT_CHECK_INT_EQ(vts_clipmap_window(&c, 0, 9.5, 0, &w), 0); /* 9.5 / 4 - 1 + 0.5 -> 1 */
    struct vts_tile_rect want = {1, 0, 3, 2};
    VT_CHECK(rect_eq(&w, &want));
    VT_CHECK_INT_EQ(vts_clipmap_window(&c, 0, NAN, INFINITY, &w), 0);
    struct vts_tile_rect origin = {0, 0, 2, 2};
    VT_CHECK(rect_eq(&w, &origin));
    VT_CHECK_INT_EQ(vts_clipmap_move(&c, 0, &want), 0);
    VT_CHECK_INT_EQ(vts_clipmap_pending(&c), 4);
    struct vts_clipmap_tile plan[4];
    VT_CHECK_INT_EQ(vts_clipmap_plan(&c, plan, 4), 4);
    VT_CHECK(plan[0].x == 1 && plan[0].y == 0 && plan[1].x == 2 && plan[1].y == 0);
    VT_CHECK(plan[1].slot_x == 0 && plan[1].slot_y == 0);
    VT_CHECK(plan[2].x == 1 && plan[2].y == 1 && plan[3].x == 2 && plan[3].y == 1);
    /* the top-left tile not loaded first: the front waits for it */
    VT_CHECK_INT_EQ(vts_clipmap_loaded(&c, &plan[1]), 0);
    VT_CHECK(rect_empty(&c.levels[0].front));
    VT_CHECK_INT_EQ(vts_clipmap_loaded(&c, &plan[0]), 0);
    struct vts_tile_rect row0 = {1, 0, 3, 1};
    VT_CHECK(rect_eq(&c.levels[0].front, &row0));
    VT_CHECK_INT_EQ(vts_clipmap_loaded(&c, &plan[2]), 0);
    VT_CHECK(rect_eq(&c.levels[0].front, &row0));
    VT_CHECK_INT_EQ(vts_clipmap_loaded(&c, &plan[3]), 0);
    VT_CHECK(vts_clipmap_complete(&c, 0));
    double x0, y0, x1, y1;
    vts_clipmap_valid(&c, 0, 1.5, &x0, &y0, &x1, &y1);
    /* left side inside the level: inset; right: the level's edge at texel 10; bottom inside */
    VT_CHECK(x0 == 5.5 && x1 == 10 && y0 == 0 && y1 == 6.5);
    /* back to the origin: tiles (1, 0) and (1, 1) stay, (0, 0) and (0, 1) replace (2, y) */
    VT_CHECK_INT_EQ(vts_clipmap_move(&c, 0, &origin), 0);
    struct vts_tile_rect stay = {1, 0, 2, 2};
    VT_CHECK(rect_eq(&c.levels[0].front, &stay));
    VT_CHECK_INT_EQ(vts_clipmap_plan(&c, plan, 4), 2);
    VT_CHECK(plan[0].x == 0 && plan[0].y == 0 && plan[1].x == 0 && plan[1].y == 1);
    vts_clipmap_free(&c);

    /* n = 1: one tile per level, the tile under the centre */
    VT_CHECK_INT_EQ(vts_clipmap_init(&c, &g, 1, NULL), 0);
    VT_CHECK_INT_EQ(vts_clipmap_window(&c, 0, 7.99, 8, &w), 0);
    struct vts_tile_rect one = {1, 2, 2, 3};
    VT_CHECK(rect_eq(&w, &one));
    uint32_t sx, sy;
    vts_clipmap_slot(&c, 5, 7, &sx, &sy);
    VT_CHECK(sx == 0 && sy == 0);
    vts_clipmap_free(&c);
}

static uint64_t area(const struct vts_tile_rect *r)
{
    return rect_empty(r) ? 0 : (uint64_t)(r->x1 - r->x0) * (r->y1 - r->y0);
}

/* n = 256 over a 2^20-texel square in 256 px tiles (4096 x 4096 tiles at level 0, 13 levels):
 * the first fill and then diagonal moves load exactly the area of the new strips, in
 * ceil(pending / budget) steps, and every level ends complete. */
static void a_large_window_loads_exactly_its_strips(void)
{
    struct vts_geometry g = {1u << 20, 1u << 20, 256, 0, 256, 13, 1, 0};
    struct vts_clipmap c;
    VT_CHECK_INT_EQ(vts_clipmap_init(&c, &g, VTS_CLIPMAP_MAX_N, NULL), 0);
    const uint32_t budget = 4096;
    struct vts_clipmap_tile *plan = calloc(budget, sizeof *plan);
    double cx = 300000.5, cy = 700000.25;
    for (int mv = 0; mv < 4; mv++) {
        uint64_t want = 0;
        for (uint32_t l = 0; l < c.level_count; l++) {
            struct vts_tile_rect w, old = c.levels[l].back;
            VT_CHECK_INT_EQ(vts_clipmap_window(&c, l, cx / (1u << l), cy / (1u << l), &w), 0);
            VT_CHECK_INT_EQ(vts_clipmap_move(&c, l, &w), 0);
            struct vts_tile_rect in = {old.x0 > w.x0 ? old.x0 : w.x0, old.y0 > w.y0 ? old.y0 : w.y0,
                                       old.x1 < w.x1 ? old.x1 : w.x1,
                                       old.y1 < w.y1 ? old.y1 : w.y1};
            want += area(&w) - area(&in);
        }
        uint64_t pending = vts_clipmap_pending(&c), steps = 0, loads = 0;
        VT_CHECK_INT_EQ(pending, want);
        for (uint32_t k; (k = vts_clipmap_plan(&c, plan, budget)) > 0; steps++)
            for (uint32_t i = 0; i < k; i++, loads++)
                VT_CHECK(vts_clipmap_loaded(&c, &plan[i]) == 0);
        VT_CHECK_INT_EQ(loads, want);
        VT_CHECK_INT_EQ(steps, (want + budget - 1) / budget);
        for (uint32_t l = 0; l < c.level_count; l++)
            VT_CHECK(vts_clipmap_complete(&c, l));
        /* 3.5 tiles right and 2 up at level 0 (the coarse levels move less or not at all) */
        cx += 3.5 * 256, cy -= 2 * 256;
    }
    free(plan);
    vts_clipmap_free(&c);
}

static void bad_arguments_are_refused(void)
{
    struct vts_geometry g = {100, 60, 8, 0, 8, 2, 1, 0};
    struct vts_clipmap c;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vts_clipmap_init(&c, &g, 0, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "outside 1..256");
    VT_CHECK_INT_EQ(vts_clipmap_init(&c, &g, 257, &err), VTS_ERR_ARG);
    VT_CHECK_INT_EQ(vts_clipmap_init(&c, NULL, 4, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "geometry");
    struct vts_geometry bad = g;
    bad.tile_payload_px = 9;
    VT_CHECK_INT_EQ(vts_clipmap_init(&c, &bad, 4, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "payload");
    vts_clipmap_free(&c); /* zeroed by the failed init */
    vts_clipmap_free(NULL);

    VT_CHECK_INT_EQ(vts_clipmap_init(&c, &g, 4, &err), 0);
    VT_CHECK_INT_EQ(c.level_count, 2);
    VT_CHECK(!vts_clipmap_complete(&c, 1)); /* no target yet */
    VT_CHECK_INT_EQ(vts_clipmap_pending(&c), 0);
    struct vts_tile_rect w = {1, 1, 1, 1};
    VT_CHECK_INT_EQ(vts_clipmap_window(&c, 2, 0, 0, &w), VTS_ERR_RANGE);
    VT_CHECK(w.x0 == 0 && w.x1 == 0 && w.y0 == 0 && w.y1 == 0);
    struct vts_tile_rect wide = {0, 0, 5, 4}, outside = {10, 0, 14, 4}, ok = {9, 4, 13, 8};
    VT_CHECK_INT_EQ(vts_clipmap_move(&c, 0, &wide), VTS_ERR_RANGE);
    VT_CHECK_INT_EQ(vts_clipmap_move(&c, 0, &outside), VTS_ERR_RANGE); /* 13 tiles across */
    VT_CHECK_INT_EQ(vts_clipmap_move(&c, 2, &ok), VTS_ERR_RANGE);
    VT_CHECK_INT_EQ(vts_clipmap_move(&c, 0, &ok), 0);
    struct vts_clipmap_tile t = {0, 8, 4, 0, 0};
    VT_CHECK_INT_EQ(vts_clipmap_loaded(&c, &t), VTS_ERR_RANGE);
    t.level = 5;
    VT_CHECK_INT_EQ(vts_clipmap_loaded(&c, &t), VTS_ERR_RANGE);
    VT_CHECK(!vts_clipmap_complete(&c, 0));
    VT_CHECK(!vts_clipmap_complete(&c, 9));
    double x0 = 1, y0 = 1, x1 = 1, y1 = 1;
    vts_clipmap_valid(&c, 9, 0, &x0, &y0, &x1, &y1);
    VT_CHECK(!(x0 < x1));
    /* an empty target empties the level */
    struct vts_tile_rect none = {0};
    VT_CHECK_INT_EQ(vts_clipmap_move(&c, 0, &none), 0);
    VT_CHECK_INT_EQ(vts_clipmap_pending(&c), 0);
    vts_clipmap_free(&c);
    vts_clipmap_free(&c);
}

int main(void)
{
    VT_RUN(known_answers);
    VT_RUN(bad_arguments_are_refused);
    VT_RUN(windows_follow_the_snapping_formula);
    VT_RUN(windows_of_one_centre_nest);
    VT_RUN(strips_cover_exactly_the_new_tiles_in_order);
    VT_RUN(state_checker_catches_a_wrong_front);
    VT_RUN(walks_load_exactly_the_missing_tiles);
    VT_RUN(a_large_window_loads_exactly_its_strips);
    return vt_test_main_result();
}
