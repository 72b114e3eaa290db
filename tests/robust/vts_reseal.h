/* Re-sealing the CRCs of a deliberately corrupted .vts image (tests and fuzz targets), so that a
 * reader's structural checks, not only its checksums, are reached. */
#ifndef VTS_RESEAL_H
#define VTS_RESEAL_H

#include <stdbool.h>
#include <stddef.h>

/* Recompute the CRC of one structure from the (possibly corrupted) header's offsets and sizes and
 * store it in the header. Each returns false and changes nothing when the header does not fit or
 * the structure does not lie inside the buffer. The header CRC must be resealed last. */
bool vts_reseal_layers(unsigned char *data, size_t size);
bool vts_reseal_index(unsigned char *data, size_t size);
bool vts_reseal_meta(unsigned char *data, size_t size);
bool vts_reseal_header(unsigned char *data, size_t size);
/* All four, in the right order. */
void vts_reseal_all(unsigned char *data, size_t size);

#endif
