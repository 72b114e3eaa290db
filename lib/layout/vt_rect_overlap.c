/* Overlap of axis-aligned rectangles: a sweep over x, the rectangles spanning the sweep line in a
 * treap keyed by y (internal/vt_rect_overlap.h). */
#include "internal/vt_rect_overlap.h"

#include <stdlib.h>

struct treap {
    uint32_t *left, *right, *prio; /* node i = rectangle i - 1; 0 = none */
    const struct vt_rect *r;
    uint32_t root;
};

static uint32_t key(const struct treap *t, uint32_t n)
{
    return t->r[n - 1].y;
}

static uint32_t rot_right(struct treap *t, uint32_t n)
{
    uint32_t l = t->left[n];
    t->left[n] = t->right[l];
    t->right[l] = n;
    return l;
}

static uint32_t rot_left(struct treap *t, uint32_t n)
{
    uint32_t r = t->right[n];
    t->right[n] = t->left[r];
    t->left[r] = n;
    return r;
}

static uint32_t treap_insert(struct treap *t, uint32_t root, uint32_t n)
{
    if (!root)
        return n;
    if (key(t, n) < key(t, root)) {
        t->left[root] = treap_insert(t, t->left[root], n);
        if (t->prio[t->left[root]] > t->prio[root])
            root = rot_right(t, root);
    } else {
        t->right[root] = treap_insert(t, t->right[root], n);
        if (t->prio[t->right[root]] > t->prio[root])
            root = rot_left(t, root);
    }
    return root;
}

/* Removes the node with n's key (keys of active rectangles are unique: they are disjoint). */
static uint32_t treap_remove(struct treap *t, uint32_t root, uint32_t n)
{
    if (!root)
        return 0;
    if (key(t, n) < key(t, root)) {
        t->left[root] = treap_remove(t, t->left[root], n);
        return root;
    }
    if (key(t, n) > key(t, root)) {
        t->right[root] = treap_remove(t, t->right[root], n);
        return root;
    }
    if (!t->left[root] || !t->right[root])
        return t->left[root] ? t->left[root] : t->right[root];
    if (t->prio[t->left[root]] > t->prio[t->right[root]]) {
        uint32_t r = rot_right(t, root);
        t->right[r] = treap_remove(t, t->right[r], n);
        return r;
    }
    uint32_t r = rot_left(t, root);
    t->left[r] = treap_remove(t, t->left[r], n);
    return r;
}

/* The active node with the largest y below limit, or 0. */
static uint32_t treap_below(const struct treap *t, uint32_t limit)
{
    uint32_t n = t->root, best = 0;
    while (n) {
        if (key(t, n) < limit) {
            best = n;
            n = t->right[n];
        } else {
            n = t->left[n];
        }
    }
    return best;
}

/* A sweep event: where a rectangle starts or ends along x, and which one. */
struct event {
    uint64_t x;
    uint32_t i;
};

static int cmp_event(const void *pa, const void *pb)
{
    const struct event *a = pa, *b = pb;
    if (a->x != b->x)
        return (a->x > b->x) - (a->x < b->x);
    return (a->i > b->i) - (a->i < b->i);
}

int vt_rect_overlap_find(const struct vt_rect *r, uint32_t n, uint32_t *a, uint32_t *b)
{
    if (n < 2)
        return 0;
    int rc = -1;
    struct treap t = {.r = r};
    struct event *start = malloc((size_t)n * sizeof *start), *end = malloc((size_t)n * sizeof *end);
    t.left = calloc((size_t)n + 1, sizeof *t.left);
    t.right = calloc((size_t)n + 1, sizeof *t.right);
    t.prio = malloc(((size_t)n + 1) * sizeof *t.prio);
    if (!start || !end || !t.left || !t.right || !t.prio)
        goto out;
    uint32_t seed = 2463534242u;
    for (uint32_t i = 0; i < n; i++) {
        start[i] = (struct event){r[i].x, i};
        end[i] = (struct event){(uint64_t)r[i].x + r[i].w, i};
        seed ^= seed << 13, seed ^= seed >> 17, seed ^= seed << 5;
        t.prio[i + 1] = seed;
    }
    qsort(start, n, sizeof *start, cmp_event);
    qsort(end, n, sizeof *end, cmp_event);
    rc = 0;
    for (uint32_t s = 0, k = 0; s < n; s++) {
        const struct vt_rect *e = &r[start[s].i];
        for (; k < n && end[k].x <= e->x; k++)
            t.root = treap_remove(&t, t.root, end[k].i + 1);
        uint32_t below = treap_below(&t, e->y + e->h);
        if (below && (uint64_t)key(&t, below) + r[below - 1].h > e->y) {
            *a = below - 1;
            *b = start[s].i;
            rc = 1;
            goto out;
        }
        t.root = treap_insert(&t, t.root, start[s].i + 1);
    }
out:
    free(start);
    free(end);
    free(t.left);
    free(t.right);
    free(t.prio);
    return rc;
}
