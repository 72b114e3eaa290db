/* CRC re-sealing of .vts images; libc + vts_crc32c only, so that the fuzz target can use it. */
#include "robust/vts_reseal.h"

#include "internal/vts_crc32c.h"
#include "internal/vts_format.h"

/* [off, off + len) inside [0, size)? */
static bool inside(uint64_t off, uint64_t len, size_t size)
{
    return off <= size && len <= size - off;
}

static bool reseal(unsigned char *data, size_t size, uint64_t off, uint64_t len, unsigned crc_field)
{
    if (size < VTS_HEADER_SIZE || !inside(off, len, size))
        return false;
    vts_store_u32(data + crc_field, vts_crc32c(0, data + off, (size_t)len));
    return true;
}

bool vts_reseal_layers(unsigned char *data, size_t size)
{
    if (size < VTS_HEADER_SIZE)
        return false;
    uint64_t len = (uint64_t)vts_load_u32(data + VTS_H_LAYER_ENTRY) *
                   vts_load_u32(data + VTS_H_LAYERS); /* < 2^64 */
    return reseal(data, size, vts_load_u64(data + VTS_H_LAYER_OFFSET), len, VTS_H_LAYERS_CRC);
}

bool vts_reseal_index(unsigned char *data, size_t size)
{
    if (size < VTS_HEADER_SIZE)
        return false;
    uint64_t count = vts_load_u64(data + VTS_H_INDEX_COUNT);
    uint32_t entry = vts_load_u32(data + VTS_H_INDEX_ENTRY);
    if (entry != 0 && count > UINT64_MAX / entry)
        return false;
    return reseal(data, size, vts_load_u64(data + VTS_H_INDEX_OFFSET), count * entry,
                  VTS_H_INDEX_CRC);
}

bool vts_reseal_meta(unsigned char *data, size_t size)
{
    if (size < VTS_HEADER_SIZE)
        return false;
    return reseal(data, size, vts_load_u64(data + VTS_H_META_OFFSET),
                  vts_load_u32(data + VTS_H_META_SIZE), VTS_H_META_CRC);
}

bool vts_reseal_header(unsigned char *data, size_t size)
{
    return reseal(data, size, 0, VTS_H_HEADER_CRC, VTS_H_HEADER_CRC);
}

void vts_reseal_all(unsigned char *data, size_t size)
{
    vts_reseal_layers(data, size);
    vts_reseal_index(data, size);
    vts_reseal_meta(data, size);
    vts_reseal_header(data, size);
}
