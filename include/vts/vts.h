/* libvts: the .vts virtual-texture tile store, reader side (C11 + libc only, thread-safe reads).
 * Format specification: docs/vts-format.md. Writer: vts_writer.h.
 *
 * Conventions of the whole API (vts.h and vts_writer.h):
 * - Every name is vts_* / VTS_*; only those symbols are exported from libvts.so.
 * - Actions return int: 0 (VTS_OK) or a negative enum vts_status, and fill the caller's
 *   struct vts_error (which may be NULL) with a one-line message. Functions returning a pointer
 *   return NULL on failure and fill err the same way.
 * - Out-of-range arguments (a layer, level, tile, entry or metadata index the store does not hold)
 *   are never clamped and never undefined: functions that return a pointer return NULL, functions
 *   that return int return VTS_ERR_RANGE and zero their output struct. Handles (store, writer) must
 *   be valid; vts_close() and vts_writer_destroy() accept NULL.
 * - Thread safety: a store may be read from many threads at once; a writer's tile puts may come
 *   from many threads, its other calls from one. */
#ifndef VTS_H
#define VTS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* VTS_API marks the exported functions; libvts is built with hidden visibility for the rest. */
#if defined(_WIN32) && defined(VTS_BUILDING_DLL)
#define VTS_API __declspec(dllexport)
#elif defined(__GNUC__) && __GNUC__ >= 4
#define VTS_API __attribute__((visibility("default")))
#else
#define VTS_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Library version (the project's: CMakeLists.txt reads it from here). Not the file format version
 * (VTS_FORMAT_MAJOR below). */
#define VTS_VERSION_MAJOR  0
#define VTS_VERSION_MINOR  1
#define VTS_VERSION_PATCH  0
#define VTS_VERSION_NUMBER (VTS_VERSION_MAJOR * 10000 + VTS_VERSION_MINOR * 100 + VTS_VERSION_PATCH)

/* Version of the library actually loaded, as VTS_VERSION_NUMBER (compare with the header's to
 * detect a mismatch) and as "MAJOR.MINOR.PATCH". */
VTS_API unsigned vts_version(void);
VTS_API const char *vts_version_string(void);

/* Pinned values: scripts and other languages test them. Never renumber, only append. */
enum vts_status {
    VTS_OK = 0,
    VTS_ERR_IO = -1,          /* open/read/write/rename failed; the message carries strerror */
    VTS_ERR_NOMEM = -2,       /* allocation failed */
    VTS_ERR_NOT_VTS = -3,     /* the file is not a .vts store (bad magic) */
    VTS_ERR_VERSION = -4,     /* a .vts store of a major version this reader does not know */
    VTS_ERR_CORRUPT = -5,     /* structure invalid: offsets, lengths, counts, geometry */
    VTS_ERR_CHECKSUM = -6,    /* a CRC-32C does not match */
    VTS_ERR_RANGE = -7,       /* layer/level/tile/key outside what the store holds */
    VTS_ERR_LIMIT = -8,       /* a size overflows or exceeds a configured limit */
    VTS_ERR_UNSUPPORTED = -9, /* a codec or sample type this build cannot handle */
    VTS_ERR_ARG = -10,        /* invalid argument from the caller */
    VTS_ERR_CANCELLED = -11,  /* a progress callback asked to stop */
    VTS_ERR_BAD_INPUT = -12,  /* an input file (image, payload, text) is malformed */
};

#define VTS_ERROR_MESSAGE_MAX 256

/* Owned by the caller; functions that take one may be given NULL. */
struct vts_error {
    int status;                          /* VTS_OK or a negative enum vts_status */
    char message[VTS_ERROR_MESSAGE_MAX]; /* one line, no trailing newline */
};

/* Stable lowercase name of a status ("corrupt", "checksum"...); "unknown" for other values. */
VTS_API const char *vts_status_name(int status);

/* Format version this library writes, and the major version it reads. */
#define VTS_FORMAT_MAJOR 1
#define VTS_FORMAT_MINOR 0

/* Limits a reader enforces before it allocates anything (see docs/vts-format.md, "Limits"). */
#define VTS_MAX_DIMENSION    (1u << 30) /* level-0 width or height, texels */
#define VTS_MAX_PAYLOAD_PX   16384u     /* tile payload edge (content + 2 * border) */
#define VTS_MAX_LAYERS       64u
#define VTS_MAX_LEVELS       32u
#define VTS_MAX_META_BYTES   (16u << 20)
#define VTS_MAX_META_ENTRIES 4096u
#define VTS_MAX_KEY_BYTES    255u
#define VTS_LAYER_NAME_BYTES 32u /* including the terminating NUL */

/* Codec of a layer's payloads, a little-endian four-character code. */
#define VTS_FOURCC(a, b, c, d)                                                                     \
    ((uint32_t)(uint8_t)(a) | ((uint32_t)(uint8_t)(b) << 8) | ((uint32_t)(uint8_t)(c) << 16) |     \
     ((uint32_t)(uint8_t)(d) << 24))
#define VTS_CODEC_RAW  VTS_FOURCC('R', 'A', 'W', ' ')
#define VTS_CODEC_PNG  VTS_FOURCC('P', 'N', 'G', ' ')
#define VTS_CODEC_JPEG VTS_FOURCC('J', 'P', 'E', 'G')
#define VTS_CODEC_BC1  VTS_FOURCC('B', 'C', '1', ' ')
#define VTS_CODEC_BC3  VTS_FOURCC('B', 'C', '3', ' ')
#define VTS_CODEC_BC4  VTS_FOURCC('B', 'C', '4', ' ') /* RGTC1 unsigned, 1 channel */
#define VTS_CODEC_BC5  VTS_FOURCC('B', 'C', '5', ' ') /* RGTC2 unsigned, RG (3 ch: normal xy) */

/* Pinned on-disk values. */
enum vts_sample {
    VTS_SAMPLE_U8 = 1,  /* unsigned 8-bit, normalised */
    VTS_SAMPLE_U16 = 2, /* unsigned 16-bit, normalised */
    VTS_SAMPLE_F16 = 3, /* IEEE half float */
    VTS_SAMPLE_F32 = 4, /* IEEE single float */
};

enum vts_colour {
    VTS_COLOUR_SRGB = 1,   /* sRGB-encoded colour (alpha, if any, is linear) */
    VTS_COLOUR_LINEAR = 2, /* linear-light colour */
    VTS_COLOUR_NORMAL = 3, /* tangent-space normal map, xyz mapped from [-1,1] */
    VTS_COLOUR_DATA = 4,   /* non-colour data (heights, masks, classes) */
};

enum vts_store_flags {
    VTS_STORE_WRAP_X = 1u << 0, /* borders and filters wrap horizontally (tiling texture) */
    VTS_STORE_WRAP_Y = 1u << 1, /* same, vertically */
};

enum vts_layer_flags {
    VTS_LAYER_PREMULTIPLIED = 1u << 0, /* colour channels are premultiplied by alpha */
};

/* Shared geometry of every layer. tile_payload_px = tile_content_px + 2 * border_px. */
struct vts_geometry {
    uint32_t width;           /* level 0, texels */
    uint32_t height;          /* level 0, texels */
    uint32_t tile_content_px; /* texels of a tile that belong to it */
    uint32_t border_px;       /* texels copied from neighbours on each side */
    uint32_t tile_payload_px; /* edge of a stored tile: content + 2 * border */
    uint32_t level_count;     /* 1 .. vts_full_level_count() */
    uint32_t layer_count;     /* 1 .. VTS_MAX_LAYERS */
    uint32_t flags;           /* enum vts_store_flags */
};

struct vts_layer {
    uint32_t codec;                  /* VTS_CODEC_* fourcc */
    uint8_t channels;                /* 1..4 */
    uint8_t sample;                  /* enum vts_sample */
    uint8_t colour;                  /* enum vts_colour */
    uint8_t flags;                   /* enum vts_layer_flags */
    uint32_t codec_param;            /* informational (e.g. JPEG quality); 0 if none */
    char name[VTS_LAYER_NAME_BYTES]; /* "diffuse", "normal"...; NUL-terminated */
};

/* Size of one level. Level l is ceil(width / 2^l) x ceil(height / 2^l) texels (never below 1). */
struct vts_level {
    uint32_t width, height;    /* texels */
    uint32_t tiles_x, tiles_y; /* ceil(size / tile_content_px) */
    uint64_t first_tile;       /* position of tile (0,0) of this level within one layer's index */
};

struct vts_tile_entry {
    uint64_t offset; /* byte offset of the payload in the file; 0 when empty */
    uint32_t length; /* payload bytes; 0 = empty tile (no texel used, nothing stored) */
    uint32_t crc32c; /* CRC-32C (Castagnoli) of the payload; 0 when empty */
};

/* ---- geometry helpers (pure functions, no I/O) ---- */

/* Number of levels from level 0 down to the first level that fits in one tile. 0 if an argument is
 * 0. */
VTS_API uint32_t vts_full_level_count(uint32_t width, uint32_t height, uint32_t tile_content_px);

/* Checks g for consistency and limits (sizes, payload = content + 2 * border, level and layer
 * counts, index size overflow). Returns 0 or VTS_ERR_ARG / VTS_ERR_LIMIT with a message. */
VTS_API int vts_geometry_check(const struct vts_geometry *g, struct vts_error *err);

/* Fills *out for level of a checked geometry. Returns 0, or VTS_ERR_RANGE (and zeroes *out) when
 * level >= g->level_count. */
VTS_API int vts_geometry_level(const struct vts_geometry *g, uint32_t level, struct vts_level *out);

/* Tiles per layer, summed over all levels of a checked geometry. */
VTS_API uint64_t vts_geometry_tiles_per_layer(const struct vts_geometry *g);

/* Bytes of a decoded payload tile: payload_px^2 * channels * sample bytes (checked by geometry). */
VTS_API size_t vts_layer_tile_bytes(const struct vts_geometry *g, const struct vts_layer *layer);

/* Bytes per sample of an enum vts_sample, 0 if unknown. */
VTS_API unsigned vts_sample_bytes(uint32_t sample);

/* Stable names: "u8", "srgb", "raw"... ("?" if unknown). The codec name is lowercase, trimmed. */
VTS_API const char *vts_sample_name(uint32_t sample);
VTS_API const char *vts_colour_name(uint32_t colour);
VTS_API void vts_codec_name(uint32_t fourcc, char out[5]);

/* ---- reader ---- */

struct vts_store;

/* Opens and validates a store: header, layer table, every index entry and the metadata are checked
 * (bounds, overflow, overlaps, CRCs) before this returns. Returns NULL and fills err on failure
 * (VTS_ERR_IO, VTS_ERR_NOT_VTS, VTS_ERR_VERSION, VTS_ERR_CORRUPT, VTS_ERR_CHECKSUM, VTS_ERR_NOMEM).
 * Free with vts_close(). */
VTS_API struct vts_store *vts_open(const char *path, struct vts_error *err);

/* Same, over a caller-owned memory image that must outlive the store; name is used in messages. */
VTS_API struct vts_store *vts_open_memory(const void *data, size_t size, const char *name,
                                          struct vts_error *err);

/* Closes the file and frees the store. Accepts NULL. */
VTS_API void vts_close(struct vts_store *store);

/* Accessors; pointers stay valid until vts_close(). vts_store_layer() returns NULL when layer is
 * out of range; vts_store_level() returns 0, or VTS_ERR_RANGE (and zeroes *out) when level is. */
VTS_API const struct vts_geometry *vts_store_geometry(const struct vts_store *store);
VTS_API const struct vts_layer *vts_store_layer(const struct vts_store *store, uint32_t layer);
VTS_API int vts_store_level(const struct vts_store *store, uint32_t level, struct vts_level *out);
VTS_API uint64_t vts_store_file_size(const struct vts_store *store);
VTS_API const char *vts_store_name(const struct vts_store *store);
VTS_API void vts_store_version(const struct vts_store *store, unsigned *major, unsigned *minor);

/* Index entry of one tile. Returns 0, or VTS_ERR_RANGE when layer/level/tile is outside the store.
 */
VTS_API int vts_store_tile(const struct vts_store *store, uint32_t layer, uint32_t level,
                           uint32_t tx, uint32_t ty, struct vts_tile_entry *out,
                           struct vts_error *err);

/* Entry by its position in the index (0 .. vts_store_tile_count() - 1), in index order:
 * layer-major, then level 0 first, then row-major tiles; NULL when index is out of range. */
VTS_API const struct vts_tile_entry *vts_store_entry(const struct vts_store *store, uint64_t index);
VTS_API uint64_t vts_store_tile_count(const struct vts_store *store);

enum vts_read_flags {
    VTS_READ_NO_CRC = 1u << 0, /* skip the CRC-32C check of the payload */
};

/* Reads one tile's payload with a single pread into dst (dst_capacity bytes) and checks its CRC.
 * *out_len receives the payload length (0 for an empty tile: nothing is read). Safe to call from
 * many threads on one store. Returns 0, VTS_ERR_RANGE, VTS_ERR_LIMIT (dst too small), VTS_ERR_IO or
 * VTS_ERR_CHECKSUM. */
VTS_API int vts_store_read(const struct vts_store *store, uint32_t layer, uint32_t level,
                           uint32_t tx, uint32_t ty, void *dst, size_t dst_capacity,
                           size_t *out_len, unsigned flags, struct vts_error *err);

/* Largest payload length in the store (a buffer this big holds any tile). */
VTS_API uint32_t vts_store_max_payload(const struct vts_store *store);

/* Metadata: key/value text pairs in file order. Returns NULL when absent or out of range. */
VTS_API uint32_t vts_store_meta_count(const struct vts_store *store);
VTS_API const char *vts_store_meta_key(const struct vts_store *store, uint32_t i);
VTS_API const char *vts_store_meta_value(const struct vts_store *store, uint32_t i);
VTS_API const char *vts_store_meta_find(const struct vts_store *store, const char *key);

#ifdef __cplusplus
}
#endif
#endif
