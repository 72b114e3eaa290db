/* .vts writer. Payloads arrive in any order from any thread and are appended, deduplicated, to a
 * hidden spool file next to the output, through a buffer written SPOOL_BUFFER bytes at a time (a
 * write per tile costs the kernel more than the copy: partial file-system blocks zeroed, the
 * inode lock taken per call). finish() lays out header, layer table, index, metadata and
 * then copies the payloads from the spool in data order (coarse levels first, Hilbert order within
 * a level, the layers of a tile together) into a hidden temporary file, which is renamed onto the
 * output. Memory: 4 bytes per tile plus 32 bytes per distinct payload. */
#define _GNU_SOURCE /* pread/pwrite and friends */
#include "vts_writer.h"

#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "internal/vts_crc32c.h"
#include "internal/vts_format.h"
#include "internal/vts_order.h"
#include "vt_atomic_file.h"
#include "vt_checked.h"
#include "vt_error.h"

#define SLOT_UNSET       0u /* tile never put: stored as empty */
#define SLOT_EMPTY       1u /* tile put with no payload */
#define SLOT_FIRST       2u /* slot = SLOT_FIRST + payload record number */
#define NOT_PLACED       UINT64_MAX
#define DATA_ALIGN       64u
#define COPY_BUFFER      (4u << 20) /* spool bytes read at a time when laying out payloads */
#define SPOOL_BUFFER     (4u << 20) /* spool bytes written at a time (a multiple of the page size) */
#define DIRECT_ALIGN     4096u      /* block alignment of direct I/O (and of the output's pieces) */
#define DIRECT_MIN_BYTES (8u << 20) /* data sections from this size on are written directly */

struct payload_rec {
    uint64_t spool_off;
    uint64_t final_off; /* NOT_PLACED until finish() lays it out */
    uint32_t length;
    uint32_t crc;
    uint32_t next; /* hash chain: record number + 1, 0 ends */
};

struct meta_pair {
    char *key, *value;
};

struct vts_writer {
    struct vts_geometry geo;
    struct vts_layer layers[VTS_MAX_LAYERS];
    struct vts_level levels[VTS_MAX_LEVELS];
    uint64_t tiles_per_layer, tile_count;
    uint32_t *slots; /* one per index entry */

    pthread_mutex_t lock; /* guards everything below and the spool */
    struct payload_rec *recs;
    uint32_t rec_count, rec_cap;
    uint32_t *buckets; /* record number + 1, 0 = empty bucket */
    uint32_t bucket_mask;
    struct vt_atomic_file spool;
    uint64_t spool_end;     /* spool bytes appended, buffered ones included */
    unsigned char *pending; /* the spool bytes [spool_end - pending_len, spool_end), not written */
    size_t pending_len;
    struct vts_writer_stats stats;
    uint64_t max_payload_bytes; /* limit on unique payload bytes (vts_writer_set_max_bytes) */
    int failed;                 /* sticky status of a failed put */
    char fail_message[VTS_ERROR_MESSAGE_MAX]; /* its message, repeated by later puts */

    struct meta_pair *meta;
    uint32_t meta_count;
    struct vt_atomic_file out;
    int finished;
};

struct vts_writer *vts_writer_create(const char *path, const struct vts_geometry *g,
                                     const struct vts_layer *layers, struct vts_error *err)
{
    struct vts_error gerr;
    if (vts_geometry_check(g, &gerr) != 0) {
        vt_error_set(err, gerr.status, "cannot write '%s': %s", path, gerr.message);
        return NULL;
    }
    for (uint32_t i = 0; i < g->layer_count; i++) {
        const struct vts_layer *L = &layers[i];
        if (L->channels < 1 || L->channels > 4 || vts_sample_bytes(L->sample) == 0 ||
            L->colour < VTS_COLOUR_SRGB || L->colour > VTS_COLOUR_DATA ||
            memchr(L->name, '\0', VTS_LAYER_NAME_BYTES) == NULL) {
            vt_error_set(err, VTS_ERR_ARG, "cannot write '%s': layer %u is invalid", path, i);
            return NULL;
        }
    }
    struct vts_writer *w = calloc(1, sizeof *w);
    if (!w) {
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory writing '%s'", path);
        return NULL;
    }
    w->spool.fd = w->out.fd = -1;
    w->geo = *g;
    memcpy(w->layers, layers, g->layer_count * sizeof *layers);
    for (uint32_t l = 0; l < g->level_count; l++)
        vts_geometry_level(g, l, &w->levels[l]);
    w->tiles_per_layer = vts_geometry_tiles_per_layer(g);
    w->tile_count = w->tiles_per_layer * g->layer_count;
    w->bucket_mask = 1023;
    pthread_mutex_init(&w->lock, NULL);
    size_t slot_bytes;
    if (!vt_size_mul((size_t)w->tile_count, sizeof *w->slots, &slot_bytes) ||
        !(w->slots = calloc(1, slot_bytes)) ||
        !(w->buckets = calloc(w->bucket_mask + 1, sizeof *w->buckets)) ||
        !(w->pending = malloc(SPOOL_BUFFER))) {
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the index of '%s' (%llu tiles)", path,
                     (unsigned long long)w->tile_count);
        goto fail;
    }
    if (vt_atomic_file_create_scratch(&w->spool, path, err) != 0)
        goto fail;
    return w;
fail:
    vts_writer_destroy(w);
    return NULL;
}

static uint32_t bucket_of(const struct vts_writer *w, uint32_t crc, uint32_t length)
{
    return (crc ^ (length * 0x9E3779B9u)) & w->bucket_mask;
}

static int grow_buckets(struct vts_writer *w)
{
    uint32_t mask = w->bucket_mask * 2 + 1;
    uint32_t *b = calloc((size_t)mask + 1, sizeof *b);
    if (!b)
        return VTS_ERR_NOMEM;
    free(w->buckets);
    w->buckets = b;
    w->bucket_mask = mask;
    for (uint32_t i = 0; i < w->rec_count; i++) {
        uint32_t k = bucket_of(w, w->recs[i].crc, w->recs[i].length);
        w->recs[i].next = b[k];
        b[k] = i + 1;
    }
    return 0;
}

/* Reads [off, off + len) of the spool into buf: the part already written from the file, the rest
 * from the pending buffer. Called with the lock held (or after the puts). */
static int read_spool(struct vts_writer *w, unsigned char *buf, uint64_t off, size_t len,
                      struct vts_error *err)
{
    uint64_t written = w->spool_end - w->pending_len;
    size_t from_file = off >= written ? 0 : (size_t)(written - off < len ? written - off : len);
    for (size_t done = 0; done < from_file;) {
        ssize_t n = pread(w->spool.fd, buf + done, from_file - done, (off_t)(off + done));
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return vt_error_set(err, VTS_ERR_IO, "cannot read back the spool of '%s': %s",
                                w->spool.final_path, n < 0 ? strerror(errno) : "short read");
        done += (size_t)n;
    }
    if (from_file < len)
        memcpy(buf + from_file, w->pending + (off + from_file - written), len - from_file);
    return 0;
}

/* Writes the pending spool bytes. Called with the lock held. */
static int flush_spool(struct vts_writer *w, struct vts_error *err)
{
    int rc = vt_atomic_file_pwrite(&w->spool, w->pending, w->pending_len,
                                   w->spool_end - w->pending_len, err);
    if (rc == 0)
        w->pending_len = 0;
    return rc;
}

/* Appends len bytes to the spool, writing the buffer each time it is full (whole buffers at
 * multiples of its size: page-aligned writes). Called with the lock held. */
static int append_spool(struct vts_writer *w, const unsigned char *payload, size_t len,
                        struct vts_error *err)
{
    while (len > 0) {
        size_t n = SPOOL_BUFFER - w->pending_len < len ? SPOOL_BUFFER - w->pending_len : len;
        memcpy(w->pending + w->pending_len, payload, n);
        w->pending_len += n;
        w->spool_end += n;
        payload += n;
        len -= n;
        if (w->pending_len == SPOOL_BUFFER) {
            int rc = flush_spool(w, err);
            if (rc)
                return rc;
        }
    }
    return 0;
}

/* Returns true when the spooled payload of rec equals payload (read back to compare bytes). */
static int spooled_equals(struct vts_writer *w, const struct payload_rec *rec, const void *payload,
                          bool *equal, struct vts_error *err)
{
    unsigned char *buf = malloc(rec->length);
    if (!buf)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory comparing tiles");
    int rc = read_spool(w, buf, rec->spool_off, rec->length, err);
    *equal = rc == 0 && memcmp(buf, payload, rec->length) == 0;
    free(buf);
    return rc;
}

/* Finds an identical spooled payload or appends this one. Called with the lock held. */
static int store_payload(struct vts_writer *w, const void *payload, uint32_t length, uint32_t crc,
                         uint32_t *rec_out, bool *shared, struct vts_error *err)
{
    for (uint32_t r = w->buckets[bucket_of(w, crc, length)]; r; r = w->recs[r - 1].next) {
        const struct payload_rec *rec = &w->recs[r - 1];
        bool equal = false;
        if (rec->crc != crc || rec->length != length)
            continue;
        int rc = spooled_equals(w, rec, payload, &equal, err);
        if (rc)
            return rc;
        if (equal) {
            *rec_out = r - 1;
            *shared = true;
            return 0;
        }
    }
    if (w->rec_count == w->rec_cap) {
        uint32_t cap = w->rec_cap ? w->rec_cap * 2 : 1024;
        if (cap > UINT32_MAX - SLOT_FIRST - 1)
            return vt_error_set(err, VTS_ERR_LIMIT, "too many distinct tiles for '%s'",
                                w->spool.final_path);
        struct payload_rec *recs = realloc(w->recs, (size_t)cap * sizeof *recs);
        if (!recs)
            return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for tile records");
        w->recs = recs;
        w->rec_cap = cap;
    }
    if (w->max_payload_bytes && w->stats.unique_bytes + length > w->max_payload_bytes)
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "'%s' would hold more than %llu bytes of tiles (the store size limit)",
                            w->spool.final_path, (unsigned long long)w->max_payload_bytes);
    uint64_t at = w->spool_end;
    int rc = append_spool(w, payload, length, err);
    if (rc)
        return rc;
    uint32_t k = bucket_of(w, crc, length);
    w->recs[w->rec_count] = (struct payload_rec){at, NOT_PLACED, length, crc, w->buckets[k]};
    w->buckets[k] = ++w->rec_count;
    w->stats.unique_bytes += length;
    *rec_out = w->rec_count - 1;
    *shared = false;
    if (w->rec_count > (w->bucket_mask + 1) / 4 * 3 && grow_buckets(w) != 0)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the tile hash table");
    return 0;
}

void vts_writer_set_max_bytes(struct vts_writer *w, uint64_t max_bytes)
{
    pthread_mutex_lock(&w->lock);
    w->max_payload_bytes = max_bytes;
    pthread_mutex_unlock(&w->lock);
}

int vts_writer_put(struct vts_writer *w, uint32_t layer, uint32_t level, uint32_t tx, uint32_t ty,
                   const void *payload, size_t payload_len, struct vts_error *err)
{
    if (layer >= w->geo.layer_count || level >= w->geo.level_count ||
        tx >= w->levels[level].tiles_x || ty >= w->levels[level].tiles_y)
        return vt_error_set(err, VTS_ERR_RANGE, "'%s' has no tile %u,%u at layer %u level %u",
                            w->spool.final_path, tx, ty, layer, level);
    if (payload_len > UINT32_MAX)
        return vt_error_set(err, VTS_ERR_LIMIT, "tile %u,%u of level %u is %zu bytes (limit 4 GiB)",
                            tx, ty, level, payload_len);
    const struct vts_level *L = &w->levels[level];
    uint64_t idx = layer * w->tiles_per_layer + L->first_tile + (uint64_t)ty * L->tiles_x + tx;
    uint32_t crc = payload_len ? vts_crc32c(0, payload, payload_len) : 0;

    pthread_mutex_lock(&w->lock);
    int rc = w->failed;
    if (rc) {
        vt_error_set(err, rc, "%s", w->fail_message);
    } else if (w->slots[idx] != SLOT_UNSET) {
        rc = vt_error_set(err, VTS_ERR_ARG, "tile %u,%u of layer %u level %u was put twice", tx, ty,
                          layer, level);
    } else if (payload_len == 0) {
        w->slots[idx] = SLOT_EMPTY;
        w->stats.tiles_empty++;
    } else {
        uint32_t rec = 0;
        bool shared = false;
        rc = store_payload(w, payload, (uint32_t)payload_len, crc, &rec, &shared, err);
        if (rc == 0) {
            w->slots[idx] = SLOT_FIRST + rec;
            w->stats.tiles_stored++;
            w->stats.tiles_shared += shared;
        } else if (rc == VTS_ERR_IO || rc == VTS_ERR_NOMEM || rc == VTS_ERR_LIMIT) {
            w->failed = rc;
            snprintf(w->fail_message, sizeof w->fail_message, "%s",
                     err ? err->message : "a tile failed to write");
        }
    }
    pthread_mutex_unlock(&w->lock);
    return rc;
}

int vts_writer_set_meta(struct vts_writer *w, const char *key, const char *value,
                        struct vts_error *err)
{
    size_t klen = strlen(key);
    bool ok = klen > 0 && klen <= VTS_MAX_KEY_BYTES;
    for (size_t i = 0; ok && i < klen; i++)
        ok = key[i] > ' ' && key[i] < 0x7f && key[i] != '=';
    if (!ok)
        return vt_error_set(err, VTS_ERR_ARG, "invalid metadata key '%s'", key);
    for (uint32_t i = 0; i < w->meta_count; i++) {
        if (strcmp(w->meta[i].key, key) == 0) {
            char *v = strdup(value);
            if (!v)
                return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for metadata");
            free(w->meta[i].value);
            w->meta[i].value = v;
            return 0;
        }
    }
    if (w->meta_count >= VTS_MAX_META_ENTRIES)
        return vt_error_set(err, VTS_ERR_LIMIT, "more than %u metadata entries",
                            VTS_MAX_META_ENTRIES);
    struct meta_pair *m = realloc(w->meta, (w->meta_count + 1) * sizeof *m);
    if (!m)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for metadata");
    w->meta = m;
    m[w->meta_count].key = strdup(key);
    m[w->meta_count].value = strdup(value);
    if (!m[w->meta_count].key || !m[w->meta_count].value) {
        free(m[w->meta_count].key);
        free(m[w->meta_count].value);
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for metadata");
    }
    w->meta_count++;
    return 0;
}

void vts_writer_stats(struct vts_writer *w, struct vts_writer_stats *out)
{
    pthread_mutex_lock(&w->lock);
    *out = w->stats;
    pthread_mutex_unlock(&w->lock);
}

void vts_writer_destroy(struct vts_writer *w)
{
    if (!w)
        return;
    vt_atomic_file_abort(&w->spool);
    vt_atomic_file_abort(&w->out);
    pthread_mutex_destroy(&w->lock);
    for (uint32_t i = 0; i < w->meta_count; i++) {
        free(w->meta[i].key);
        free(w->meta[i].value);
    }
    free(w->meta);
    free(w->slots);
    free(w->recs);
    free(w->buckets);
    free(w->pending);
    free(w);
}

/* ---- finish: lay out and write the final file ---- */

struct copy_run {
    uint64_t src, dst, len;
};

struct layout {
    uint64_t layer_off, index_off, meta_off, data_off, data_size;
    uint32_t meta_size;
    struct copy_run *runs;
    uint64_t run_count, run_cap;
};

static int add_copy(struct layout *lay, uint64_t src, uint64_t dst, uint64_t len)
{
    struct copy_run *last = lay->run_count ? &lay->runs[lay->run_count - 1] : NULL;
    if (last && last->src + last->len == src && last->dst + last->len == dst) {
        last->len += len; /* spool and output both contiguous: one bigger copy */
        return 0;
    }
    if (lay->run_count == lay->run_cap) {
        uint64_t cap = lay->run_cap ? lay->run_cap * 2 : 256;
        struct copy_run *r = realloc(lay->runs, (size_t)cap * sizeof *r);
        if (!r)
            return VTS_ERR_NOMEM;
        lay->runs = r;
        lay->run_cap = cap;
    }
    lay->runs[lay->run_count++] = (struct copy_run){src, dst, len};
    return 0;
}

/* Assigns final offsets in data order: coarse levels first, Hilbert order within a level, the
 * layers of one tile next to each other; a shared payload sits where it is first needed. */
static int place_payloads(struct vts_writer *w, struct layout *lay, struct vts_error *err)
{
    const struct vts_level *L0 = &w->levels[0];
    uint64_t *order = malloc((size_t)L0->tiles_x * L0->tiles_y * sizeof *order);
    if (!order)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory ordering tiles");
    uint64_t cursor = lay->data_off;
    int rc = 0;
    for (uint32_t level = w->geo.level_count; level-- > 0 && rc == 0;) {
        const struct vts_level *L = &w->levels[level];
        rc = vts_order_level(L->tiles_x, L->tiles_y, order, err);
        for (uint64_t i = 0; rc == 0 && i < (uint64_t)L->tiles_x * L->tiles_y; i++) {
            for (uint32_t layer = 0; layer < w->geo.layer_count && rc == 0; layer++) {
                uint32_t slot = w->slots[layer * w->tiles_per_layer + L->first_tile + order[i]];
                if (slot < SLOT_FIRST || w->recs[slot - SLOT_FIRST].final_off != NOT_PLACED)
                    continue;
                struct payload_rec *rec = &w->recs[slot - SLOT_FIRST];
                rec->final_off = cursor;
                if (add_copy(lay, rec->spool_off, cursor, rec->length) != 0)
                    rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory laying out tiles");
                cursor += rec->length;
            }
        }
    }
    free(order);
    lay->data_size = cursor - lay->data_off;
    return rc;
}

/* Direct I/O for the data section of a large store: the output's pages never enter the page
 * cache (allocating them and writing them back cost more than the copy itself), so the final
 * fsync has only the head left. Only for a regular file that accepts O_DIRECT. */
static bool direct_begin(struct vts_writer *w, const struct layout *lay, int *flags)
{
#ifdef O_DIRECT
    if (w->out.mode != VT_ATOMIC_FILE_RENAME || lay->data_size < DIRECT_MIN_BYTES)
        return false;
    *flags = fcntl(w->out.fd, F_GETFL);
    return *flags >= 0 && fcntl(w->out.fd, F_SETFL, *flags | O_DIRECT) == 0;
#else
    (void)w, (void)lay, (void)flags;
    return false;
#endif
}

/* Writes the len bytes of buf (a piece of the data section) at off: directly when *direct (len
 * rounded up to whole blocks with zeros past it: buf has room, and the file is cut back to its
 * size at the end), else buffered and handed to writeback at once. A file system that refuses
 * the direct write gets it buffered, and so do the rest. */
static int write_piece(struct vts_writer *w, unsigned char *buf, size_t len, uint64_t off,
                       bool *direct, int flags, struct vts_error *err)
{
    if (*direct) {
        size_t whole = (len + DIRECT_ALIGN - 1) / DIRECT_ALIGN * DIRECT_ALIGN;
        memset(buf + len, 0, whole - len);
        size_t done = 0;
        while (done < whole) {
            ssize_t n = pwrite(w->out.fd, buf + done, whole - done, (off_t)(off + done));
            if (n < 0 && errno == EINTR)
                continue;
            if (n <= 0 || (size_t)n % DIRECT_ALIGN != 0)
                break;
            done += (size_t)n;
        }
        if (done == whole)
            return 0;
        *direct = false; /* the rest of this piece and all after it, buffered */
        fcntl(w->out.fd, F_SETFL, flags);
        buf += done;
        off += done;
        len = done < len ? len - done : 0;
    }
    int rc = vt_atomic_file_pwrite(&w->out, buf, len, off, err);
#ifdef SYNC_FILE_RANGE_WRITE
    if (rc == 0)
        sync_file_range(w->out.fd, (off_t)off, (off_t)len, SYNC_FILE_RANGE_WRITE);
#endif
    return rc;
}

/* Writes the data section [lay->data_off, + data_size) front to back: each run is read from the
 * spool (its page cache, or the pending buffer) into an output buffer that is written whenever it
 * reaches a block boundary COPY_BUFFER bytes on: large aligned writes in file order (one write
 * per tile at scattered offsets made the kernel zero partial blocks and allocate them piecemeal).
 * With direct I/O the buffer starts at the block holding data_off, with the head's bytes before
 * it read back. */
static int copy_payloads(struct vts_writer *w, struct layout *lay, struct vts_error *err)
{
    if (lay->run_count == 0)
        return 0;
    unsigned char *buf = aligned_alloc(DIRECT_ALIGN, COPY_BUFFER);
    if (!buf)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory copying tiles");
    int flags = 0, rc = 0;
    /* the head's bytes in the block holding data_off, read before the descriptor goes direct
     * (zeros past what was written: the alignment padding) */
    uint64_t start = lay->data_off / DIRECT_ALIGN * DIRECT_ALIGN, fill = lay->data_off - start;
    memset(buf, 0, (size_t)fill);
    ssize_t got = pread(w->out.fd, buf, (size_t)fill, (off_t)start);
    bool direct = got >= 0 && direct_begin(w, lay, &flags);
    if (!direct) {
        start = lay->data_off;
        fill = 0;
    }
    uint64_t limit = (start + COPY_BUFFER) / DIRECT_ALIGN * DIRECT_ALIGN - start;
    for (uint64_t i = 0; i < lay->run_count && rc == 0; i++) {
        uint64_t src = lay->runs[i].src, left = lay->runs[i].len;
        if (lay->runs[i].dst != start + fill || src + left > w->spool_end) {
            rc = vt_error_set(err, VTS_ERR_ARG, "payload run out of place in '%s'",
                              w->out.final_path);
            break;
        }
        while (left > 0 && rc == 0) {
            size_t n = (size_t)(limit - fill < left ? limit - fill : left);
            rc = read_spool(w, buf + fill, src, n, err);
            src += n;
            left -= n;
            fill += n;
            if (rc == 0 && (fill == limit || (left == 0 && i + 1 == lay->run_count))) {
                rc = write_piece(w, buf, (size_t)fill, start, &direct, flags, err);
                start += fill;
                fill = 0;
                limit = COPY_BUFFER;
            }
        }
    }
    if (direct) {
        fcntl(w->out.fd, F_SETFL, flags);
        if (rc == 0 && ftruncate(w->out.fd, (off_t)(lay->data_off + lay->data_size)) != 0)
            rc = vt_error_set(err, VTS_ERR_IO, "cannot write '%s': %s", w->out.final_path,
                              strerror(errno));
    }
    free(buf);
    return rc;
}

static uint32_t meta_bytes(const struct vts_writer *w)
{
    uint64_t n = 4;
    for (uint32_t i = 0; i < w->meta_count; i++)
        n += 8 + strlen(w->meta[i].key) + strlen(w->meta[i].value);
    return n > VTS_MAX_META_BYTES ? 0 : (uint32_t)n;
}

static int write_layers_and_meta(struct vts_writer *w, const struct layout *lay,
                                 uint32_t *layers_crc, uint32_t *meta_crc, struct vts_error *err)
{
    unsigned char lt[VTS_MAX_LAYERS * VTS_LAYER_ENTRY_SIZE];
    memset(lt, 0, sizeof lt);
    for (uint32_t i = 0; i < w->geo.layer_count; i++) {
        unsigned char *e = lt + i * VTS_LAYER_ENTRY_SIZE;
        const struct vts_layer *L = &w->layers[i];
        vts_store_u32(e + VTS_L_CODEC, L->codec);
        e[VTS_L_CHANNELS] = L->channels;
        e[VTS_L_SAMPLE] = L->sample;
        e[VTS_L_COLOUR] = L->colour;
        e[VTS_L_FLAGS] = L->flags;
        vts_store_u32(e + VTS_L_PARAM, L->codec_param);
        strncpy((char *)e + VTS_L_NAME, L->name, VTS_LAYER_NAME_BYTES - 1);
    }
    size_t lt_size = (size_t)w->geo.layer_count * VTS_LAYER_ENTRY_SIZE;
    *layers_crc = vts_crc32c(0, lt, lt_size);
    int rc = vt_atomic_file_pwrite(&w->out, lt, lt_size, lay->layer_off, err);
    if (rc)
        return rc;
    unsigned char *m = malloc(lay->meta_size);
    if (!m)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for metadata");
    vts_store_u32(m, w->meta_count);
    size_t pos = 4;
    for (uint32_t i = 0; i < w->meta_count; i++) {
        size_t kl = strlen(w->meta[i].key), vl = strlen(w->meta[i].value);
        vts_store_u32(m + pos, (uint32_t)kl);
        vts_store_u32(m + pos + 4, (uint32_t)vl);
        memcpy(m + pos + 8, w->meta[i].key, kl);
        memcpy(m + pos + 8 + kl, w->meta[i].value, vl);
        pos += 8 + kl + vl;
    }
    *meta_crc = vts_crc32c(0, m, lay->meta_size);
    rc = vt_atomic_file_pwrite(&w->out, m, lay->meta_size, lay->meta_off, err);
    free(m);
    return rc;
}

static int write_index(struct vts_writer *w, const struct layout *lay, uint32_t *crc,
                       struct vts_error *err)
{
    enum { CHUNK = 65536 };
    unsigned char *buf = malloc((size_t)CHUNK * VTS_INDEX_ENTRY_SIZE);
    if (!buf)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory writing the index");
    *crc = 0;
    int rc = 0;
    for (uint64_t first = 0; first < w->tile_count && rc == 0; first += CHUNK) {
        uint64_t n = w->tile_count - first < CHUNK ? w->tile_count - first : CHUNK;
        memset(buf, 0, (size_t)n * VTS_INDEX_ENTRY_SIZE);
        for (uint64_t k = 0; k < n; k++) {
            uint32_t slot = w->slots[first + k];
            if (slot < SLOT_FIRST)
                continue;
            const struct payload_rec *rec = &w->recs[slot - SLOT_FIRST];
            unsigned char *e = buf + k * VTS_INDEX_ENTRY_SIZE;
            vts_store_u64(e, rec->final_off);
            vts_store_u32(e + 8, rec->length);
            vts_store_u32(e + 12, rec->crc);
        }
        *crc = vts_crc32c(*crc, buf, (size_t)n * VTS_INDEX_ENTRY_SIZE);
        rc = vt_atomic_file_pwrite(&w->out, buf, (size_t)n * VTS_INDEX_ENTRY_SIZE,
                                   lay->index_off + first * VTS_INDEX_ENTRY_SIZE, err);
    }
    free(buf);
    return rc;
}

static int write_header(struct vts_writer *w, const struct layout *lay, uint32_t layers_crc,
                        uint32_t index_crc, uint32_t meta_crc, struct vts_error *err)
{
    unsigned char h[VTS_HEADER_SIZE];
    memset(h, 0, sizeof h);
    memcpy(h + VTS_H_MAGIC, VTS_MAGIC, VTS_MAGIC_SIZE);
    vts_store_u16(h + VTS_H_MAJOR, VTS_FORMAT_MAJOR);
    vts_store_u16(h + VTS_H_MINOR, VTS_FORMAT_MINOR);
    vts_store_u32(h + VTS_H_HEADER_SIZE, VTS_HEADER_SIZE);
    vts_store_u32(h + VTS_H_WIDTH, w->geo.width);
    vts_store_u32(h + VTS_H_HEIGHT, w->geo.height);
    vts_store_u32(h + VTS_H_CONTENT, w->geo.tile_content_px);
    vts_store_u32(h + VTS_H_BORDER, w->geo.border_px);
    vts_store_u32(h + VTS_H_PAYLOAD, w->geo.tile_payload_px);
    vts_store_u32(h + VTS_H_LEVELS, w->geo.level_count);
    vts_store_u32(h + VTS_H_LAYERS, w->geo.layer_count);
    vts_store_u32(h + VTS_H_FLAGS, w->geo.flags);
    vts_store_u64(h + VTS_H_LAYER_OFFSET, lay->layer_off);
    vts_store_u32(h + VTS_H_LAYER_ENTRY, VTS_LAYER_ENTRY_SIZE);
    vts_store_u32(h + VTS_H_INDEX_ENTRY, VTS_INDEX_ENTRY_SIZE);
    vts_store_u64(h + VTS_H_INDEX_OFFSET, lay->index_off);
    vts_store_u64(h + VTS_H_INDEX_COUNT, w->tile_count);
    vts_store_u64(h + VTS_H_DATA_OFFSET, lay->data_off);
    vts_store_u64(h + VTS_H_DATA_SIZE, lay->data_size);
    vts_store_u64(h + VTS_H_META_OFFSET, lay->meta_off);
    vts_store_u32(h + VTS_H_META_SIZE, lay->meta_size);
    vts_store_u32(h + VTS_H_LAYERS_CRC, layers_crc);
    vts_store_u32(h + VTS_H_INDEX_CRC, index_crc);
    vts_store_u32(h + VTS_H_META_CRC, meta_crc);
    vts_store_u32(h + VTS_H_HEADER_CRC, vts_crc32c(0, h, VTS_H_HEADER_CRC));
    return vt_atomic_file_pwrite(&w->out, h, sizeof h, 0, err);
}

int vts_writer_finish(struct vts_writer *w, struct vts_error *err)
{
    if (w->finished)
        return vt_error_set(err, VTS_ERR_ARG, "'%s' is already finished", w->spool.final_path);
    w->finished = 1;
    if (w->failed)
        return vt_error_set(err, w->failed, "%s", w->fail_message);
    struct layout lay = {0};
    lay.meta_size = meta_bytes(w);
    if (lay.meta_size == 0)
        return vt_error_set(err, VTS_ERR_LIMIT, "metadata of '%s' exceeds %u bytes",
                            w->spool.final_path, VTS_MAX_META_BYTES);
    lay.layer_off = VTS_HEADER_SIZE;
    lay.index_off = lay.layer_off + (uint64_t)w->geo.layer_count * VTS_LAYER_ENTRY_SIZE;
    lay.meta_off = lay.index_off + w->tile_count * VTS_INDEX_ENTRY_SIZE;
    lay.data_off = (lay.meta_off + lay.meta_size + DATA_ALIGN - 1) / DATA_ALIGN * DATA_ALIGN;
    uint32_t layers_crc = 0, index_crc = 0, meta_crc = 0;
    int rc = place_payloads(w, &lay, err);
    if (lay.data_size == 0)
        lay.data_off = lay.meta_off + lay.meta_size; /* no payload: the file ends with metadata */
    if (rc == 0)
        rc = vt_atomic_file_create(&w->out, w->spool.final_path, "tmp", 0, err);
    if (rc == 0)
        rc = write_layers_and_meta(w, &lay, &layers_crc, &meta_crc, err);
    if (rc == 0)
        rc = write_index(w, &lay, &index_crc, err);
    if (rc == 0)
        rc = flush_spool(w, err);
    if (rc == 0)
        rc = copy_payloads(w, &lay, err);
    if (rc == 0)
        rc = write_header(w, &lay, layers_crc, index_crc, meta_crc, err);
    free(lay.runs);
    if (rc == 0)
        rc = vt_atomic_file_commit(&w->out, err);
    vt_atomic_file_abort(&w->out);
    vt_atomic_file_abort(&w->spool);
    return rc;
}
