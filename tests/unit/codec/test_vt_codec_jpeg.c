/* Tests of the jpeg tile codec (formats/codec/vt_codec_jpeg.c). */
#include <math.h>
#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vt_codec.h"
#include "vt_synth_photo.h"
#include "vt_test.h"
#include "vts.h"

/* ---- helpers ---- */

static uint64_t rng_state;

/* splitmix64: a seeded stream, identical on every machine */
static uint64_t rng_next(void)
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* Encodes img (quality, subsampling) into a fresh buffer of exactly encoded_bound() bytes; NULL
 * (and a failed check) on error. */
static unsigned char *encode_alloc(const struct vt_image *img, int quality, int subsampling,
                                   size_t *len)
{
    const struct vt_codec *jpeg = vt_codec_find("jpeg");
    size_t bound = jpeg->encoded_bound(img->width, img->height, img->channels, img->sample);
    unsigned char *buf = malloc(bound ? bound : 1);
    struct vt_codec_params params = {.quality = quality, .subsampling = subsampling};
    struct vts_error err = {0};
    int rc = jpeg->encode(img, &params, buf, bound, len, &err);
    VT_CHECK_INT_EQ(rc, 0);
    if (rc != 0) {
        fprintf(stderr, "  encode: %s\n", err.message);
        free(buf);
        return NULL;
    }
    VT_CHECK(*len > 0 && *len <= bound);
    return buf;
}

/* Decodes payload into a fresh u8 image (stride padded by 5 bytes preset to 0xcd). */
static int decode_into(const void *payload, size_t len, struct vt_image *dst, uint32_t w,
                       uint32_t h, uint32_t channels, struct vts_error *err)
{
    *dst = (struct vt_image){w, h, channels, VTS_SAMPLE_U8, (size_t)w * channels + 5, NULL};
    dst->pixels = malloc(dst->stride * h);
    memset(dst->pixels, 0xcd, dst->stride * h);
    return vt_codec_find("jpeg")->decode(payload, len, dst, err);
}

/* Encodes and decodes img; returns the PSNR (0 on failure); *len_out gets the payload size. */
static double round_trip_psnr(const struct vt_image *img, int quality, int subsampling,
                              size_t *len_out)
{
    size_t len = 0;
    unsigned char *payload = encode_alloc(img, quality, subsampling, &len);
    struct vt_image dst;
    struct vts_error err = {0};
    int rc = decode_into(payload, len, &dst, img->width, img->height, img->channels, &err);
    VT_CHECK_INT_EQ(rc, 0);
    if (rc)
        fprintf(stderr, "  decode: %s\n", err.message);
    bool padding_kept = true;
    for (uint32_t y = 0; y < dst.height; y++)
        padding_kept &=
            ((unsigned char *)dst.pixels)[y * dst.stride + dst.width * dst.channels] == 0xcd;
    VT_CHECK(padding_kept);
    double psnr = rc ? 0 : vt_synth_psnr_u8(img, &dst);
    if (len_out)
        *len_out = len;
    free(dst.pixels);
    free(payload);
    return psnr;
}

/* Copy of the first len bytes in a fresh allocation of exactly len, so ASan sees over-reads. */
static unsigned char *dup_prefix(const unsigned char *src, size_t len)
{
    unsigned char *p = malloc(len ? len : 1);
    memcpy(p, src, len);
    return p;
}

/* ---- round trips ---- */

static void jpeg_round_trips_grey_and_rgb(void)
{
    static const uint32_t sizes[] = {256, 264, 1};
    for (size_t s = 0; s < 3; s++) {
        for (uint32_t channels = 1; channels <= 3; channels += 2) {
            struct vt_image img = vt_synth_photo(sizes[s], sizes[s], channels, 1, 0.6);
            double q95 = round_trip_psnr(&img, 95, 0, NULL);
            double q85 = round_trip_psnr(&img, 85, 0, NULL);
            fprintf(stderr, "  %ux%u x%u: q95 %.2f dB, q85 %.2f dB\n", sizes[s], sizes[s], channels,
                    q95, q85);
            VT_CHECK(q95 >= (sizes[s] == 1 ? 35.0 : 38.0));
            VT_CHECK(q85 >= (sizes[s] == 1 ? 30.0 : 36.0));
            VT_CHECK(q95 > q85 || sizes[s] == 1);
            free(img.pixels);
        }
    }
}

static void jpeg_444_is_at_least_as_good_as_420(void)
{
    struct vt_image img = vt_synth_photo(256, 256, 3, 2, 1.0); /* colourful */
    size_t len420 = 0, len422 = 0, len444 = 0;
    double p420 = round_trip_psnr(&img, 85, 420, &len420);
    double p422 = round_trip_psnr(&img, 85, 422, &len422);
    double p444 = round_trip_psnr(&img, 85, 444, &len444);
    fprintf(stderr, "  q85: 4:2:0 %.2f dB %zu B, 4:2:2 %.2f dB %zu B, 4:4:4 %.2f dB %zu B\n", p420,
            len420, p422, len422, p444, len444);
    VT_CHECK(p444 >= p420);
    VT_CHECK(p422 >= p420 && p444 >= p422);
    VT_CHECK(len420 < len422 && len422 < len444);
    /* 0 is the default, 420 */
    size_t len_default = 0, len_explicit = 0;
    unsigned char *a = encode_alloc(&img, 85, 0, &len_default);
    unsigned char *b = encode_alloc(&img, 85, 420, &len_explicit);
    VT_CHECK(a && b && len_default == len_explicit && memcmp(a, b, len_default) == 0);
    free(a);
    free(b);
    free(img.pixels);
}

static void jpeg_size_and_quality_grow_with_quality(void)
{
    struct vt_image img = vt_synth_photo(256, 256, 3, 3, 0.6);
    size_t len50 = 0, len85 = 0, len95 = 0;
    double p50 = round_trip_psnr(&img, 50, 420, &len50);
    double p85 = round_trip_psnr(&img, 85, 420, &len85);
    double p95 = round_trip_psnr(&img, 95, 420, &len95);
    VT_CHECK(len50 < len85 && len85 < len95);
    VT_CHECK(p50 < p85 && p85 < p95);
    /* quality 0 is 85 */
    size_t len_default = 0, len_q85 = 0;
    unsigned char *a = encode_alloc(&img, 0, 0, &len_default);
    unsigned char *b = encode_alloc(&img, 85, 0, &len_q85);
    VT_CHECK(a && b && len_default == len_q85 && memcmp(a, b, len_q85) == 0);
    free(a);
    free(b);
    free(img.pixels);
}

static void jpeg_reads_rows_through_the_stride(void)
{
    struct vt_image tight = vt_synth_photo(40, 24, 3, 4, 0.6), padded = tight;
    padded.stride = tight.stride + 9;
    padded.pixels = malloc(padded.stride * tight.height);
    memset(padded.pixels, 0x55, padded.stride * tight.height);
    for (uint32_t y = 0; y < tight.height; y++)
        memcpy((char *)padded.pixels + y * padded.stride, (char *)tight.pixels + y * tight.stride,
               tight.stride);
    size_t len_a = 0, len_b = 0;
    unsigned char *a = encode_alloc(&tight, 90, 444, &len_a);
    unsigned char *b = encode_alloc(&padded, 90, 444, &len_b);
    VT_CHECK(a && b && len_a == len_b && memcmp(a, b, len_a) == 0);
    free(a);
    free(b);
    free(padded.pixels);
    free(tight.pixels);
}

/* ---- refusals ---- */

static void jpeg_check_refuses_alpha_and_deep_samples(void)
{
    const struct vt_codec *jpeg = vt_codec_find("jpeg");
    struct vts_error err = {0};
    VT_CHECK(jpeg && jpeg->fourcc == VTS_CODEC_JPEG && !jpeg->lossless);
    VT_CHECK(vt_codec_by_fourcc(VTS_CODEC_JPEG) == jpeg);
    VT_CHECK_INT_EQ(jpeg->check(256, 1, VTS_SAMPLE_U8, &err), 0);
    VT_CHECK_INT_EQ(jpeg->check(258, 3, VTS_SAMPLE_U8, &err), 0);
    for (uint32_t channels = 2; channels <= 4; channels += 2) {
        VT_CHECK_INT_EQ(jpeg->check(256, channels, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
        VT_CHECK_STR_CONTAINS(err.message, "jpeg cannot store alpha: use png, bc3 or raw");
        VT_CHECK_STR_CONTAINS(err.message, "vt-tiles drops an alpha that is opaque everywhere");
    }
    VT_CHECK_INT_EQ(jpeg->check(256, 3, VTS_SAMPLE_U16, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_CONTAINS(err.message, "jpeg stores 8-bit samples only");
    VT_CHECK_STR_CONTAINS(err.message, "use png or raw");
    VT_CHECK_INT_EQ(jpeg->check(256, 1, VTS_SAMPLE_F32, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_CONTAINS(err.message, "jpeg stores 8-bit samples only (got f32)");
    VT_CHECK_INT_EQ(jpeg->check(256, 3, VTS_SAMPLE_F16, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_INT_EQ(jpeg->check(256, 5, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_INT_EQ(jpeg->check(0, 3, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_INT_EQ(jpeg->check(65501, 3, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_INT_EQ(jpeg->encoded_bound(256, 256, 4, VTS_SAMPLE_U8), 0);
    VT_CHECK_INT_EQ(jpeg->encoded_bound(256, 256, 3, VTS_SAMPLE_U16), 0);
    VT_CHECK(jpeg->encoded_bound(256, 256, 3, VTS_SAMPLE_U8) > 256 * 256 * 3);
    VT_CHECK(jpeg->encoded_bound(256, 256, 1, VTS_SAMPLE_U8) > 256 * 256);
}

static void jpeg_encode_refuses_bad_params_and_small_buffers(void)
{
    const struct vt_codec *jpeg = vt_codec_find("jpeg");
    struct vt_image img = vt_synth_photo(16, 16, 3, 5, 0.6);
    size_t bound = jpeg->encoded_bound(16, 16, 3, VTS_SAMPLE_U8), len = 99;
    unsigned char *buf = malloc(bound);
    struct vts_error err = {0};
    struct vt_codec_params params = {.quality = 101};
    VT_CHECK_INT_EQ(jpeg->encode(&img, &params, buf, bound, &len, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "quality 101");
    VT_CHECK_INT_EQ(len, 0);
    params = (struct vt_codec_params){.quality = -1};
    VT_CHECK_INT_EQ(jpeg->encode(&img, &params, buf, bound, &len, &err), VTS_ERR_ARG);
    params = (struct vt_codec_params){.subsampling = 411};
    VT_CHECK_INT_EQ(jpeg->encode(&img, &params, buf, bound, &len, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "subsampling 411");
    VT_CHECK_INT_EQ(jpeg->encode(&img, NULL, buf, 100, &len, &err), VTS_ERR_LIMIT);
    VT_CHECK_INT_EQ(jpeg->encode(&img, NULL, buf, bound, &len, &err), 0);
    img.channels = 4;
    VT_CHECK_INT_EQ(jpeg->encode(&img, NULL, buf, bound, &len, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_CONTAINS(err.message, "jpeg cannot store alpha");
    img.channels = 3;
    img.sample = VTS_SAMPLE_U16;
    VT_CHECK_INT_EQ(jpeg->encode(&img, NULL, buf, bound, &len, &err), VTS_ERR_UNSUPPORTED);
    free(buf);
    free(img.pixels);
}

/* ---- hostile payloads ---- */

/* Decodes the first cut bytes of payload (a fresh allocation); true when it fails cleanly. */
static bool prefix_fails_cleanly(const unsigned char *payload, size_t cut, uint32_t edge,
                                 uint32_t channels)
{
    unsigned char *prefix = dup_prefix(payload, cut);
    struct vt_image dst;
    struct vts_error err = {0};
    int rc = decode_into(prefix, cut, &dst, edge, edge, channels, &err);
    bool clean = rc == VTS_ERR_BAD_INPUT && strncmp(err.message, "jpeg payload: ", 14) == 0;
    if (!clean)
        fprintf(stderr, "  cut %zu: rc %d '%s'\n", cut, rc, err.message);
    free(dst.pixels);
    free(prefix);
    return clean;
}

static void jpeg_decode_rejects_truncated_payloads(void)
{
    for (uint32_t channels = 1; channels <= 3; channels += 2) {
        struct vt_image img = vt_synth_photo(64, 64, channels, 6, 0.6);
        size_t len = 0;
        unsigned char *payload = encode_alloc(&img, 90, 420, &len);
        int failures = 0, cuts = 0;
        for (size_t cut = 0; payload && cut < len; cut += 97, cuts++)
            failures += !prefix_fails_cleanly(payload, cut, 64, channels);
        for (size_t cut = len - 2; payload && cut < len; cut++, cuts++) /* inside EOI */
            failures += !prefix_fails_cleanly(payload, cut, 64, channels);
        VT_CHECK(cuts > 10);
        VT_CHECK_INT_EQ(failures, 0);
        free(payload);
        free(img.pixels);
    }
}

static void jpeg_decode_rejects_garbage(void)
{
    rng_state = 7;
    int failures = 0;
    for (size_t len = 0; len < 600; len += 5) {
        unsigned char *junk = malloc(len + 1);
        for (size_t i = 0; i < len; i++)
            junk[i] = (unsigned char)rng_next();
        if (len >= 2 && len % 2) /* half of them start with an SOI marker */
            junk[0] = 0xff, junk[1] = 0xd8;
        struct vt_image dst;
        struct vts_error err = {0};
        if (decode_into(junk, len, &dst, 8, 8, 3, &err) != VTS_ERR_BAD_INPUT)
            failures++;
        free(dst.pixels);
        free(junk);
    }
    VT_CHECK_INT_EQ(failures, 0);
}

static void jpeg_decode_survives_bit_flips(void)
{
    struct vt_image img = vt_synth_photo(32, 32, 3, 8, 0.6);
    size_t len = 0;
    unsigned char *payload = encode_alloc(&img, 80, 420, &len);
    rng_state = 8;
    int bad_status = 0, rejected = 0;
    for (int i = 0; payload && i < 2000; i++) {
        unsigned char *copy = dup_prefix(payload, len);
        for (int flips = 1 + i % 3; flips > 0; flips--)
            copy[2 + rng_next() % (len - 2)] ^= (unsigned char)(1u << (rng_next() % 8));
        struct vt_image dst;
        struct vts_error err = {0};
        int rc = decode_into(copy, len, &dst, 32, 32, 3, &err);
        rejected += rc != 0;
        bad_status += rc != 0 && rc != VTS_ERR_BAD_INPUT;
        free(dst.pixels);
        free(copy);
    }
    VT_CHECK_INT_EQ(bad_status, 0);
    VT_CHECK(rejected > 100); /* corrupt streams are noticed (warnings are errors) */
    free(payload);
    free(img.pixels);
}

/* Encodes a w x h tile of channels and decodes it as another shape: must fail with expect. */
static void check_mismatch(uint32_t w, uint32_t h, uint32_t channels, uint32_t tw, uint32_t th,
                           uint32_t tchannels, const char *expect)
{
    struct vt_image img = vt_synth_photo(w, h, channels, 9, 0.6);
    size_t len = 0;
    unsigned char *payload = encode_alloc(&img, 85, 420, &len);
    struct vt_image dst;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(decode_into(payload, len, &dst, tw, th, tchannels, &err), VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_CONTAINS(err.message, expect);
    free(dst.pixels);
    free(payload);
    free(img.pixels);
}

static void jpeg_decode_rejects_other_shapes(void)
{
    check_mismatch(264, 256, 3, 256, 256, 3, "jpeg payload: width 264 != tile 256");
    check_mismatch(256, 264, 3, 256, 256, 3, "jpeg payload: height 264 != tile 256");
    check_mismatch(16, 16, 1, 16, 16, 3, "jpeg payload: greyscale JPEG for a 3-channel tile");
    check_mismatch(16, 16, 3, 16, 16, 1, "jpeg payload: colour JPEG for a greyscale tile");
    /* a destination jpeg never produces is the caller's error */
    struct vt_image img = vt_synth_photo(16, 16, 3, 9, 0.6);
    size_t len = 0;
    unsigned char *payload = encode_alloc(&img, 85, 420, &len);
    struct vt_image dst;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(decode_into(payload, len, &dst, 16, 16, 4, &err), VTS_ERR_UNSUPPORTED);
    free(dst.pixels);
    free(payload);
    free(img.pixels);
}

static void jpeg_decodes_again_after_a_failed_decode(void)
{
    /* libjpeg-turbo 2.1.5 leaves a handle mid-header after a failed header read; the codec must
     * not reuse it as it is */
    struct vt_image img = vt_synth_photo(24, 24, 3, 10, 0.6);
    size_t len = 0;
    unsigned char *payload = encode_alloc(&img, 85, 420, &len);
    int failures = 0;
    for (size_t cut = 3; payload && cut < len; cut += 31) {
        unsigned char *prefix = dup_prefix(payload, cut);
        struct vt_image dst;
        failures += decode_into(prefix, cut, &dst, 24, 24, 3, NULL) != VTS_ERR_BAD_INPUT;
        free(dst.pixels);
        struct vts_error err = {0};
        int rc = decode_into(payload, len, &dst, 24, 24, 3, &err);
        if (rc)
            fprintf(stderr, "  after cut %zu: %s\n", cut, err.message);
        failures += rc != 0;
        free(dst.pixels);
        free(prefix);
    }
    VT_CHECK_INT_EQ(failures, 0);
    free(payload);
    free(img.pixels);
}

/* ---- threads ---- */

#define THREAD_TILES 6

struct thread_job {
    const struct vt_image *tiles; /* THREAD_TILES of them */
    unsigned char *payload[THREAD_TILES];
    size_t len[THREAD_TILES];
    double psnr_sum;
    int failures;
};

/* Encodes and decodes every tile three times (reusing this thread's TurboJPEG handles). */
static void *thread_job_run(void *arg)
{
    struct thread_job *job = arg;
    const struct vt_codec *jpeg = vt_codec_find("jpeg");
    for (int round = 0; round < 3; round++) {
        for (int t = 0; t < THREAD_TILES; t++) {
            const struct vt_image *img = &job->tiles[t];
            size_t bound = jpeg->encoded_bound(img->width, img->height, img->channels, img->sample);
            free(job->payload[t]);
            job->payload[t] = malloc(bound);
            struct vt_codec_params params = {.quality = 60 + 7 * t, .subsampling = t % 2 ? 444 : 0};
            if (jpeg->encode(img, &params, job->payload[t], bound, &job->len[t], NULL) != 0) {
                job->failures++;
                continue;
            }
            struct vt_image dst = *img;
            dst.pixels = malloc(img->stride * img->height);
            if (jpeg->decode(job->payload[t], job->len[t], &dst, NULL) != 0)
                job->failures++;
            else if (round == 0)
                job->psnr_sum += vt_synth_psnr_u8(img, &dst);
            free(dst.pixels);
        }
    }
    return NULL;
}

static void jpeg_threads_give_the_same_bytes_as_one_thread(void)
{
    struct vt_image tiles[THREAD_TILES];
    for (int t = 0; t < THREAD_TILES; t++)
        tiles[t] = vt_synth_photo(128, 128, t % 3 ? 3 : 1, 20u + (uint32_t)t, 0.8);
    struct thread_job alone = {tiles, {NULL}, {0}, 0, 0}, jobs[2];
    thread_job_run(&alone);
    VT_CHECK_INT_EQ(alone.failures, 0);
    pthread_t threads[2];
    for (int i = 0; i < 2; i++) {
        jobs[i] = (struct thread_job){tiles, {NULL}, {0}, 0, 0};
        VT_CHECK_INT_EQ(pthread_create(&threads[i], NULL, thread_job_run, &jobs[i]), 0);
    }
    for (int i = 0; i < 2; i++) {
        pthread_join(threads[i], NULL); /* the thread's handles are destroyed as it exits */
        VT_CHECK_INT_EQ(jobs[i].failures, 0);
        VT_CHECK(jobs[i].psnr_sum == alone.psnr_sum);
        int differ = 0;
        for (int t = 0; t < THREAD_TILES; t++) {
            differ += jobs[i].len[t] != alone.len[t] ||
                      memcmp(jobs[i].payload[t], alone.payload[t], alone.len[t]) != 0;
            free(jobs[i].payload[t]);
        }
        VT_CHECK_INT_EQ(differ, 0);
    }
    for (int t = 0; t < THREAD_TILES; t++) {
        free(alone.payload[t]);
        free(tiles[t].pixels);
    }
}

int main(void)
{
    VT_RUN(jpeg_round_trips_grey_and_rgb);
    VT_RUN(jpeg_444_is_at_least_as_good_as_420);
    VT_RUN(jpeg_size_and_quality_grow_with_quality);
    VT_RUN(jpeg_reads_rows_through_the_stride);
    VT_RUN(jpeg_check_refuses_alpha_and_deep_samples);
    VT_RUN(jpeg_encode_refuses_bad_params_and_small_buffers);
    VT_RUN(jpeg_decode_rejects_truncated_payloads);
    VT_RUN(jpeg_decode_rejects_garbage);
    VT_RUN(jpeg_decode_survives_bit_flips);
    VT_RUN(jpeg_decode_rejects_other_shapes);
    VT_RUN(jpeg_decodes_again_after_a_failed_decode);
    VT_RUN(jpeg_threads_give_the_same_bytes_as_one_thread);
    return vt_test_main_result();
}
