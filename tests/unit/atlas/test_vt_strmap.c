/* Unit tests of the scene scan's string map (lib/atlas/vt_strmap.c). */
#include <stdio.h>
#include <string.h>

#include "internal/vt_strmap.h"
#include "vt_test.h"

#define KEYS 5000

static char keys[KEYS][16];

static void strmap_finds_every_key_across_growth(void)
{
    struct vt_strmap m = {0};
    VT_CHECK_INT_EQ(vt_strmap_get(&m, "a"), -1); /* empty, no tables yet */
    int put_failures = 0;
    for (uint32_t i = 0; i < KEYS; i++) {
        snprintf(keys[i], sizeof keys[i], "key%u", (unsigned)i);
        put_failures += vt_strmap_put(&m, keys[i], 3 * i) != 0;
    }
    VT_CHECK_INT_EQ(put_failures, 0);
    VT_CHECK_INT_EQ(m.count, KEYS);
    VT_CHECK_INT_EQ(m.capacity, 16384); /* 64 doubled until at most half full */
    int wrong = 0;
    for (uint32_t i = 0; i < KEYS; i++)
        wrong += vt_strmap_get(&m, keys[i]) != (int64_t)(3 * i);
    VT_CHECK_INT_EQ(wrong, 0);
    char probe[16] = "key4999"; /* another buffer with the same text */
    VT_CHECK_INT_EQ(vt_strmap_get(&m, probe), 3 * 4999);
    VT_CHECK_INT_EQ(vt_strmap_get(&m, "key5000"), -1);
    VT_CHECK_INT_EQ(vt_strmap_get(&m, ""), -1);
    VT_CHECK_INT_EQ(vt_strmap_get(&m, "key"), -1);
    vt_strmap_release(&m);
    VT_CHECK(m.keys == NULL && m.values == NULL && m.capacity == 0 && m.count == 0);
    VT_CHECK_INT_EQ(vt_strmap_get(&m, "key1"), -1);
    vt_strmap_release(NULL);
}

static void strmap_keeps_values_including_the_largest(void)
{
    struct vt_strmap m = {0};
    VT_CHECK_INT_EQ(vt_strmap_put(&m, "", 7), 0);
    VT_CHECK_INT_EQ(vt_strmap_put(&m, "max", UINT32_MAX), 0);
    VT_CHECK_INT_EQ(vt_strmap_get(&m, ""), 7);
    VT_CHECK_INT_EQ(vt_strmap_get(&m, "max"), UINT32_MAX);
    VT_CHECK_INT_EQ(m.capacity, 64);
    vt_strmap_release(&m);
}

int main(void)
{
    VT_RUN(strmap_finds_every_key_across_growth);
    VT_RUN(strmap_keeps_values_including_the_largest);
    return vt_test_main_result();
}
