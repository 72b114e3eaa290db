/* lib/compose's chain cache (vt_atlas_cache): a chain is built once and shared while it stays
 * cached, unreferenced chains are freed least recently used first while the cache holds more than
 * its budget, a pinned chain is never freed, a freed chain is built again on its next use (and
 * counted), a worker holds at most VT_ATLAS_CACHE_PINS chains, a failed build is reported and
 * retried, and workers asking for one chain at once build it once. The build callback counts its
 * calls per key, independently of the cache's own counter. */
#define _GNU_SOURCE /* syscall(SYS_gettid) in vt_test_threads.h */
#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_atlas_cache.h"
#include "unit/vt_test_threads.h"
#include "vt_error.h"
#include "vt_image.h"
#include "vt_test.h"

#define KEYS        64
#define MAX_WORKERS 8
#define SIDE        32 /* every chain: one 32x32 level of 1 byte per texel */
#define CHAIN_BYTES ((uint64_t)SIDE * SIDE)

struct builder {
    atomic_int builds[KEYS];
    int fail_key; /* the next build of this key fails */
    atomic_int fail_next;
    /* gate: a build of gate_key waits until the other workers are blocked in the cache */
    int gate_key;
    pid_t worker_tids[MAX_WORKERS];
    atomic_int asking[MAX_WORKERS]; /* worker i has asked for its chain */
    atomic_int done[MAX_WORKERS];   /* ... and got it (a broken cache may let it build its own) */
    unsigned workers;
    atomic_int gate_timed_out;
};

static bool other_workers_blocked(const struct builder *b)
{
    pid_t self = vt_test_tid();
    for (unsigned i = 0; i < b->workers; i++)
        if (b->worker_tids[i] != self && !atomic_load(&b->done[i]) &&
            !(atomic_load(&b->asking[i]) && vt_test_thread_sleeping(b->worker_tids[i])))
            return false;
    return true;
}

/* Chain of key: one level filled with (key * 3 + texel index) & 255. */
static int build(void *user, uint64_t key, struct vt_mip_chain *out, struct vts_error *err)
{
    struct builder *b = user;
    memset(out, 0, sizeof *out);
    atomic_fetch_add(&b->builds[key], 1);
    if ((int)key == b->gate_key) {
        double until = vt_test_now() + VT_TEST_DEADLINE_S;
        while (!other_workers_blocked(b) && vt_test_now() < until)
            vt_test_sleep_ms(1);
        if (vt_test_now() >= until)
            atomic_store(&b->gate_timed_out, 1);
    }
    if ((int)key == b->fail_key && atomic_exchange(&b->fail_next, 0))
        return vt_error_set(err, VTS_ERR_IO, "'tex%d.png': cannot decode", (int)key);
    int rc = vt_image_alloc(&out->levels[0], SIDE, SIDE, 1, VTS_SAMPLE_U8, err);
    if (rc)
        return rc;
    uint8_t *p = out->levels[0].pixels;
    for (uint32_t i = 0; i < SIDE * SIDE; i++)
        p[i] = (uint8_t)(key * 3 + i);
    out->level_count = 1;
    out->bytes = CHAIN_BYTES;
    return 0;
}

static bool chain_is(const struct vt_mip_chain *c, uint64_t key)
{
    if (!c || c->level_count != 1 || c->bytes != CHAIN_BYTES || c->levels[0].width != SIDE)
        return false;
    const uint8_t *p = c->levels[0].pixels;
    for (uint32_t i = 0; i < SIDE * SIDE; i++)
        if (p[i] != (uint8_t)(key * 3 + i))
            return false;
    return true;
}

static struct builder *builder_new(void)
{
    struct builder *b = calloc(1, sizeof *b);
    b->fail_key = -1;
    b->gate_key = -1;
    return b;
}

static int builds_of(struct builder *b, uint64_t key)
{
    return atomic_load(&b->builds[key]);
}

/* Gets key in a fresh pin set, checks its texels, unpins it. */
static bool use(struct vt_atlas_cache *c, uint64_t key)
{
    struct vt_atlas_cache_pins pins = {0};
    const struct vt_mip_chain *chain = NULL;
    bool ok = vt_atlas_cache_get(c, &pins, key, &chain, NULL) == 0 && chain_is(chain, key);
    vt_atlas_cache_unpin_all(c, &pins);
    return ok;
}

static void the_chain_check_catches_a_wrong_value(void)
{
    struct builder *b = builder_new();
    struct vt_mip_chain chain;
    VT_CHECK_INT_EQ(build(b, 5, &chain, NULL), 0);
    VT_CHECK(chain_is(&chain, 5));
    VT_CHECK(!chain_is(&chain, 6));                            /* another key's chain */
    ((uint8_t *)chain.levels[0].pixels)[SIDE * SIDE - 1] ^= 1; /* its last texel off by one */
    VT_CHECK(!chain_is(&chain, 5));
    vt_mip_chain_release(&chain);
    free(b);
}

static void a_chain_is_built_once_while_it_stays_cached(void)
{
    struct builder *b = builder_new();
    struct vt_atlas_cache c;
    VT_CHECK_INT_EQ(vt_atlas_cache_init(&c, KEYS, 10 * CHAIN_BYTES, build, b, NULL), 0);
    struct vt_atlas_cache_pins pins = {0};
    const struct vt_mip_chain *first = NULL, *again = NULL;
    VT_CHECK_INT_EQ(vt_atlas_cache_get(&c, &pins, 7, &first, NULL), 0);
    VT_CHECK(chain_is(first, 7));
    VT_CHECK_INT_EQ(vt_atlas_cache_get(&c, &pins, 7, &again, NULL), 0); /* pinned: same chain */
    VT_CHECK(again == first);
    VT_CHECK_INT_EQ(pins.count, 1);
    vt_atlas_cache_unpin_all(&c, &pins);
    VT_CHECK_INT_EQ(pins.count, 0);
    VT_CHECK(use(&c, 7)); /* unpinned but cached: not built again */
    VT_CHECK_INT_EQ(builds_of(b, 7), 1);
    VT_CHECK_INT_EQ(c.built, 1);
    VT_CHECK_INT_EQ(c.bytes, CHAIN_BYTES);
    vt_atlas_cache_release(&c);
    free(b);
}

static void unreferenced_chains_stay_within_the_budget_oldest_freed_first(void)
{
    struct builder *b = builder_new();
    struct vt_atlas_cache c;
    VT_CHECK_INT_EQ(vt_atlas_cache_init(&c, KEYS, 3 * CHAIN_BYTES, build, b, NULL), 0);
    bool budget_held = true;
    for (uint64_t k = 0; k < 5; k++) {
        VT_CHECK(use(&c, k));
        budget_held = budget_held && c.bytes <= c.budget;
    }
    VT_CHECK(budget_held);
    VT_CHECK_INT_EQ(c.bytes, 3 * CHAIN_BYTES); /* 2, 3, 4 kept; 0 and 1 freed */
    VT_CHECK_INT_EQ(c.peak, 4 * CHAIN_BYTES);  /* one over while a new chain was in use */
    VT_CHECK(use(&c, 2) && use(&c, 3) && use(&c, 4));
    VT_CHECK_INT_EQ(c.built, 5);
    /* now the order of use is 2, 3, 4: touching 2 makes 3 the oldest */
    VT_CHECK(use(&c, 2));
    VT_CHECK(use(&c, 10)); /* frees 3 */
    VT_CHECK(use(&c, 2) && use(&c, 4) && use(&c, 10));
    VT_CHECK_INT_EQ(builds_of(b, 2), 1);
    VT_CHECK_INT_EQ(builds_of(b, 4), 1);
    VT_CHECK_INT_EQ(builds_of(b, 3), 1);
    VT_CHECK(use(&c, 3)); /* freed: built again, counted */
    VT_CHECK_INT_EQ(builds_of(b, 3), 2);
    VT_CHECK(use(&c, 0));
    VT_CHECK_INT_EQ(builds_of(b, 0), 2);
    VT_CHECK_INT_EQ(c.built, 8);
    VT_CHECK(c.bytes <= c.budget);
    vt_atlas_cache_release(&c);
    free(b);
}

static void a_pinned_chain_is_not_freed(void)
{
    struct builder *b = builder_new();
    struct vt_atlas_cache c;
    VT_CHECK_INT_EQ(vt_atlas_cache_init(&c, KEYS, 1 * CHAIN_BYTES, build, b, NULL), 0);
    struct vt_atlas_cache_pins held = {0};
    const struct vt_mip_chain *kept = NULL;
    VT_CHECK_INT_EQ(vt_atlas_cache_get(&c, &held, 0, &kept, NULL), 0);
    for (uint64_t k = 1; k < 20; k++) /* each new chain pushes the cache over its budget */
        VT_CHECK(use(&c, k));
    VT_CHECK(chain_is(kept, 0)); /* still there, texels intact (ASan: not freed) */
    VT_CHECK_INT_EQ(builds_of(b, 0), 1);
    VT_CHECK_INT_EQ(c.bytes, CHAIN_BYTES); /* the pinned chain only: the others were freed */
    const struct vt_mip_chain *same = NULL;
    struct vt_atlas_cache_pins other = {0};
    VT_CHECK_INT_EQ(vt_atlas_cache_get(&c, &other, 0, &same, NULL), 0); /* a second worker */
    VT_CHECK(same == kept);
    vt_atlas_cache_unpin_all(&c, &other);
    VT_CHECK(chain_is(kept, 0)); /* still referenced by the first */
    vt_atlas_cache_unpin_all(&c, &held);
    VT_CHECK(c.bytes <= c.budget); /* once released, the budget holds again */
    VT_CHECK_INT_EQ(c.built, 20);
    vt_atlas_cache_release(&c);
    free(b);
}

static void a_worker_holds_at_most_the_pin_limit(void)
{
    struct builder *b = builder_new();
    struct vt_atlas_cache c;
    VT_CHECK_INT_EQ(vt_atlas_cache_init(&c, KEYS, 0, build, b, NULL), 0); /* keeps nothing */
    struct vt_atlas_cache_pins pins = {0};
    const struct vt_mip_chain *chain;
    for (uint64_t k = 0; k < VT_ATLAS_CACHE_PINS; k++)
        VT_CHECK_INT_EQ(vt_atlas_cache_get(&c, &pins, k, &chain, NULL), 0);
    VT_CHECK_INT_EQ(pins.count, VT_ATLAS_CACHE_PINS);
    VT_CHECK_INT_EQ(c.bytes, VT_ATLAS_CACHE_PINS * CHAIN_BYTES); /* all pinned */
    /* one more: the oldest pin (key 0) is released, and with a budget of 0 freed */
    VT_CHECK_INT_EQ(vt_atlas_cache_get(&c, &pins, 100 % KEYS, &chain, NULL), 0);
    VT_CHECK(chain_is(chain, 100 % KEYS));
    VT_CHECK_INT_EQ(pins.count, VT_ATLAS_CACHE_PINS);
    VT_CHECK_INT_EQ(c.bytes, VT_ATLAS_CACHE_PINS * CHAIN_BYTES);
    VT_CHECK(c.table[0] == NULL);
    VT_CHECK(c.table[1] != NULL); /* the other pins hold */
    vt_atlas_cache_unpin_all(&c, &pins);
    VT_CHECK_INT_EQ(c.bytes, 0);
    vt_atlas_cache_release(&c);
    free(b);
}

static void a_failed_build_is_reported_and_retried(void)
{
    struct builder *b = builder_new();
    b->fail_key = 9;
    atomic_store(&b->fail_next, 1);
    struct vt_atlas_cache c;
    VT_CHECK_INT_EQ(vt_atlas_cache_init(&c, KEYS, 4 * CHAIN_BYTES, build, b, NULL), 0);
    struct vt_atlas_cache_pins pins = {0};
    const struct vt_mip_chain *chain = NULL;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atlas_cache_get(&c, &pins, 9, &chain, &err), VTS_ERR_IO);
    VT_CHECK_STR_CONTAINS(err.message, "'tex9.png': cannot decode");
    VT_CHECK_INT_EQ(pins.count, 0);
    VT_CHECK_INT_EQ(c.bytes, 0);
    VT_CHECK_INT_EQ(c.built, 0);
    VT_CHECK(use(&c, 9)); /* built again, this time fine */
    VT_CHECK_INT_EQ(builds_of(b, 9), 2);
    VT_CHECK_INT_EQ(c.built, 1);
    vt_atlas_cache_release(&c);
    free(b);
}

struct worker {
    struct vt_atlas_cache *cache;
    struct builder *b;
    unsigned index;
    atomic_int *registered;
    uint64_t key; /* the one key to get, or with rounds: random keys */
    unsigned rounds;
    uint64_t seed;
    bool ok;
};

static void *worker_main(void *arg)
{
    struct worker *w = arg;
    w->b->worker_tids[w->index] = vt_test_tid();
    atomic_fetch_add(w->registered, 1);
    double until = vt_test_now() + VT_TEST_DEADLINE_S;
    while (atomic_load(w->registered) < (int)w->b->workers && vt_test_now() < until)
        vt_test_sleep_ms(1);
    atomic_store(&w->b->asking[w->index], 1);
    w->ok = true;
    if (!w->rounds) {
        w->ok = use(w->cache, w->key);
        atomic_store(&w->b->done[w->index], 1);
        return NULL;
    }
    /* random keys, several pinned at once (a worker compositing tiles that span entries) */
    struct vt_atlas_cache_pins pins = {0};
    for (unsigned i = 0; i < w->rounds && w->ok; i++) {
        w->seed = w->seed * 6364136223846793005ull + 1442695040888963407ull;
        uint64_t key = (w->seed >> 33) % 24;
        const struct vt_mip_chain *chain = NULL;
        w->ok = vt_atlas_cache_get(w->cache, &pins, key, &chain, NULL) == 0 && chain_is(chain, key);
        if ((w->seed >> 20) % 4 == 0)
            vt_atlas_cache_unpin_all(w->cache, &pins);
    }
    vt_atlas_cache_unpin_all(w->cache, &pins);
    atomic_store(&w->b->done[w->index], 1);
    return NULL;
}

static void workers_asking_for_one_chain_at_once_build_it_once(void)
{
    static const unsigned counts[] = {2, 4, 8};
    for (size_t k = 0; k < sizeof counts / sizeof counts[0]; k++) {
        unsigned n = counts[k];
        struct builder *b = builder_new();
        b->workers = n;
        b->gate_key = 5; /* its builder waits until the other workers wait for it */
        struct vt_atlas_cache c;
        VT_CHECK_INT_EQ(vt_atlas_cache_init(&c, KEYS, 4 * CHAIN_BYTES, build, b, NULL), 0);
        atomic_int registered = 0;
        struct worker w[MAX_WORKERS];
        pthread_t th[MAX_WORKERS];
        for (unsigned i = 0; i < n; i++) {
            w[i] = (struct worker){&c, b, i, &registered, 5, 0, 0, false};
            pthread_create(&th[i], NULL, worker_main, &w[i]);
        }
        for (unsigned i = 0; i < n; i++) {
            pthread_join(th[i], NULL);
            VT_CHECK(w[i].ok);
        }
        VT_CHECK_INT_EQ(atomic_load(&b->gate_timed_out), 0);
        VT_CHECK_INT_EQ(builds_of(b, 5), 1);
        VT_CHECK_INT_EQ(c.built, 1);
        vt_atlas_cache_release(&c);
        free(b);
    }
}

/* Four workers, random keys, a budget of 3 chains: every chain they see is right, and once they
 * are done the cache is within its budget (run under ThreadSanitizer by scripts/test). */
static void many_workers_with_a_small_budget_see_the_right_chains(void)
{
    const unsigned n = 4;
    struct builder *b = builder_new();
    b->workers = n;
    struct vt_atlas_cache c;
    VT_CHECK_INT_EQ(vt_atlas_cache_init(&c, KEYS, 3 * CHAIN_BYTES, build, b, NULL), 0);
    atomic_int registered = 0;
    struct worker w[MAX_WORKERS];
    pthread_t th[MAX_WORKERS];
    for (unsigned i = 0; i < n; i++) {
        w[i] = (struct worker){&c, b, i, &registered, 0, 2000, 77 + i, false};
        pthread_create(&th[i], NULL, worker_main, &w[i]);
    }
    for (unsigned i = 0; i < n; i++) {
        pthread_join(th[i], NULL);
        VT_CHECK(w[i].ok);
    }
    int builds = 0;
    for (int k = 0; k < KEYS; k++)
        builds += builds_of(b, (uint64_t)k);
    VT_CHECK_INT_EQ(c.built, builds);
    VT_CHECK(builds > 24); /* 3 chains of budget for 24 keys: some were built again */
    VT_CHECK(c.bytes <= c.budget);
    vt_atlas_cache_release(&c);
    free(b);
}

int main(void)
{
    VT_RUN(the_chain_check_catches_a_wrong_value);
    VT_RUN(a_chain_is_built_once_while_it_stays_cached);
    VT_RUN(unreferenced_chains_stay_within_the_budget_oldest_freed_first);
    VT_RUN(a_pinned_chain_is_not_freed);
    VT_RUN(a_worker_holds_at_most_the_pin_limit);
    VT_RUN(a_failed_build_is_reported_and_retried);
    VT_RUN(workers_asking_for_one_chain_at_once_build_it_once);
    VT_RUN(many_workers_with_a_small_budget_see_the_right_chains);
    return vt_test_main_result();
}
