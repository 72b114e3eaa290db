/* Corrupted stores: each named case patches a valid store, re-seals the CRCs it did not mean to
 * break (so that the structural check behind the checksum is the one that fires), and expects an
 * exact status and a message that names the file and the defect. Each case is opened both from
 * memory (a fresh exact-size allocation, so ASan sees any over-read) and from a real file.
 *
 *   test_vts_corrupt                 run the cases
 *   test_vts_corrupt --write-bad DIR also write every case as DIR/<name>.vts plus DIR/MANIFEST
 *                                    (how tests/data/bad/ is regenerated) */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "internal/vts_format.h"
#include "robust/vts_fixture.h"
#include "vt_error.h"
#include "vt_test.h"
#include "vts.h"

static char tmpdir[256];
static unsigned char *fixture;
static size_t fixture_size;

struct image {
    unsigned char *data;
    size_t size;
};

/* ---- access to the fixture's structures ---- */

static uint64_t hdr64(const struct image *im, unsigned field)
{
    return vts_load_u64(im->data + field);
}

static uint32_t hdr32(const struct image *im, unsigned field)
{
    return vts_load_u32(im->data + field);
}

static void set32(struct image *im, unsigned field, uint32_t v)
{
    vts_store_u32(im->data + field, v);
}

static void set64(struct image *im, unsigned field, uint64_t v)
{
    vts_store_u64(im->data + field, v);
}

static unsigned char *layer_at(struct image *im, uint32_t i)
{
    return im->data + hdr64(im, VTS_H_LAYER_OFFSET) + (size_t)i * VTS_LAYER_ENTRY_SIZE;
}

static unsigned char *entry_at(struct image *im, uint64_t i)
{
    return im->data + hdr64(im, VTS_H_INDEX_OFFSET) + i * VTS_INDEX_ENTRY_SIZE;
}

static unsigned char *meta_at(struct image *im, uint32_t byte)
{
    return im->data + hdr64(im, VTS_H_META_OFFSET) + byte;
}

static uint64_t e_off(struct image *im, uint64_t i)
{
    return vts_load_u64(entry_at(im, i));
}

static uint32_t e_len(struct image *im, uint64_t i)
{
    return vts_load_u32(entry_at(im, i) + 8);
}

/* Index of the first entry that is empty (want_empty) or holds a payload that no other entry
 * shares. */
static uint64_t find_entry(struct image *im, bool want_empty, uint64_t after)
{
    uint64_t n = hdr64(im, VTS_H_INDEX_COUNT);
    for (uint64_t i = after; i < n; i++) {
        if (want_empty) {
            if (e_len(im, i) == 0)
                return i;
            continue;
        }
        if (e_len(im, i) < 2)
            continue;
        bool unique = true;
        for (uint64_t j = 0; j < n && unique; j++)
            unique = j == i || e_off(im, j) != e_off(im, i);
        if (unique)
            return i;
    }
    fprintf(stderr, "fixture has no suitable entry\n");
    abort();
}

/* Two unshared payloads a, b with a's offset below b's. */
static void two_payloads(struct image *im, uint64_t *a, uint64_t *b)
{
    *a = find_entry(im, false, 0);
    *b = find_entry(im, false, *a + 1);
    if (e_off(im, *a) > e_off(im, *b)) {
        uint64_t t = *a;
        *a = *b;
        *b = t;
    }
}

/* ---- the corruptions ---- */

#define HEADER_U32(fn, field, value)                                                               \
    static void fn(struct image *im)                                                               \
    {                                                                                              \
        set32(im, field, value);                                                                   \
    }
#define HEADER_U64(fn, field, value)                                                               \
    static void fn(struct image *im)                                                               \
    {                                                                                              \
        set64(im, field, value);                                                                   \
    }

static void empty_file(struct image *im)
{
    im->size = 0;
}

static void seven_bytes(struct image *im)
{
    im->size = 7;
}

static void bad_magic(struct image *im)
{
    im->data[1] = 'W';
}

static void magic_crlf_translated(struct image *im) /* a text-mode transfer turned \r\n into \n */
{
    memmove(im->data + 4, im->data + 5, im->size - 5);
    im->size--;
}

static void major_version_2(struct image *im)
{
    vts_store_u16(im->data + VTS_H_MAJOR, 2);
}

static void major_version_0(struct image *im)
{
    vts_store_u16(im->data + VTS_H_MAJOR, 0);
}

static void header_crc_mismatch(struct image *im)
{
    set32(im, VTS_H_WIDTH, hdr32(im, VTS_H_WIDTH) + 1);
}

static void header_truncated_at_100(struct image *im)
{
    im->size = 100;
}

static void header_only(struct image *im)
{
    im->size = VTS_HEADER_SIZE;
}

HEADER_U32(width_zero, VTS_H_WIDTH, 0)
HEADER_U32(height_over_limit, VTS_H_HEIGHT, VTS_MAX_DIMENSION + 1)
HEADER_U32(border_wider_than_content, VTS_H_BORDER, 17)
HEADER_U32(payload_not_content_plus_borders, VTS_H_PAYLOAD, 21)

static void content_zero(struct image *im)
{
    set32(im, VTS_H_CONTENT, 0);
    set32(im, VTS_H_BORDER, 0);
    set32(im, VTS_H_PAYLOAD, 0);
}

static void payload_over_limit(struct image *im)
{
    set32(im, VTS_H_CONTENT, 16384);
    set32(im, VTS_H_BORDER, 1);
    set32(im, VTS_H_PAYLOAD, 16386);
}

HEADER_U32(level_count_too_large, VTS_H_LEVELS, 4)
HEADER_U32(level_count_huge, VTS_H_LEVELS, 0xffffffffu)
HEADER_U32(level_count_zero, VTS_H_LEVELS, 0)
HEADER_U32(level_count_changed_index_not, VTS_H_LEVELS, 3)
HEADER_U32(layer_count_zero, VTS_H_LAYERS, 0)
HEADER_U32(layer_count_65, VTS_H_LAYERS, 65)
HEADER_U32(layer_count_changed_index_not, VTS_H_LAYERS, 3)

/* 2^30 x 2^30 texels in 1 px tiles: 2^60 tiles per level. */
static void tile_count_overflow_1px_tiles(struct image *im)
{
    set32(im, VTS_H_WIDTH, VTS_MAX_DIMENSION);
    set32(im, VTS_H_HEIGHT, VTS_MAX_DIMENSION);
    set32(im, VTS_H_CONTENT, 1);
    set32(im, VTS_H_BORDER, 0);
    set32(im, VTS_H_PAYLOAD, 1);
    set32(im, VTS_H_LEVELS, 31);
}

/* 65536^2 one-texel tiles: 2^32 per layer is the limit; two layers make the product too big. */
static void tiles_times_layers_over_limit(struct image *im)
{
    set32(im, VTS_H_WIDTH, 65536);
    set32(im, VTS_H_HEIGHT, 65536);
    set32(im, VTS_H_CONTENT, 1);
    set32(im, VTS_H_BORDER, 0);
    set32(im, VTS_H_PAYLOAD, 1);
    set32(im, VTS_H_LEVELS, 1);
}

/* Exactly 2^32 tiles: a legal geometry whose index (64 GiB) cannot be in a small file. */
static void index_of_4g_tiles_past_eof(struct image *im)
{
    tiles_times_layers_over_limit(im);
    set32(im, VTS_H_LAYERS, 1);
    set64(im, VTS_H_INDEX_COUNT, 1ull << 32);
}

static void index_count_mismatch(struct image *im)
{
    set64(im, VTS_H_INDEX_COUNT, hdr64(im, VTS_H_INDEX_COUNT) + 1);
}

static void index_count_huge(struct image *im)
{
    set64(im, VTS_H_INDEX_COUNT, UINT64_MAX);
}

HEADER_U32(header_size_too_small, VTS_H_HEADER_SIZE, 64)
HEADER_U32(header_size_past_eof, VTS_H_HEADER_SIZE, 0xffffffffu)
HEADER_U32(header_size_covers_layer_table, VTS_H_HEADER_SIZE, 200)
HEADER_U32(layer_entry_size_too_small, VTS_H_LAYER_ENTRY, 47)
HEADER_U32(layer_entry_size_huge, VTS_H_LAYER_ENTRY, 0x80000000u)
HEADER_U32(index_entry_size_too_small, VTS_H_INDEX_ENTRY, 8)
HEADER_U32(index_entry_size_over_4096, VTS_H_INDEX_ENTRY, 4097)
HEADER_U32(index_entry_stride_4096_past_eof, VTS_H_INDEX_ENTRY, 4096)

static void layer_table_offset_past_eof(struct image *im)
{
    set64(im, VTS_H_LAYER_OFFSET, im->size);
}

HEADER_U64(layer_table_offset_wraps_u64, VTS_H_LAYER_OFFSET, UINT64_MAX - 10)

static void index_offset_past_eof(struct image *im)
{
    set64(im, VTS_H_INDEX_OFFSET, im->size - 8);
}

HEADER_U64(index_offset_wraps_u64, VTS_H_INDEX_OFFSET, UINT64_MAX - 15)
HEADER_U64(index_overlapping_header, VTS_H_INDEX_OFFSET, 64)

static void index_overlapping_layer_table(struct image *im)
{
    set64(im, VTS_H_INDEX_OFFSET, hdr64(im, VTS_H_LAYER_OFFSET) + 48);
}

HEADER_U32(meta_size_over_limit, VTS_H_META_SIZE, VTS_MAX_META_BYTES + 1)
HEADER_U32(meta_size_below_4, VTS_H_META_SIZE, 3)

static void meta_offset_past_eof(struct image *im)
{
    set64(im, VTS_H_META_OFFSET, im->size);
}

static void meta_overlapping_index(struct image *im)
{
    set64(im, VTS_H_META_OFFSET, hdr64(im, VTS_H_INDEX_OFFSET) + 16);
}

static void data_overlapping_index(struct image *im)
{
    uint64_t end = hdr64(im, VTS_H_DATA_OFFSET) + hdr64(im, VTS_H_DATA_SIZE);
    uint64_t off = hdr64(im, VTS_H_INDEX_OFFSET) + 16;
    set64(im, VTS_H_DATA_OFFSET, off);
    set64(im, VTS_H_DATA_SIZE, end - off);
}

static void data_overlapping_metadata(struct image *im)
{
    uint64_t end = hdr64(im, VTS_H_DATA_OFFSET) + hdr64(im, VTS_H_DATA_SIZE);
    uint64_t off = hdr64(im, VTS_H_META_OFFSET) + 8;
    set64(im, VTS_H_DATA_OFFSET, off);
    set64(im, VTS_H_DATA_SIZE, end - off);
}

static void data_size_one_past_eof(struct image *im)
{
    set64(im, VTS_H_DATA_SIZE, hdr64(im, VTS_H_DATA_SIZE) + 1);
}

HEADER_U64(data_offset_wraps_u64, VTS_H_DATA_OFFSET, UINT64_MAX)

static void data_region_shrunk_below_payloads(struct image *im)
{
    set64(im, VTS_H_DATA_SIZE, hdr64(im, VTS_H_DATA_SIZE) - 1);
}

static void entry_offset_past_eof(struct image *im)
{
    vts_store_u64(entry_at(im, find_entry(im, false, 0)), im->size);
}

static void entry_length_huge(struct image *im)
{
    vts_store_u32(entry_at(im, find_entry(im, false, 0)) + 8, 0xffffffffu);
}

static void entry_offset_plus_length_wraps_u64(struct image *im)
{
    unsigned char *e = entry_at(im, find_entry(im, false, 0));
    vts_store_u64(e, UINT64_MAX - 4);
    vts_store_u32(e + 8, 16);
}

static void entry_offset_inside_index(struct image *im)
{
    vts_store_u64(entry_at(im, find_entry(im, false, 0)), hdr64(im, VTS_H_INDEX_OFFSET));
}

static void entry_one_byte_past_data_region(struct image *im)
{
    uint64_t i = find_entry(im, false, 0);
    uint64_t end = hdr64(im, VTS_H_DATA_OFFSET) + hdr64(im, VTS_H_DATA_SIZE);
    vts_store_u64(entry_at(im, i), end - e_len(im, i) + 1);
}

static void empty_entry_with_offset(struct image *im)
{
    vts_store_u64(entry_at(im, find_entry(im, true, 0)), hdr64(im, VTS_H_DATA_OFFSET));
}

static void empty_entry_with_crc(struct image *im)
{
    vts_store_u32(entry_at(im, find_entry(im, true, 0)) + 12, 0x12345678u);
}

static void entries_partially_overlap(struct image *im)
{
    uint64_t a, b;
    two_payloads(im, &a, &b);
    vts_store_u64(entry_at(im, b), e_off(im, a) + 1);
}

static void entries_same_offset_different_length(struct image *im)
{
    uint64_t a, b;
    two_payloads(im, &a, &b);
    vts_store_u64(entry_at(im, b), e_off(im, a));
    vts_store_u32(entry_at(im, b) + 8, e_len(im, a) - 1);
    memcpy(entry_at(im, b) + 12, entry_at(im, a) + 12, 4);
}

static void entries_same_payload_different_crc(struct image *im)
{
    uint64_t a, b;
    two_payloads(im, &a, &b);
    memcpy(entry_at(im, b), entry_at(im, a), VTS_INDEX_ENTRY_SIZE);
    entry_at(im, b)[12] ^= 1;
}

static void layer_zero_channels(struct image *im)
{
    layer_at(im, 1)[VTS_L_CHANNELS] = 0;
}

static void layer_five_channels(struct image *im)
{
    layer_at(im, 1)[VTS_L_CHANNELS] = 5;
}

static void layer_unknown_sample(struct image *im)
{
    layer_at(im, 1)[VTS_L_SAMPLE] = 5;
}

static void layer_sample_zero(struct image *im)
{
    layer_at(im, 0)[VTS_L_SAMPLE] = 0;
}

static void layer_unknown_colour(struct image *im)
{
    layer_at(im, 1)[VTS_L_COLOUR] = 5;
}

static void layer_colour_zero(struct image *im)
{
    layer_at(im, 0)[VTS_L_COLOUR] = 0;
}

static void layer_name_unterminated(struct image *im)
{
    memset(layer_at(im, 0) + VTS_L_NAME, 'n', VTS_LAYER_NAME_BYTES);
}

static void layer_table_crc_mismatch(struct image *im)
{
    layer_at(im, 1)[VTS_L_PARAM] ^= 0x40;
}

static void index_crc_mismatch(struct image *im)
{
    entry_at(im, find_entry(im, false, 0))[12] ^= 1;
}

static void meta_crc_mismatch(struct image *im)
{
    *meta_at(im, 4 + 8 + 9) ^= 1; /* a byte of the first value */
}

static void meta_count_huge(struct image *im)
{
    vts_store_u32(meta_at(im, 0), 0xffffffffu);
}

static void meta_count_over_limit(struct image *im)
{
    vts_store_u32(meta_at(im, 0), VTS_MAX_META_ENTRIES + 1);
}

static void meta_count_one_too_many(struct image *im)
{
    vts_store_u32(meta_at(im, 0), vts_load_u32(meta_at(im, 0)) + 1);
}

static void meta_trailing_entry_bytes(struct image *im)
{
    vts_store_u32(meta_at(im, 0), vts_load_u32(meta_at(im, 0)) - 1);
}

static void meta_trailing_padding_byte(struct image *im)
{
    set32(im, VTS_H_META_SIZE, hdr32(im, VTS_H_META_SIZE) + 1);
}

static void meta_key_with_equals(struct image *im)
{
    *meta_at(im, 4 + 8 + 3) = '=';
}

static void meta_key_with_space(struct image *im)
{
    *meta_at(im, 4 + 8 + 3) = ' ';
}

static void meta_key_with_del(struct image *im)
{
    *meta_at(im, 4 + 8) = 0x7f;
}

static void meta_key_empty(struct image *im)
{
    uint32_t klen = vts_load_u32(meta_at(im, 4)), vlen = vts_load_u32(meta_at(im, 8));
    vts_store_u32(meta_at(im, 4), 0);
    vts_store_u32(meta_at(im, 8), klen + vlen);
}

static void meta_key_length_over_255(struct image *im)
{
    vts_store_u32(meta_at(im, 4), 256);
}

static void meta_value_with_nul(struct image *im)
{
    *meta_at(im, 4 + 8 + 9 + 2) = '\0';
}

static void meta_value_length_huge(struct image *im)
{
    vts_store_u32(meta_at(im, 8), 0xffffffffu);
}

static void meta_value_length_past_block(struct image *im)
{
    uint32_t size = hdr32(im, VTS_H_META_SIZE), vlen = vts_load_u32(meta_at(im, 8));
    vts_store_u32(meta_at(im, 8), size - 4 - 8 - 9 + 1 > vlen ? size - 4 - 8 - 9 + 1 : vlen + 1);
}

/* ---- the case table ---- */

enum { K_LAYERS = 1, K_INDEX = 2, K_META = 4, K_HEADER = 8, K_ALL = 15 };

struct corrupt_case {
    const char *name; /* also the file name under tests/data/bad/ */
    void (*corrupt)(struct image *);
    unsigned keep; /* CRCs left as they are (not re-sealed) after corrupt() */
    int status;
    const char *message; /* a substring of the error message */
};

#define C(fn, keep, status, msg)                                                                   \
    {                                                                                              \
#fn, fn, keep, status, msg                                                                 \
    }

static const struct corrupt_case cases[] = {
    C(empty_file, K_ALL, VTS_ERR_NOT_VTS, "is not a vts store (0 bytes)"),
    C(seven_bytes, K_ALL, VTS_ERR_NOT_VTS, "is not a vts store (7 bytes)"),
    C(bad_magic, K_ALL, VTS_ERR_NOT_VTS, "is not a vts store (bad magic)"),
    C(magic_crlf_translated, K_ALL, VTS_ERR_NOT_VTS, "(bad magic)"),
    C(major_version_2, 0, VTS_ERR_VERSION, "format version 2.0 is not supported"),
    C(major_version_0, 0, VTS_ERR_VERSION, "format version 0.0 is not supported"),
    C(header_crc_mismatch, K_HEADER, VTS_ERR_CHECKSUM, "header checksum mismatch"),
    C(header_truncated_at_100, K_ALL, VTS_ERR_CORRUPT, "header is truncated (100 of 128 bytes)"),
    C(header_only, K_ALL, VTS_ERR_CORRUPT, "layer table (bytes 128 + 96) lies past the end"),
    C(width_zero, 0, VTS_ERR_CORRUPT, "invalid geometry: size 0x24 is outside"),
    C(height_over_limit, 0, VTS_ERR_CORRUPT, "invalid geometry: size 40x1073741825 is outside"),
    C(border_wider_than_content, 0, VTS_ERR_CORRUPT, "tile content 16 px with border 17 px"),
    C(payload_not_content_plus_borders, 0, VTS_ERR_CORRUPT,
      "tile payload 21 px != content 16 + 2 * border 2"),
    C(content_zero, 0, VTS_ERR_CORRUPT, "tile content 0 px with border 0 px is invalid"),
    C(payload_over_limit, 0, VTS_ERR_CORRUPT, "tile payload 16386 px is above the limit"),
    C(level_count_too_large, 0, VTS_ERR_CORRUPT, "4 levels requested, 40x24 with 16 px tiles"),
    C(level_count_huge, 0, VTS_ERR_CORRUPT, "4294967295 levels requested"),
    C(level_count_zero, 0, VTS_ERR_CORRUPT, "0 levels requested"),
    C(level_count_changed_index_not, 0, VTS_ERR_CORRUPT,
      "index holds 16 entries, the geometry needs 18"),
    C(layer_count_zero, 0, VTS_ERR_CORRUPT, "0 layers is outside 1..64"),
    C(layer_count_65, 0, VTS_ERR_CORRUPT, "65 layers is outside 1..64"),
    C(layer_count_changed_index_not, 0, VTS_ERR_CORRUPT,
      "index holds 16 entries, the geometry needs 24"),
    C(tile_count_overflow_1px_tiles, 0, VTS_ERR_CORRUPT, "has too many tiles"),
    C(tiles_times_layers_over_limit, 0, VTS_ERR_CORRUPT,
      "65536x65536 with 1 px tiles and 2 layers has too many tiles"),
    C(index_of_4g_tiles_past_eof, 0, VTS_ERR_CORRUPT,
      "tile index (bytes 224 + 68719476736) lies past"),
    C(index_count_mismatch, 0, VTS_ERR_CORRUPT, "index holds 17 entries, the geometry needs 16"),
    C(index_count_huge, 0, VTS_ERR_CORRUPT, "index holds 18446744073709551615 entries"),
    C(header_size_too_small, 0, VTS_ERR_CORRUPT, "invalid header (header 64,"),
    C(header_size_past_eof, 0, VTS_ERR_CORRUPT, "header size 4294967295 is past the end"),
    C(header_size_covers_layer_table, 0, VTS_ERR_CORRUPT, "layer table overlaps the header"),
    C(layer_entry_size_too_small, 0, VTS_ERR_CORRUPT, "layer entry 47, index entry 16 bytes"),
    C(layer_entry_size_huge, 0, VTS_ERR_CORRUPT, "layer entry 2147483648, index entry"),
    C(index_entry_size_too_small, 0, VTS_ERR_CORRUPT, "index entry 8 bytes"),
    C(index_entry_size_over_4096, 0, VTS_ERR_CORRUPT, "index entry 4097 bytes"),
    C(index_entry_stride_4096_past_eof, 0, VTS_ERR_CORRUPT,
      "tile index (bytes 224 + 65536) lies past"),
    C(layer_table_offset_past_eof, 0, VTS_ERR_CORRUPT, "layer table (bytes"),
    C(layer_table_offset_wraps_u64, 0, VTS_ERR_CORRUPT,
      "layer table (bytes 18446744073709551605 + 96) lies past the end"),
    C(index_offset_past_eof, 0, VTS_ERR_CORRUPT, "tile index (bytes"),
    C(index_offset_wraps_u64, 0, VTS_ERR_CORRUPT, "tile index (bytes 18446744073709551600 + 256)"),
    C(index_overlapping_header, 0, VTS_ERR_CORRUPT, "tile index overlaps the header"),
    C(index_overlapping_layer_table, 0, VTS_ERR_CORRUPT, "tile index overlaps the layer table"),
    C(meta_size_over_limit, 0, VTS_ERR_CORRUPT, "metadata size 16777217 is outside 4..16777216"),
    C(meta_size_below_4, 0, VTS_ERR_CORRUPT, "metadata size 3 is outside"),
    C(meta_offset_past_eof, 0, VTS_ERR_CORRUPT, "metadata (bytes"),
    C(meta_overlapping_index, 0, VTS_ERR_CORRUPT, "metadata overlaps the tile index"),
    C(data_overlapping_index, 0, VTS_ERR_CORRUPT, "data region overlaps the tile index"),
    C(data_overlapping_metadata, 0, VTS_ERR_CORRUPT, "data region overlaps the metadata"),
    C(data_size_one_past_eof, 0, VTS_ERR_CORRUPT, "data region (bytes"),
    C(data_offset_wraps_u64, 0, VTS_ERR_CORRUPT, "data region (bytes 18446744073709551615 +"),
    C(data_region_shrunk_below_payloads, 0, VTS_ERR_CORRUPT, "points outside the data region"),
    C(entry_offset_past_eof, 0, VTS_ERR_CORRUPT,
      "index entry of layer 0 level 0 tile 0,0 points outside the data region"),
    C(entry_length_huge, 0, VTS_ERR_CORRUPT, "points outside the data region (offset"),
    C(entry_offset_plus_length_wraps_u64, 0, VTS_ERR_CORRUPT,
      "points outside the data region (offset 18446744073709551611, length 16)"),
    C(entry_offset_inside_index, 0, VTS_ERR_CORRUPT, "points outside the data region"),
    C(entry_one_byte_past_data_region, 0, VTS_ERR_CORRUPT, "points outside the data region"),
    C(empty_entry_with_offset, 0, VTS_ERR_CORRUPT,
      "index entry of layer 0 level 0 tile 2,1 is empty but has an offset or checksum"),
    C(empty_entry_with_crc, 0, VTS_ERR_CORRUPT, "is empty but has an offset or checksum (offset 0"),
    C(entries_partially_overlap, 0, VTS_ERR_CORRUPT, "overlaps another payload at offset"),
    C(entries_same_offset_different_length, 0, VTS_ERR_CORRUPT, "overlaps another payload"),
    C(entries_same_payload_different_crc, 0, VTS_ERR_CORRUPT, "overlaps another payload"),
    C(layer_zero_channels, 0, VTS_ERR_CORRUPT, "layer 1 has an invalid description (0 channels"),
    C(layer_five_channels, 0, VTS_ERR_CORRUPT, "layer 1 has an invalid description (5 channels"),
    C(layer_unknown_sample, 0, VTS_ERR_CORRUPT, "(3 channels, sample 5, colour 3)"),
    C(layer_sample_zero, 0, VTS_ERR_CORRUPT,
      "layer 0 has an invalid description (4 channels, sample 0"),
    C(layer_unknown_colour, 0, VTS_ERR_CORRUPT, "(3 channels, sample 2, colour 5)"),
    C(layer_colour_zero, 0, VTS_ERR_CORRUPT, "(4 channels, sample 1, colour 0)"),
    C(layer_name_unterminated, 0, VTS_ERR_CORRUPT, "layer 0 has an invalid description"),
    C(layer_table_crc_mismatch, K_LAYERS, VTS_ERR_CHECKSUM, "layer table checksum mismatch"),
    C(index_crc_mismatch, K_INDEX, VTS_ERR_CHECKSUM, "tile index checksum mismatch"),
    C(meta_crc_mismatch, K_META, VTS_ERR_CHECKSUM, "metadata checksum mismatch"),
    C(meta_count_huge, 0, VTS_ERR_CORRUPT, "metadata claims 4294967295 entries in 82 bytes"),
    C(meta_count_over_limit, 0, VTS_ERR_CORRUPT, "metadata claims 4097 entries"),
    C(meta_count_one_too_many, 0, VTS_ERR_CORRUPT, "malformed metadata block"),
    C(meta_trailing_entry_bytes, 0, VTS_ERR_CORRUPT, "malformed metadata block"),
    C(meta_trailing_padding_byte, 0, VTS_ERR_CORRUPT, "malformed metadata block"),
    C(meta_key_with_equals, 0, VTS_ERR_CORRUPT, "malformed metadata block"),
    C(meta_key_with_space, 0, VTS_ERR_CORRUPT, "malformed metadata block"),
    C(meta_key_with_del, 0, VTS_ERR_CORRUPT, "malformed metadata block"),
    C(meta_key_empty, 0, VTS_ERR_CORRUPT, "malformed metadata block"),
    C(meta_key_length_over_255, 0, VTS_ERR_CORRUPT, "malformed metadata block"),
    C(meta_value_with_nul, 0, VTS_ERR_CORRUPT, "malformed metadata block"),
    C(meta_value_length_huge, 0, VTS_ERR_CORRUPT, "malformed metadata block"),
    C(meta_value_length_past_block, 0, VTS_ERR_CORRUPT, "malformed metadata block"),
};

#define CASE_COUNT (sizeof cases / sizeof cases[0])

/* Applies a case to a copy of the fixture; returns the corrupted image (caller frees data). */
static struct image make_case(const struct corrupt_case *c)
{
    struct image im = {malloc(fixture_size), fixture_size};
    memcpy(im.data, fixture, fixture_size);
    c->corrupt(&im);
    if (!(c->keep & K_LAYERS))
        vts_reseal_layers(im.data, im.size);
    if (!(c->keep & K_INDEX))
        vts_reseal_index(im.data, im.size);
    if (!(c->keep & K_META))
        vts_reseal_meta(im.data, im.size);
    if (!(c->keep & K_HEADER))
        vts_reseal_header(im.data, im.size);
    return im;
}

static int case_failures;

static void expect(const struct corrupt_case *c, const char *how, struct vts_store *s,
                   const struct vts_error *err, const char *name)
{
    bool ok = s == NULL && err->status == c->status && strstr(err->message, c->message) &&
              strstr(err->message, name) && strchr(err->message, '\n') == NULL;
    VT_CHECK(ok);
    if (!ok) {
        case_failures++;
        fprintf(stderr, "  case %s (%s): %s, status %s, message '%s'; expected %s '%s'\n", c->name,
                how, s ? "opened" : "failed", vts_status_name(err->status), err->message,
                vts_status_name(c->status), c->message);
    }
    vts_close(s);
}

static void each_corruption_gives_its_status_and_message(void)
{
    for (size_t i = 0; i < CASE_COUNT; i++) {
        const struct corrupt_case *c = &cases[i];
        struct image im = make_case(c);
        char name[300];
        snprintf(name, sizeof name, "bad/%s.vts", c->name);
        /* memory: an allocation of exactly the file's size */
        unsigned char *exact = malloc(im.size ? im.size : 1);
        memcpy(exact, im.data, im.size);
        struct vts_error err = {0};
        struct vts_store *s = vts_open_memory(exact, im.size, name, &err);
        expect(c, "memory", s, &err, name);
        free(exact);
        /* file: the pread path */
        char path[600];
        snprintf(path, sizeof path, "%s/%s.vts", tmpdir, c->name);
        VT_CHECK_INT_EQ(vts_fixture_write_file(path, im.data, im.size), 0);
        vt_error_clear(&err);
        s = vts_open(path, &err);
        expect(c, "file", s, &err, path);
        unlink(path);
        free(im.data);
    }
    fprintf(stderr, "     %zu corruption cases, %d failed\n", CASE_COUNT, case_failures);
    VT_CHECK(CASE_COUNT >= 25);
}

/* The fixture must have what the cases rely on; otherwise some cases test nothing. */
static void fixture_has_padding_empty_and_shared_tiles(void)
{
    struct image im = {fixture, fixture_size};
    uint64_t meta_end = hdr64(&im, VTS_H_META_OFFSET) + hdr32(&im, VTS_H_META_SIZE);
    VT_CHECK(meta_end < hdr64(&im, VTS_H_DATA_OFFSET)); /* meta_trailing_padding_byte */
    VT_CHECK_INT_EQ(hdr32(&im, VTS_H_META_SIZE), 82);
    VT_CHECK_INT_EQ(hdr64(&im, VTS_H_INDEX_COUNT), 16);
    VT_CHECK_INT_EQ(hdr64(&im, VTS_H_DATA_OFFSET) + hdr64(&im, VTS_H_DATA_SIZE), fixture_size);
    uint64_t empty = 0, shared = 0;
    for (uint64_t i = 0; i < 16; i++) {
        empty += e_len(&im, i) == 0;
        for (uint64_t j = 0; j < i; j++)
            shared += e_len(&im, i) > 0 && e_off(&im, i) == e_off(&im, j);
    }
    VT_CHECK(empty >= 2);
    VT_CHECK(shared >= 2);
    struct vts_error err;
    unsigned failures = 99;
    VT_CHECK_INT_EQ(vts_fixture_exercise(fixture, fixture_size, "fixture", &err, &failures), 0);
    VT_CHECK_INT_EQ(failures, 0);
}

/* Opens an image that should be valid; returns the store or NULL (reported). */
static struct vts_store *open_valid(struct image *im, const char *name)
{
    struct vts_error err = {0};
    struct vts_store *s = vts_open_memory(im->data, im->size, name, &err);
    VT_CHECK(s != NULL);
    if (!s)
        fprintf(stderr, "  %s: %s\n", name, err.message);
    return s;
}

static void newer_minor_version_opens(void)
{
    struct image im = {malloc(fixture_size), fixture_size};
    memcpy(im.data, fixture, fixture_size);
    vts_store_u16(im.data + VTS_H_MINOR, 7);
    vts_reseal_header(im.data, im.size);
    struct vts_store *s = open_valid(&im, "minor7");
    if (s) {
        unsigned major, minor;
        vts_store_version(s, &major, &minor);
        VT_CHECK_INT_EQ(major, 1);
        VT_CHECK_INT_EQ(minor, 7);
        vts_close(s);
    }
    free(im.data);
}

/* A later minor version may widen index entries; a reader skips the extra bytes. Here the index
 * is rewritten with a 32- and a 4096-byte stride at the end of the file. */
static void wider_index_entries_are_read_by_stride(void)
{
    const uint32_t strides[] = {32, 4096};
    for (int k = 0; k < 2; k++) {
        uint32_t stride = strides[k];
        struct image old = {fixture, fixture_size};
        uint64_t n = hdr64(&old, VTS_H_INDEX_COUNT);
        struct image im = {calloc(1, fixture_size + n * stride), fixture_size + n * stride};
        memcpy(im.data, fixture, fixture_size);
        for (uint64_t i = 0; i < n; i++) {
            unsigned char *e = im.data + fixture_size + i * stride;
            memcpy(e, entry_at(&old, i), VTS_INDEX_ENTRY_SIZE);
            memset(e + VTS_INDEX_ENTRY_SIZE, 0xab, stride - VTS_INDEX_ENTRY_SIZE);
        }
        set64(&im, VTS_H_INDEX_OFFSET, fixture_size);
        set32(&im, VTS_H_INDEX_ENTRY, stride);
        vts_reseal_all(im.data, im.size);
        struct vts_error err;
        unsigned failures = 99;
        VT_CHECK_INT_EQ(vts_fixture_exercise(im.data, im.size, "stride", &err, &failures), 0);
        VT_CHECK_INT_EQ(failures, 0);
        struct vts_store *s = open_valid(&im, "stride");
        if (s) {
            for (uint64_t i = 0; i < n; i++)
                VT_CHECK_INT_EQ(vts_store_entry(s, i)->offset, e_off(&old, i));
            vts_close(s);
        }
        free(im.data);
    }
}

/* Sharing is legal when offset, length and CRC all agree. */
static void entry_pointing_at_another_payload_opens(void)
{
    struct image im = {malloc(fixture_size), fixture_size};
    memcpy(im.data, fixture, fixture_size);
    uint64_t a, b;
    two_payloads(&im, &a, &b);
    memcpy(entry_at(&im, b), entry_at(&im, a), VTS_INDEX_ENTRY_SIZE);
    vts_reseal_all(im.data, im.size);
    struct vts_store *s = open_valid(&im, "shared");
    if (s) {
        VT_CHECK_INT_EQ(vts_store_entry(s, b)->offset, e_off(&im, a));
        vts_close(s);
    }
    free(im.data);
}

/* A payload byte flipped: the store opens (only the index is checked at open), the read of that
 * tile reports the checksum, NO_CRC returns the bytes, and other tiles still read. */
static void payload_crc_mismatch_is_reported_by_read(void)
{
    struct image im = {malloc(fixture_size), fixture_size};
    memcpy(im.data, fixture, fixture_size);
    uint64_t i = find_entry(&im, false, 0);
    im.data[e_off(&im, i) + 3] ^= 0x10;
    struct vts_store *s = open_valid(&im, "bad/payload_crc_mismatch.vts");
    if (s) {
        /* entry i is layer 0, level 0, tile 0,0 in the fixture (checked by the position) */
        VT_CHECK_INT_EQ(i, 0);
        unsigned char buf[VTS_FIXTURE_MAX_PAYLOAD], want[VTS_FIXTURE_MAX_PAYLOAD];
        size_t len = 99, want_len = vts_fixture_payload(VTS_FIXTURE_SMALL, 0, 0, 0, 0, want);
        struct vts_error err = {0};
        VT_CHECK_INT_EQ(vts_store_read(s, 0, 0, 0, 0, buf, sizeof buf, &len, 0, &err),
                        VTS_ERR_CHECKSUM);
        VT_CHECK_STR_CONTAINS(
            err.message,
            "'bad/payload_crc_mismatch.vts': tile 0,0 of level 0 of layer 0 has a bad checksum");
        VT_CHECK_INT_EQ(len, 0);
        VT_CHECK_INT_EQ(vts_store_read(s, 0, 0, 0, 0, buf, sizeof buf, &len, VTS_READ_NO_CRC, &err),
                        0);
        VT_CHECK_INT_EQ(len, want_len);
        VT_CHECK(buf[3] == (want[3] ^ 0x10) && memcmp(buf, want, 3) == 0);
        VT_CHECK_INT_EQ(vts_store_read(s, 1, 0, 0, 0, buf, sizeof buf, &len, 0, &err), 0);
        VT_CHECK_INT_EQ(vts_store_read(s, 0, 1, 0, 0, buf, sizeof buf, &len, 0, &err), 0);
        vts_close(s);
    }
    free(im.data);
}

/* The file shrinks after open (another process truncates it): reads fail cleanly. */
static void file_truncated_after_open_fails_reads_cleanly(void)
{
    char path[600];
    snprintf(path, sizeof path, "%s/shrinks.vts", tmpdir);
    VT_CHECK_INT_EQ(vts_fixture_write_file(path, fixture, fixture_size), 0);
    struct vts_error err = {0};
    struct vts_store *s = vts_open(path, &err);
    VT_CHECK(s != NULL);
    if (!s)
        return;
    struct image im = {fixture, fixture_size};
    VT_CHECK_INT_EQ(truncate(path, (off_t)hdr64(&im, VTS_H_DATA_OFFSET)), 0);
    unsigned char buf[VTS_FIXTURE_MAX_PAYLOAD];
    size_t len = 99;
    VT_CHECK_INT_EQ(vts_store_read(s, 0, 0, 0, 0, buf, sizeof buf, &len, 0, &err), VTS_ERR_CORRUPT);
    VT_CHECK_STR_CONTAINS(err.message, "tile 0,0 of level 0 is truncated at byte");
    VT_CHECK_STR_CONTAINS(err.message, path);
    VT_CHECK_INT_EQ(len, 0);
    vts_close(s);
    unlink(path);
}

static void on_alarm(int sig)
{
    (void)sig;
    static const char msg[] = "vts_open blocked on a FIFO\n";
    if (write(2, msg, sizeof msg - 1) < 0)
        _exit(2);
    _exit(1);
}

static void not_a_regular_file_is_an_io_error(void)
{
    char fifo[600], missing[600];
    snprintf(fifo, sizeof fifo, "%s/fifo.vts", tmpdir);
    snprintf(missing, sizeof missing, "%s/missing.vts", tmpdir);
    const char *paths[] = {tmpdir, "/dev/null", missing, fifo};
    const char *messages[] = {"not a regular file", "not a regular file",
                              "No such file or directory", "not a regular file"};
    VT_CHECK_INT_EQ(mkfifo(fifo, 0600), 0);
    signal(SIGALRM, on_alarm);
    alarm(120); /* opening a FIFO for reading must not wait for a writer (a generous watchdog) */
    for (int i = 0; i < 4; i++) {
        struct vts_error err = {0};
        struct vts_store *s = vts_open(paths[i], &err);
        VT_CHECK(s == NULL);
        vts_close(s);
        VT_CHECK_INT_EQ(err.status, VTS_ERR_IO);
        VT_CHECK_STR_CONTAINS(err.message, messages[i]);
        VT_CHECK_STR_CONTAINS(err.message, paths[i]);
    }
    alarm(0);
    unlink(fifo);
}

/* An empty tile needs no buffer: reading it into NULL with capacity 0 reads nothing (this was a
 * memcpy(NULL, ..., 0), undefined behaviour that UBSan reports, for memory stores). */
static void empty_tiles_read_into_no_buffer(void)
{
    for (int which = 0; which < 2; which++) {
        struct image im = {fixture, fixture_size};
        uint64_t i = find_entry(&im, true, 0); /* layer 0, level 0, tile 2,1 in the fixture */
        VT_CHECK_INT_EQ(i, 5);
        char path[600];
        snprintf(path, sizeof path, "%s/empty-tile.vts", tmpdir);
        VT_CHECK_INT_EQ(vts_fixture_write_file(path, fixture, fixture_size), 0);
        struct vts_error err = {0};
        struct vts_store *s =
            which ? vts_open(path, &err) : vts_open_memory(fixture, fixture_size, "m", &err);
        VT_CHECK(s != NULL);
        if (!s)
            continue;
        size_t len = 99;
        VT_CHECK_INT_EQ(vts_store_read(s, 0, 0, 2, 1, NULL, 0, &len, 0, &err), 0);
        VT_CHECK_INT_EQ(len, 0);
        VT_CHECK_INT_EQ(vts_store_read(s, 0, 0, 0, 0, NULL, 0, &len, 0, &err), VTS_ERR_LIMIT);
        vts_close(s);
        unlink(path);
    }
}

static void null_memory_is_an_empty_file(void)
{
    struct vts_error err = {0};
    struct vts_store *s = vts_open_memory(NULL, 100, "nothing", &err);
    VT_CHECK(s == NULL);
    VT_CHECK_INT_EQ(err.status, VTS_ERR_NOT_VTS);
    VT_CHECK_STR_CONTAINS(err.message, "'nothing' is not a vts store (0 bytes)");
}

/* Regenerates tests/data/bad/: one file per case and a MANIFEST line "file status message". */
static int write_bad_files(const char *dir)
{
    char path[600];
    snprintf(path, sizeof path, "%s/MANIFEST", dir);
    FILE *m = fopen(path, "w");
    if (!m)
        return 1;
    fprintf(m, "# file status message-substring (written by test_vts_corrupt --write-bad)\n");
    for (size_t i = 0; i < CASE_COUNT; i++) {
        struct image im = make_case(&cases[i]);
        snprintf(path, sizeof path, "%s/%s.vts", dir, cases[i].name);
        if (vts_fixture_write_file(path, im.data, im.size) != 0)
            return 1;
        fprintf(m, "%s.vts %s %s\n", cases[i].name, vts_status_name(cases[i].status),
                cases[i].message);
        free(im.data);
    }
    return fclose(m) == 0 ? 0 : 1;
}

int main(int argc, char **argv)
{
    if (!vts_fixture_mkdtemp(tmpdir, sizeof tmpdir, "test_vts_corrupt"))
        return 1;
    fixture = vts_fixture_bytes(tmpdir, VTS_FIXTURE_SMALL, &fixture_size);
    if (!fixture)
        return 1;
    int rc = 0;
    if (argc == 3 && strcmp(argv[1], "--write-bad") == 0) {
        rc = write_bad_files(argv[2]);
    } else {
        VT_RUN(fixture_has_padding_empty_and_shared_tiles);
        VT_RUN(each_corruption_gives_its_status_and_message);
        VT_RUN(newer_minor_version_opens);
        VT_RUN(wider_index_entries_are_read_by_stride);
        VT_RUN(entry_pointing_at_another_payload_opens);
        VT_RUN(payload_crc_mismatch_is_reported_by_read);
        VT_RUN(file_truncated_after_open_fails_reads_cleanly);
        VT_RUN(not_a_regular_file_is_an_io_error);
        VT_RUN(empty_tiles_read_into_no_buffer);
        VT_RUN(null_memory_is_an_empty_file);
        rc = vt_test_main_result();
    }
    free(fixture);
    vts_fixture_rmdir_all(tmpdir);
    return rc;
}
