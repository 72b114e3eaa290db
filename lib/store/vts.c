/* libvts reader: opens a store without trusting it. Every offset, length and count is checked
 * (overflow included) at open; afterwards tile reads are one pread each, safe from many threads. */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "internal/vts_crc32c.h"
#include "internal/vts_format.h"
#include "vt_checked.h"
#include "vt_error.h"
#include "vts.h"

#define INDEX_CHUNK_ENTRIES 65536u
#define MAX_ENTRY_SIZE      4096u /* layer / index entry stride a reader accepts (1.0: 48 / 16) */

struct vts_store {
    int fd;                   /* -1 for a memory store */
    const unsigned char *mem; /* memory image, or NULL */
    uint64_t file_size;
    char name[512];
    unsigned major, minor;
    struct vts_geometry geo;
    struct vts_layer *layers;
    struct vts_level levels[VTS_MAX_LEVELS];
    uint64_t tiles_per_layer;
    uint64_t tile_count;
    struct vts_tile_entry *entries;
    uint32_t max_payload;
    uint32_t meta_count;
    char *meta_block; /* keys and values, each NUL-terminated */
    const char **meta_keys;
    const char **meta_values;
};

/* Reads exactly len bytes at off; a short read means the file ends early (VTS_ERR_CORRUPT). */
static int read_at(const struct vts_store *s, void *buf, size_t len, uint64_t off, const char *what,
                   struct vts_error *err)
{
    if (!vt_range_within(off, len, s->file_size))
        return vt_error_set(err, VTS_ERR_CORRUPT,
                            "'%s': %s is truncated (needs bytes %llu..%llu, file has %llu)",
                            s->name, what, (unsigned long long)off, (unsigned long long)(off + len),
                            (unsigned long long)s->file_size);
    if (s->mem) {
        memcpy(buf, s->mem + off, len);
        return 0;
    }
    unsigned char *p = buf;
    while (len > 0) {
        ssize_t n = pread(s->fd, p, len, (off_t)off);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            return vt_error_set(err, VTS_ERR_IO, "cannot read %s of '%s': %s", what, s->name,
                                strerror(errno));
        if (n == 0)
            return vt_error_set(err, VTS_ERR_CORRUPT, "'%s': %s is truncated at byte %llu", s->name,
                                what, (unsigned long long)off);
        p += n;
        len -= (size_t)n;
        off += (uint64_t)n;
    }
    return 0;
}

/* Locates index position i: layer, level and tile coordinates (for messages). */
static void entry_position(const struct vts_store *s, uint64_t i, uint32_t *layer, uint32_t *level,
                           uint32_t *tx, uint32_t *ty)
{
    *layer = (uint32_t)(i / s->tiles_per_layer);
    uint64_t r = i % s->tiles_per_layer;
    uint32_t l = 0;
    while (l + 1 < s->geo.level_count && s->levels[l + 1].first_tile <= r)
        l++;
    r -= s->levels[l].first_tile;
    *level = l;
    *tx = (uint32_t)(r % s->levels[l].tiles_x);
    *ty = (uint32_t)(r / s->levels[l].tiles_x);
}

struct region {
    uint64_t off, size;
    const char *what;
};

static int check_regions(const struct vts_store *s, struct region *r, int n, uint64_t header_size,
                         struct vts_error *err)
{
    for (int i = 0; i < n; i++) {
        if (!vt_range_within(r[i].off, r[i].size, s->file_size))
            return vt_error_set(
                err, VTS_ERR_CORRUPT,
                "'%s': %s (bytes %llu + %llu) lies past the end of the file (%llu bytes)", s->name,
                r[i].what, (unsigned long long)r[i].off, (unsigned long long)r[i].size,
                (unsigned long long)s->file_size);
        if (r[i].size > 0 && r[i].off < header_size)
            return vt_error_set(err, VTS_ERR_CORRUPT, "'%s': %s overlaps the header", s->name,
                                r[i].what);
        for (int j = 0; j < i; j++)
            if (r[i].size > 0 && r[j].size > 0 && r[i].off < r[j].off + r[j].size &&
                r[j].off < r[i].off + r[i].size)
                return vt_error_set(err, VTS_ERR_CORRUPT, "'%s': %s overlaps the %s", s->name,
                                    r[i].what, r[j].what);
    }
    return 0;
}

static int parse_layers(struct vts_store *s, uint64_t off, uint32_t entry_size, uint32_t crc,
                        struct vts_error *err)
{
    size_t bytes = (size_t)s->geo.layer_count * entry_size; /* <= 64 * 4096 */
    unsigned char *buf = malloc(bytes);
    s->layers = calloc(s->geo.layer_count, sizeof *s->layers);
    int rc = 0;
    if (!buf || !s->layers) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory reading '%s'", s->name);
        goto out;
    }
    rc = read_at(s, buf, bytes, off, "layer table", err);
    if (rc)
        goto out;
    if (vts_crc32c(0, buf, bytes) != crc) {
        rc = vt_error_set(err, VTS_ERR_CHECKSUM, "'%s': layer table checksum mismatch", s->name);
        goto out;
    }
    for (uint32_t i = 0; i < s->geo.layer_count; i++) {
        const unsigned char *e = buf + (size_t)i * entry_size;
        struct vts_layer *L = &s->layers[i];
        L->codec = vts_load_u32(e + VTS_L_CODEC);
        L->channels = e[VTS_L_CHANNELS];
        L->sample = e[VTS_L_SAMPLE];
        L->colour = e[VTS_L_COLOUR];
        L->flags = e[VTS_L_FLAGS];
        L->codec_param = vts_load_u32(e + VTS_L_PARAM);
        memcpy(L->name, e + VTS_L_NAME, VTS_LAYER_NAME_BYTES);
        if (L->channels < 1 || L->channels > 4 || vts_sample_bytes(L->sample) == 0 ||
            L->colour < VTS_COLOUR_SRGB || L->colour > VTS_COLOUR_DATA ||
            memchr(L->name, '\0', VTS_LAYER_NAME_BYTES) == NULL) {
            rc = vt_error_set(
                err, VTS_ERR_CORRUPT,
                "'%s': layer %u has an invalid description (%u channels, sample %u, colour %u)",
                s->name, i, L->channels, L->sample, L->colour);
            goto out;
        }
    }
out:
    free(buf);
    return rc;
}

static int check_entry(struct vts_store *s, uint64_t i, uint64_t data_off, uint64_t data_size,
                       struct vts_error *err)
{
    const struct vts_tile_entry *e = &s->entries[i];
    const char *why = NULL;
    if (e->length == 0 && (e->offset != 0 || e->crc32c != 0))
        why = "is empty but has an offset or checksum";
    else if (e->length > 0 &&
             (e->offset < data_off || !vt_range_within(e->offset - data_off, e->length, data_size)))
        why = "points outside the data region";
    if (!why)
        return 0;
    uint32_t layer, level, tx, ty;
    entry_position(s, i, &layer, &level, &tx, &ty);
    return vt_error_set(
        err, VTS_ERR_CORRUPT,
        "'%s': index entry of layer %u level %u tile %u,%u %s (offset %llu, length %u)", s->name,
        layer, level, tx, ty, why, (unsigned long long)e->offset, e->length);
}

static int parse_index(struct vts_store *s, uint64_t off, uint32_t entry_size, uint32_t crc,
                       uint64_t data_off, uint64_t data_size, struct vts_error *err)
{
    /* tile_count * 16 <= 2^36 by the geometry check, and the region was checked to lie inside
     * the file, so these allocations are bounded by the file size (the chunk too: never more
     * entries than the index holds, whatever the entry size). */
    s->entries = malloc((size_t)s->tile_count * sizeof *s->entries);
    uint64_t chunk_entries =
        s->tile_count < INDEX_CHUNK_ENTRIES ? s->tile_count : INDEX_CHUNK_ENTRIES;
    unsigned char *chunk = malloc((size_t)chunk_entries * entry_size);
    int rc = 0;
    if (!s->entries || !chunk) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the index of '%s'", s->name);
        goto out;
    }
    uint32_t running = 0;
    for (uint64_t first = 0; first < s->tile_count; first += INDEX_CHUNK_ENTRIES) {
        uint64_t n = s->tile_count - first < INDEX_CHUNK_ENTRIES ? s->tile_count - first
                                                                 : INDEX_CHUNK_ENTRIES;
        rc = read_at(s, chunk, (size_t)n * entry_size, off + first * entry_size, "tile index", err);
        if (rc)
            goto out;
        running = vts_crc32c(running, chunk, (size_t)n * entry_size);
        for (uint64_t k = 0; k < n; k++) {
            const unsigned char *p = chunk + k * entry_size;
            struct vts_tile_entry *e = &s->entries[first + k];
            e->offset = vts_load_u64(p);
            e->length = vts_load_u32(p + 8);
            e->crc32c = vts_load_u32(p + 12);
        }
    }
    if (running != crc) {
        rc = vt_error_set(err, VTS_ERR_CHECKSUM, "'%s': tile index checksum mismatch", s->name);
        goto out;
    }
    for (uint64_t i = 0; i < s->tile_count; i++) {
        rc = check_entry(s, i, data_off, data_size, err);
        if (rc)
            goto out;
        if (s->entries[i].length > s->max_payload)
            s->max_payload = s->entries[i].length;
    }
out:
    free(chunk);
    return rc;
}

static int compare_by_offset(const void *a, const void *b)
{
    const struct vts_tile_entry *x = *(const struct vts_tile_entry *const *)a;
    const struct vts_tile_entry *y = *(const struct vts_tile_entry *const *)b;
    return x->offset < y->offset ? -1 : x->offset > y->offset;
}

/* Payloads may be shared (same offset, length and CRC) but never partly overlap. */
static int check_overlaps(struct vts_store *s, struct vts_error *err)
{
    uint64_t n = 0;
    for (uint64_t i = 0; i < s->tile_count; i++)
        n += s->entries[i].length > 0;
    if (n < 2)
        return 0;
    const struct vts_tile_entry **sorted = malloc((size_t)n * sizeof *sorted);
    if (!sorted)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory checking '%s'", s->name);
    n = 0;
    for (uint64_t i = 0; i < s->tile_count; i++)
        if (s->entries[i].length > 0)
            sorted[n++] = &s->entries[i];
    qsort(sorted, (size_t)n, sizeof *sorted, compare_by_offset);
    int rc = 0;
    for (uint64_t k = 1; k < n && rc == 0; k++) {
        const struct vts_tile_entry *a = sorted[k - 1], *b = sorted[k];
        bool shared = a->offset == b->offset && a->length == b->length && a->crc32c == b->crc32c;
        if (!shared && a->offset + a->length > b->offset) {
            uint32_t layer, level, tx, ty;
            entry_position(s, (uint64_t)(b - s->entries), &layer, &level, &tx, &ty);
            rc = vt_error_set(
                err, VTS_ERR_CORRUPT,
                "'%s': payload of layer %u level %u tile %u,%u overlaps another payload at offset %llu",
                s->name, layer, level, tx, ty, (unsigned long long)a->offset);
        }
    }
    free(sorted);
    return rc;
}

static bool key_is_valid(const unsigned char *k, uint32_t len)
{
    for (uint32_t i = 0; i < len; i++)
        if (k[i] <= ' ' || k[i] >= 0x7f || k[i] == '=')
            return false;
    return len > 0;
}

static int parse_meta(struct vts_store *s, uint64_t off, uint32_t size, uint32_t crc,
                      struct vts_error *err)
{
    unsigned char *raw = malloc(size ? size : 1);
    int rc = 0;
    if (!raw)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the metadata of '%s'", s->name);
    rc = read_at(s, raw, size, off, "metadata", err);
    if (rc)
        goto out;
    if (vts_crc32c(0, raw, size) != crc) {
        rc = vt_error_set(err, VTS_ERR_CHECKSUM, "'%s': metadata checksum mismatch", s->name);
        goto out;
    }
    uint32_t count = vts_load_u32(raw);
    if (count > VTS_MAX_META_ENTRIES || count > (size - 4) / 8) {
        rc = vt_error_set(err, VTS_ERR_CORRUPT, "'%s': metadata claims %u entries in %u bytes",
                          s->name, count, size);
        goto out;
    }
    /* Each entry gains two NULs and loses its 8-byte length prefix: the copy fits in size. */
    s->meta_block = malloc(size);
    s->meta_keys = calloc(count ? count : 1, sizeof *s->meta_keys);
    s->meta_values = calloc(count ? count : 1, sizeof *s->meta_values);
    if (!s->meta_block || !s->meta_keys || !s->meta_values) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the metadata of '%s'", s->name);
        goto out;
    }
    uint64_t pos = 4, out_pos = 0;
    for (uint32_t i = 0; i < count; i++) {
        if (size - pos < 8)
            goto bad;
        uint32_t klen = vts_load_u32(raw + pos), vlen = vts_load_u32(raw + pos + 4);
        pos += 8;
        if (klen > VTS_MAX_KEY_BYTES || (uint64_t)klen + vlen > size - pos ||
            !key_is_valid(raw + pos, klen) || memchr(raw + pos + klen, '\0', vlen))
            goto bad;
        char *k = s->meta_block + out_pos;
        memcpy(k, raw + pos, klen);
        k[klen] = '\0';
        char *v = k + klen + 1;
        memcpy(v, raw + pos + klen, vlen);
        v[vlen] = '\0';
        s->meta_keys[i] = k;
        s->meta_values[i] = v;
        out_pos += (uint64_t)klen + vlen + 2;
        pos += (uint64_t)klen + vlen;
    }
    if (pos != size)
        goto bad;
    s->meta_count = count;
    goto out;
bad:
    rc = vt_error_set(err, VTS_ERR_CORRUPT, "'%s': malformed metadata block", s->name);
out:
    free(raw);
    return rc;
}

static int parse_header(struct vts_store *s, struct vts_error *err)
{
    unsigned char h[VTS_HEADER_SIZE];
    if (s->file_size < VTS_MAGIC_SIZE)
        return vt_error_set(err, VTS_ERR_NOT_VTS, "'%s' is not a vts store (%llu bytes)", s->name,
                            (unsigned long long)s->file_size);
    int rc = read_at(s, h, VTS_MAGIC_SIZE, 0, "header", err);
    if (rc)
        return rc;
    if (memcmp(h, VTS_MAGIC, VTS_MAGIC_SIZE) != 0)
        return vt_error_set(err, VTS_ERR_NOT_VTS, "'%s' is not a vts store (bad magic)", s->name);
    if (s->file_size < VTS_HEADER_SIZE)
        return vt_error_set(err, VTS_ERR_CORRUPT, "'%s': header is truncated (%llu of %u bytes)",
                            s->name, (unsigned long long)s->file_size, VTS_HEADER_SIZE);
    rc = read_at(s, h, VTS_HEADER_SIZE, 0, "header", err);
    if (rc)
        return rc;
    s->major = vts_load_u16(h + VTS_H_MAJOR);
    s->minor = vts_load_u16(h + VTS_H_MINOR);
    if (s->major != VTS_FORMAT_MAJOR)
        return vt_error_set(err, VTS_ERR_VERSION,
                            "'%s': format version %u.%u is not supported (this reader knows %u.x)",
                            s->name, s->major, s->minor, VTS_FORMAT_MAJOR);
    if (vts_crc32c(0, h, VTS_H_HEADER_CRC) != vts_load_u32(h + VTS_H_HEADER_CRC))
        return vt_error_set(err, VTS_ERR_CHECKSUM, "'%s': header checksum mismatch", s->name);

    struct vts_geometry *g = &s->geo;
    g->width = vts_load_u32(h + VTS_H_WIDTH);
    g->height = vts_load_u32(h + VTS_H_HEIGHT);
    g->tile_content_px = vts_load_u32(h + VTS_H_CONTENT);
    g->border_px = vts_load_u32(h + VTS_H_BORDER);
    g->tile_payload_px = vts_load_u32(h + VTS_H_PAYLOAD);
    g->level_count = vts_load_u32(h + VTS_H_LEVELS);
    g->layer_count = vts_load_u32(h + VTS_H_LAYERS);
    g->flags = vts_load_u32(h + VTS_H_FLAGS);
    struct vts_error gerr;
    if (vts_geometry_check(g, &gerr) != 0)
        return vt_error_set(err, VTS_ERR_CORRUPT, "'%s': invalid geometry: %s", s->name,
                            gerr.message);
    for (uint32_t l = 0; l < g->level_count; l++)
        vts_geometry_level(g, l, &s->levels[l]);
    s->tiles_per_layer = vts_geometry_tiles_per_layer(g);
    s->tile_count = s->tiles_per_layer * g->layer_count;

    uint64_t header_size = vts_load_u32(h + VTS_H_HEADER_SIZE);
    uint32_t layer_entry = vts_load_u32(h + VTS_H_LAYER_ENTRY);
    uint32_t index_entry = vts_load_u32(h + VTS_H_INDEX_ENTRY);
    uint64_t index_count = vts_load_u64(h + VTS_H_INDEX_COUNT);
    uint32_t meta_size = vts_load_u32(h + VTS_H_META_SIZE);
    if (header_size < VTS_HEADER_SIZE || layer_entry < VTS_LAYER_ENTRY_SIZE ||
        layer_entry > MAX_ENTRY_SIZE || index_entry < VTS_INDEX_ENTRY_SIZE ||
        index_entry > MAX_ENTRY_SIZE)
        return vt_error_set(
            err, VTS_ERR_CORRUPT,
            "'%s': invalid header (header %llu, layer entry %u, index entry %u bytes)", s->name,
            (unsigned long long)header_size, layer_entry, index_entry);
    if (index_count != s->tile_count)
        return vt_error_set(err, VTS_ERR_CORRUPT,
                            "'%s': index holds %llu entries, the geometry needs %llu", s->name,
                            (unsigned long long)index_count, (unsigned long long)s->tile_count);
    if (meta_size < 4 || meta_size > VTS_MAX_META_BYTES)
        return vt_error_set(err, VTS_ERR_CORRUPT, "'%s': metadata size %u is outside 4..%u",
                            s->name, meta_size, VTS_MAX_META_BYTES);
    struct region r[4] = {
        {vts_load_u64(h + VTS_H_LAYER_OFFSET), (uint64_t)layer_entry * g->layer_count,
         "layer table"},
        {vts_load_u64(h + VTS_H_INDEX_OFFSET), index_count * index_entry, "tile index"},
        {vts_load_u64(h + VTS_H_META_OFFSET), meta_size, "metadata"},
        {vts_load_u64(h + VTS_H_DATA_OFFSET), vts_load_u64(h + VTS_H_DATA_SIZE), "data region"},
    };
    if (header_size > s->file_size)
        return vt_error_set(err, VTS_ERR_CORRUPT,
                            "'%s': header size %llu is past the end of the file", s->name,
                            (unsigned long long)header_size);
    rc = check_regions(s, r, 4, header_size, err);
    if (rc == 0)
        rc = parse_layers(s, r[0].off, layer_entry, vts_load_u32(h + VTS_H_LAYERS_CRC), err);
    if (rc == 0)
        rc = parse_index(s, r[1].off, index_entry, vts_load_u32(h + VTS_H_INDEX_CRC), r[3].off,
                         r[3].size, err);
    if (rc == 0)
        rc = check_overlaps(s, err);
    if (rc == 0)
        rc = parse_meta(s, r[2].off, meta_size, vts_load_u32(h + VTS_H_META_CRC), err);
    return rc;
}

static struct vts_store *store_new(const char *name, struct vts_error *err)
{
    struct vts_store *s = calloc(1, sizeof *s);
    if (!s) {
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory opening '%s'", name);
        return NULL;
    }
    s->fd = -1;
    snprintf(s->name, sizeof s->name, "%s", name);
    return s;
}

static struct vts_store *store_finish_open(struct vts_store *s, struct vts_error *err)
{
    if (parse_header(s, err) != 0) {
        vts_close(s);
        return NULL;
    }
    return s;
}

struct vts_store *vts_open(const char *path, struct vts_error *err)
{
    struct vts_store *s = store_new(path, err);
    if (!s)
        return NULL;
    /* O_NONBLOCK: opening a FIFO must not wait for a writer (it is then refused below). */
    s->fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    struct stat st;
    if (s->fd < 0 || fstat(s->fd, &st) != 0) {
        vt_error_set(err, VTS_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
        vts_close(s);
        return NULL;
    }
    if (!S_ISREG(st.st_mode)) {
        vt_error_set(err, VTS_ERR_IO, "cannot open '%s': not a regular file", path);
        vts_close(s);
        return NULL;
    }
    s->file_size = (uint64_t)st.st_size;
    return store_finish_open(s, err);
}

struct vts_store *vts_open_memory(const void *data, size_t size, const char *name,
                                  struct vts_error *err)
{
    struct vts_store *s = store_new(name ? name : "(memory)", err);
    if (!s)
        return NULL;
    static const unsigned char empty[1];
    s->mem = data ? data : empty;
    s->file_size = data ? size : 0;
    return store_finish_open(s, err);
}

void vts_close(struct vts_store *s)
{
    if (!s)
        return;
    if (s->fd >= 0)
        close(s->fd);
    free(s->layers);
    free(s->entries);
    free(s->meta_block);
    free(s->meta_keys);
    free(s->meta_values);
    free(s);
}

const struct vts_geometry *vts_store_geometry(const struct vts_store *s)
{
    return &s->geo;
}

const struct vts_layer *vts_store_layer(const struct vts_store *s, uint32_t layer)
{
    return layer < s->geo.layer_count ? &s->layers[layer] : NULL;
}

int vts_store_level(const struct vts_store *s, uint32_t level, struct vts_level *out)
{
    if (level >= s->geo.level_count) {
        memset(out, 0, sizeof *out);
        return VTS_ERR_RANGE;
    }
    *out = s->levels[level];
    return 0;
}

uint64_t vts_store_file_size(const struct vts_store *s)
{
    return s->file_size;
}

const char *vts_store_name(const struct vts_store *s)
{
    return s->name;
}

void vts_store_version(const struct vts_store *s, unsigned *major, unsigned *minor)
{
    *major = s->major;
    *minor = s->minor;
}

uint64_t vts_store_tile_count(const struct vts_store *s)
{
    return s->tile_count;
}

const struct vts_tile_entry *vts_store_entry(const struct vts_store *s, uint64_t index)
{
    return index < s->tile_count ? &s->entries[index] : NULL;
}

uint32_t vts_store_max_payload(const struct vts_store *s)
{
    return s->max_payload;
}

int vts_store_tile(const struct vts_store *s, uint32_t layer, uint32_t level, uint32_t tx,
                   uint32_t ty, struct vts_tile_entry *out, struct vts_error *err)
{
    if (layer >= s->geo.layer_count || level >= s->geo.level_count ||
        tx >= s->levels[level].tiles_x || ty >= s->levels[level].tiles_y)
        return vt_error_set(err, VTS_ERR_RANGE, "'%s' has no tile %u,%u at layer %u level %u",
                            s->name, tx, ty, layer, level);
    const struct vts_level *L = &s->levels[level];
    *out = s->entries[layer * s->tiles_per_layer + L->first_tile + (uint64_t)ty * L->tiles_x + tx];
    return 0;
}

int vts_store_read(const struct vts_store *s, uint32_t layer, uint32_t level, uint32_t tx,
                   uint32_t ty, void *dst, size_t dst_capacity, size_t *out_len, unsigned flags,
                   struct vts_error *err)
{
    struct vts_tile_entry e;
    *out_len = 0;
    int rc = vts_store_tile(s, layer, level, tx, ty, &e, err);
    if (rc)
        return rc;
    if (e.length > dst_capacity)
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "'%s': tile %u,%u of level %u is %u bytes, buffer holds %zu", s->name,
                            tx, ty, level, e.length, dst_capacity);
    if (e.length == 0) /* empty tile: nothing to read (dst may be NULL) */
        return 0;
    char what[64];
    snprintf(what, sizeof what, "tile %u,%u of level %u", tx, ty, level);
    rc = read_at(s, dst, e.length, e.offset, what, err);
    if (rc)
        return rc;
    if (!(flags & VTS_READ_NO_CRC) && vts_crc32c(0, dst, e.length) != e.crc32c)
        return vt_error_set(err, VTS_ERR_CHECKSUM, "'%s': %s of layer %u has a bad checksum",
                            s->name, what, layer);
    *out_len = e.length;
    return 0;
}

uint32_t vts_store_meta_count(const struct vts_store *s)
{
    return s->meta_count;
}

const char *vts_store_meta_key(const struct vts_store *s, uint32_t i)
{
    return i < s->meta_count ? s->meta_keys[i] : NULL;
}

const char *vts_store_meta_value(const struct vts_store *s, uint32_t i)
{
    return i < s->meta_count ? s->meta_values[i] : NULL;
}

const char *vts_store_meta_find(const struct vts_store *s, const char *key)
{
    for (uint32_t i = 0; i < s->meta_count; i++)
        if (strcmp(s->meta_keys[i], key) == 0)
            return s->meta_values[i];
    return NULL;
}
