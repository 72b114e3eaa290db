/* Block store of the atlas compositor's mip chains (see internal/vt_block_cache.h). */
#include "internal/vt_block_cache.h"

#include <assert.h>
#include <errno.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "vt_error.h"

struct vt_block_cache_node {
    uint8_t *data; /* NULL while the block is only in the file */
    uint64_t off;  /* in the file, when in_file */
    uint32_t bytes;
    int refs;
    bool in_file;
    bool loading; /* busy: being read back, or being written out (then data is still set) */
    /* LRU list of unreferenced blocks in memory; next also chains the blocks one caller writes */
    struct vt_block_cache_node *prev, *next;
};

struct vt_block_cache {
    pthread_mutex_t mu;
    pthread_cond_t cv;
    struct vt_block_cache_node **table;
    uint64_t count;
    struct vt_block_cache_node *lru_head, *lru_tail;
    uint64_t budget, bytes, pinned, peak, peak_unpinned, spilled, reloads, file_end;
    uint64_t writing; /* bytes of evicted blocks still being written out (outside the lock) */
    uint64_t reserved, peak_reserved; /* readers' and writers' buffers counted in the budget */
    uint64_t freed; /* block bytes freed since memory was last given back (trim_due) */
    int fd;
    char dir[4096];
};

static void lru_unlink(struct vt_block_cache *c, struct vt_block_cache_node *n)
{
    if (n->prev)
        n->prev->next = n->next;
    else
        c->lru_head = n->next;
    if (n->next)
        n->next->prev = n->prev;
    else
        c->lru_tail = n->prev;
    n->prev = n->next = NULL;
}

static void lru_push(struct vt_block_cache *c, struct vt_block_cache_node *n)
{
    n->prev = c->lru_tail;
    n->next = NULL;
    if (c->lru_tail)
        c->lru_tail->next = n;
    else
        c->lru_head = n;
    c->lru_tail = n;
}

static void note_peak(struct vt_block_cache *c)
{
    if (c->bytes + c->writing > c->peak)
        c->peak = c->bytes + c->writing;
    if (c->bytes - c->pinned > c->peak_unpinned)
        c->peak_unpinned = c->bytes - c->pinned;
}

static int open_file(struct vt_block_cache *c, struct vts_error *err)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/.vt-chains-XXXXXX", c->dir);
    c->fd = mkstemp(path);
    if (c->fd < 0)
        return vt_error_set(err, VTS_ERR_IO, "cannot create a temporary file in '%s': %s", c->dir,
                            strerror(errno));
    unlink(path); /* the blocks live until the descriptor closes, even if the process is killed */
    return 0;
}

/* Reserves `bytes` at the end of the file (opened on first use) and returns where. Under the
 * lock; the caller writes them with file_write once it has let go of it, so that the threads
 * never wait on each other's disk writes. */
static int file_reserve(struct vt_block_cache *c, uint32_t bytes, uint64_t *off,
                        struct vts_error *err)
{
    if (c->fd < 0 && open_file(c, err))
        return err ? err->status : VTS_ERR_IO;
    *off = c->file_end;
    c->file_end += bytes;
    c->spilled += bytes;
    return 0;
}

/* Writes a reserved range of the file. Outside the lock (fd is set before any range is
 * reserved and never changes afterwards). */
static int file_write(struct vt_block_cache *c, const void *data, uint32_t bytes, uint64_t off,
                      struct vts_error *err)
{
    const char *p = data;
    size_t left = bytes;
    while (left > 0) {
        ssize_t n = pwrite(c->fd, p, left, (off_t)off);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return vt_error_set(err, VTS_ERR_IO, "cannot write the temporary file in '%s': %s",
                                c->dir, n < 0 ? strerror(errno) : "disk full");
        p += n;
        off += (uint64_t)n;
        left -= (size_t)n;
    }
    return 0;
}

static int file_read(struct vt_block_cache *c, void *data, uint32_t bytes, uint64_t off,
                     struct vts_error *err)
{
    char *p = data;
    size_t left = bytes;
    while (left > 0) {
        ssize_t n = pread(c->fd, p, left, (off_t)off);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return vt_error_set(err, VTS_ERR_IO, "cannot read the temporary file in '%s': %s",
                                c->dir, n < 0 ? strerror(errno) : "truncated");
        p += n;
        off += (uint64_t)n;
        left -= (size_t)n;
    }
    return 0;
}

#define TRIM_EVERY ((uint64_t)32 << 20) /* block bytes freed between two trims */

/* Under the lock: whether this caller gives freed memory back to the system once it has let go
 * of the lock. Blocks of several sizes are freed and allocated in LRU order, so glibc keeps
 * their pages resident amid live blocks: at SCALE 1 of scripts/bench/layout-vs-vips that slack
 * reached 88 MiB (a third of the budget) during the texture pass. */
static bool trim_due(struct vt_block_cache *c)
{
    if (c->freed < TRIM_EVERY)
        return false;
    c->freed = 0;
    return true;
}

/* Returns the free pages inside malloc's heaps to the system (glibc: malloc_trim madvises them
 * away). Outside the lock. */
static void trim(bool due)
{
#if defined(__GLIBC__)
    if (due)
        malloc_trim(0);
#else
    (void)due;
#endif
}

/* Frees unreferenced blocks, oldest first, until `need` more bytes fit in the budget or none is
 * left. Under the lock, but it lets go of it while it writes the blocks not yet in the file:
 * those are taken off the LRU list under the lock (busy, their file range reserved, their bytes
 * counted in c->writing until freed, so that the budget holds), written outside it, then freed
 * under it again; and then it looks again, since other threads may have taken room meanwhile. */
static int make_room(struct vt_block_cache *c, uint64_t need, struct vts_error *err)
{
    for (;;) {
        struct vt_block_cache_node *chain = NULL;
        uint64_t mine = 0; /* bytes of the chain: the room this caller makes (others' writing
                            * bytes are the room they make for themselves) */
        int rc = 0;
        while (c->bytes + (c->writing - mine) + c->reserved + need > c->budget && c->lru_head) {
            struct vt_block_cache_node *n = c->lru_head;
            if (!n->in_file && (rc = file_reserve(c, n->bytes, &n->off, err)) != 0)
                break;
            lru_unlink(c, n);
            c->bytes -= n->bytes;
            if (n->in_file) {
                free(n->data);
                n->data = NULL;
                c->freed += n->bytes;
            } else {
                n->loading = true;
                c->writing += n->bytes;
                mine += n->bytes;
                n->next = chain;
                chain = n;
            }
        }
        if (!chain)
            return rc;
        pthread_mutex_unlock(&c->mu);
        for (struct vt_block_cache_node *n = chain; n && rc == 0; n = n->next)
            rc = file_write(c, n->data, n->bytes, n->off, err);
        pthread_mutex_lock(&c->mu);
        while (chain) {
            struct vt_block_cache_node *n = chain;
            chain = n->next;
            n->next = NULL;
            n->loading = false;
            c->writing -= n->bytes;
            if (rc == 0) { /* written: only in the file from now on */
                n->in_file = true;
                free(n->data);
                n->data = NULL;
                c->freed += n->bytes;
            } else { /* maybe not written: back in memory (its file range stays unused) */
                c->bytes += n->bytes;
                lru_push(c, n);
            }
        }
        pthread_cond_broadcast(&c->cv); /* readers waiting for these blocks */
        if (rc)
            return rc;
    }
}

int vt_block_cache_put(struct vt_block_cache *c, uint64_t id, const void *data, size_t bytes,
                       struct vts_error *err)
{
    assert(id < c->count && bytes > 0 && bytes <= UINT32_MAX);
    struct vt_block_cache_node *n = calloc(1, sizeof *n);
    if (!n)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a texture block");
    n->bytes = (uint32_t)bytes;
    pthread_mutex_lock(&c->mu);
    assert(!c->table[id]);
    int rc = make_room(c, bytes, err);
    if (rc == 0 && c->bytes + c->writing + c->reserved + bytes > c->budget) {
        /* all in memory is pinned or being written: straight to the file (outside the lock; no
         * other thread knows this block before it is in the table) */
        rc = file_reserve(c, n->bytes, &n->off, err);
        if (rc == 0) {
            pthread_mutex_unlock(&c->mu);
            rc = file_write(c, data, n->bytes, n->off, err);
            pthread_mutex_lock(&c->mu);
        }
        n->in_file = true;
    } else if (rc == 0) {
        n->data = malloc(bytes);
        if (!n->data) {
            rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a texture block");
        } else {
            memcpy(n->data, data, bytes);
            c->bytes += bytes;
            lru_push(c, n);
            note_peak(c);
        }
    }
    if (rc == 0)
        c->table[id] = n;
    else
        free(n);
    bool due = trim_due(c);
    pthread_mutex_unlock(&c->mu);
    trim(due);
    return rc;
}

void vt_block_cache_drop(struct vt_block_cache *c, uint64_t id)
{
    pthread_mutex_lock(&c->mu);
    struct vt_block_cache_node *n = c->table[id];
    while (n && n->loading)
        pthread_cond_wait(&c->cv, &c->mu); /* another thread is writing it out */
    if (n) {
        assert(n->refs == 0);
        if (n->data) {
            lru_unlink(c, n);
            c->bytes -= n->bytes;
            free(n->data);
        }
        free(n);
        c->table[id] = NULL;
    }
    pthread_mutex_unlock(&c->mu);
}

/* Block id referenced, in memory (read back from the file if it was spilled). */
static int acquire(struct vt_block_cache *c, uint64_t id, struct vt_block_cache_node **out,
                   struct vts_error *err)
{
    pthread_mutex_lock(&c->mu);
    struct vt_block_cache_node *n = c->table[id];
    assert(n);
    while (n->loading)
        pthread_cond_wait(&c->cv, &c->mu); /* another reader is reading it back */
    int rc = 0;
    if (n->data) {
        if (n->refs++ == 0) {
            lru_unlink(c, n);
            c->pinned += n->bytes;
        }
    } else {
        n->loading = true;
        rc = make_room(c, n->bytes, err);
        uint8_t *data = rc == 0 ? malloc(n->bytes) : NULL;
        if (rc == 0 && !data)
            rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a texture block");
        if (rc == 0) {
            c->bytes += n->bytes; /* counted (and pinned) from now on */
            c->pinned += n->bytes;
            note_peak(c);
            pthread_mutex_unlock(&c->mu);
            rc = file_read(c, data, n->bytes, n->off, err);
            pthread_mutex_lock(&c->mu);
            if (rc) {
                c->bytes -= n->bytes;
                c->pinned -= n->bytes;
                free(data);
            } else {
                n->data = data;
                n->refs = 1;
                c->reloads++;
            }
        }
        n->loading = false;
        pthread_cond_broadcast(&c->cv);
    }
    bool due = trim_due(c);
    pthread_mutex_unlock(&c->mu);
    trim(due);
    *out = n;
    return rc;
}

static void release(struct vt_block_cache *c, struct vt_block_cache_node *n)
{
    pthread_mutex_lock(&c->mu);
    if (--n->refs == 0) {
        c->pinned -= n->bytes;
        lru_push(c, n);
    }
    pthread_mutex_unlock(&c->mu);
}

void vt_block_cache_unpin_all(struct vt_block_cache *c, struct vt_block_cache_pins *p)
{
    for (uint32_t i = 0; i < p->count; i++)
        release(c, p->pins[i].node);
    p->count = 0;
    p->next = 0;
}

int vt_block_cache_get(struct vt_block_cache *c, struct vt_block_cache_pins *p, uint64_t id,
                       const uint8_t **out, struct vts_error *err)
{
    for (uint32_t i = 0; i < p->count; i++)
        if (p->pins[i].id == id) {
            *out = p->pins[i].node->data;
            return 0;
        }
    uint32_t i;
    if (p->count < VT_BLOCK_CACHE_PINS) {
        i = p->count++;
    } else { /* drop the oldest pin first, so that a reader never holds more than its share */
        i = p->next;
        p->next = (p->next + 1) % VT_BLOCK_CACHE_PINS;
        release(c, p->pins[i].node);
    }
    struct vt_block_cache_node *n = NULL;
    int rc = acquire(c, id, &n, err);
    if (rc) { /* the slot is free again: move the last pin into it */
        p->pins[i] = p->pins[--p->count];
        p->next = 0;
        return rc;
    }
    p->pins[i].id = id;
    p->pins[i].node = n;
    *out = n->data;
    return 0;
}

int vt_block_cache_reserve(struct vt_block_cache *c, uint64_t bytes, bool first,
                           struct vts_error *err)
{
    pthread_mutex_lock(&c->mu);
    while (first && c->reserved > 0 && c->reserved + bytes > c->budget / 2)
        pthread_cond_wait(&c->cv, &c->mu); /* the others' buffers first */
    c->reserved += bytes;
    if (c->reserved > c->peak_reserved)
        c->peak_reserved = c->reserved;
    uint64_t freed = c->freed;
    int rc = make_room(c, 0, err);
    /* the buffers take new memory: give back what made room for them at once */
    bool due = c->freed != freed ? (c->freed = 0, true) : trim_due(c);
    pthread_mutex_unlock(&c->mu);
    trim(due);
    return rc;
}

void vt_block_cache_unreserve(struct vt_block_cache *c, uint64_t bytes)
{
    pthread_mutex_lock(&c->mu);
    assert(bytes <= c->reserved);
    c->reserved -= bytes;
    pthread_cond_broadcast(&c->cv);
    pthread_mutex_unlock(&c->mu);
}

void vt_block_cache_stats(struct vt_block_cache *c, struct vt_block_cache_stats *out)
{
    pthread_mutex_lock(&c->mu);
    *out = (struct vt_block_cache_stats){c->budget,  c->bytes,   c->peak,         c->peak_unpinned,
                                         c->spilled, c->reloads, c->peak_reserved};
    pthread_mutex_unlock(&c->mu);
}

struct vt_block_cache *vt_block_cache_create(uint64_t block_count, uint64_t budget_bytes,
                                             const char *temp_dir, struct vts_error *err)
{
    struct vt_block_cache *c = calloc(1, sizeof *c);
    if (!c || block_count > SIZE_MAX / sizeof *c->table ||
        !(c->table = calloc(block_count ? block_count : 1, sizeof *c->table))) {
        free(c);
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the texture block table");
        return NULL;
    }
    if (pthread_mutex_init(&c->mu, NULL) || pthread_cond_init(&c->cv, NULL)) {
        free(c->table);
        free(c);
        vt_error_set(err, VTS_ERR_NOMEM, "cannot create a mutex");
        return NULL;
    }
    const char *dir = temp_dir ? temp_dir : getenv("TMPDIR");
    snprintf(c->dir, sizeof c->dir, "%s", dir && *dir ? dir : "/tmp");
    c->count = block_count;
    c->budget = budget_bytes;
    c->fd = -1;
    return c;
}

void vt_block_cache_destroy(struct vt_block_cache *c)
{
    if (!c)
        return;
    for (uint64_t i = 0; i < c->count; i++)
        if (c->table[i]) {
            free(c->table[i]->data);
            free(c->table[i]);
        }
    if (c->fd >= 0)
        close(c->fd);
    pthread_mutex_destroy(&c->mu);
    pthread_cond_destroy(&c->cv);
    free(c->table);
    free(c);
}
