/* vt-view: selection stores (see vtv_select.h). */
#include "vtv_select.h"

#include <stdio.h>
#include <string.h>

int vtv_select_store(const struct vts_store *s, char *why, size_t cap)
{
    static const char *const selections[] = {"nearest", "mode", "min", "max"};
    const char *colour = vts_store_meta_find(s, "colour");
    const char *filter = vts_store_meta_find(s, "filter");
    if (cap)
        why[0] = '\0';
    if (colour && strcmp(colour, "index") == 0) {
        snprintf(why, cap, "colour=%s", colour);
        return 1;
    }
    for (size_t i = 0; filter && i < sizeof(selections) / sizeof(selections[0]); i++)
        if (strcmp(filter, selections[i]) == 0) {
            snprintf(why, cap, "filter=%s", filter);
            return 1;
        }
    return 0;
}

void vtv_index_colour(uint32_t v, uint8_t rgb[3])
{
    uint32_t h = v * 0x9E3779B1u;
    h ^= h >> 16;
    h *= 0x85EBCA6Bu;
    h ^= h >> 13;
    for (int c = 0; c < 3; c++) {
        uint32_t b = (h >> (8 * c)) & 255u;
        rgb[c] = (uint8_t)(b < 48 ? 48 : b);
    }
}
