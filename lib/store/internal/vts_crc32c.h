/* CRC-32C (Castagnoli, reflected polynomial 0x82F63B78), as used by iSCSI, ext4 and the .vts index.
 * Part of libvts: libc only, so that a renderer can vendor the reader. */
#ifndef VTS_CRC32C_H
#define VTS_CRC32C_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Extends crc (0 for a fresh start) over len bytes of data; vts_crc32c(0, "123456789", 9) is
 * 0xE3069283. Uses the SSE4.2 crc32 instruction when the CPU has it. Thread-safe. */
uint32_t vts_crc32c(uint32_t crc, const void *data, size_t len);

#ifdef __cplusplus
}
#endif
#endif
