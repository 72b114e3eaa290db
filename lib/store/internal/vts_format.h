/* Private: the on-disk layout of a .vts store (docs/vts-format.md) and little-endian access. */
#ifndef VTS_FORMAT_H
#define VTS_FORMAT_H

#include <stdint.h>
#include <string.h>

/* "\x89VTS\r\n\x1a\n": high bit and line-ending bytes catch 7-bit and text-mode transfers. */
#define VTS_MAGIC      "\x89VTS\r\n\x1a\n"
#define VTS_MAGIC_SIZE 8

#define VTS_HEADER_SIZE      128u
#define VTS_LAYER_ENTRY_SIZE 48u
#define VTS_INDEX_ENTRY_SIZE 16u

/* Header field offsets (bytes from the start of the file). */
enum vts_header_field {
    VTS_H_MAGIC = 0,
    VTS_H_MAJOR = 8,         /* u16 */
    VTS_H_MINOR = 10,        /* u16 */
    VTS_H_HEADER_SIZE = 12,  /* u32 */
    VTS_H_WIDTH = 16,        /* u32 */
    VTS_H_HEIGHT = 20,       /* u32 */
    VTS_H_CONTENT = 24,      /* u32 */
    VTS_H_BORDER = 28,       /* u32 */
    VTS_H_PAYLOAD = 32,      /* u32 */
    VTS_H_LEVELS = 36,       /* u32 */
    VTS_H_LAYERS = 40,       /* u32 */
    VTS_H_FLAGS = 44,        /* u32 */
    VTS_H_LAYER_OFFSET = 48, /* u64 */
    VTS_H_LAYER_ENTRY = 56,  /* u32 */
    VTS_H_INDEX_ENTRY = 60,  /* u32 */
    VTS_H_INDEX_OFFSET = 64, /* u64 */
    VTS_H_INDEX_COUNT = 72,  /* u64 */
    VTS_H_DATA_OFFSET = 80,  /* u64 */
    VTS_H_DATA_SIZE = 88,    /* u64 */
    VTS_H_META_OFFSET = 96,  /* u64 */
    VTS_H_META_SIZE = 104,   /* u32 */
    VTS_H_LAYERS_CRC = 108,  /* u32, CRC-32C of the layer table */
    VTS_H_INDEX_CRC = 112,   /* u32, CRC-32C of the index */
    VTS_H_META_CRC = 116,    /* u32, CRC-32C of the metadata block */
    VTS_H_RESERVED = 120,    /* u32, zero */
    VTS_H_HEADER_CRC = 124,  /* u32, CRC-32C of bytes 0..123 */
};

/* Layer table entry field offsets. */
enum vts_layer_field {
    VTS_L_CODEC = 0,     /* u32 fourcc */
    VTS_L_CHANNELS = 4,  /* u8 */
    VTS_L_SAMPLE = 5,    /* u8 */
    VTS_L_COLOUR = 6,    /* u8 */
    VTS_L_FLAGS = 7,     /* u8 */
    VTS_L_PARAM = 8,     /* u32 */
    VTS_L_RESERVED = 12, /* u32, zero */
    VTS_L_NAME = 16,     /* 32 bytes, NUL-padded */
};

static inline uint16_t vts_load_u16(const unsigned char *p)
{
    return (uint16_t)(p[0] | (p[1] << 8));
}

static inline uint32_t vts_load_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static inline uint64_t vts_load_u64(const unsigned char *p)
{
    return (uint64_t)vts_load_u32(p) | ((uint64_t)vts_load_u32(p + 4) << 32);
}

static inline void vts_store_u16(unsigned char *p, uint16_t v)
{
    p[0] = (unsigned char)v;
    p[1] = (unsigned char)(v >> 8);
}

static inline void vts_store_u32(unsigned char *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (unsigned char)(v >> (8 * i));
}

static inline void vts_store_u64(unsigned char *p, uint64_t v)
{
    vts_store_u32(p, (uint32_t)v);
    vts_store_u32(p + 4, (uint32_t)(v >> 32));
}

#endif
