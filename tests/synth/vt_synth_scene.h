/* Writing the test scenes of vt-synth-scene (tests/synth/vt_synth_scene_main.c): an OBJ file and
 * its MTL file as text, numbered v / vt / vn lines and faces, PNG textures of every colour type
 * (grey, grey + alpha, RGB, RGBA, palette with or without tRNS; 8 or 16 bits) written with libpng,
 * and a seeded random generator. Not a library for anything else: errors end the program. */
#ifndef VT_SYNTH_SCENE_H
#define VT_SYNTH_SCENE_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

/* splitmix64: a seeded, platform-independent stream (the scenes must be the same everywhere). */
struct vt_synth_scene_rng {
    uint64_t state;
};

uint64_t vt_synth_scene_rng_next(struct vt_synth_scene_rng *r);
/* Uniform in [0, 1) with 53 bits. */
double vt_synth_scene_rng_unit(struct vt_synth_scene_rng *r);
/* Uniform integer in [0, n). */
uint32_t vt_synth_scene_rng_below(struct vt_synth_scene_rng *r, uint32_t n);

/* One scene being written: OUTDIR/obj_name and OUTDIR/mtl_path (an mtl_path with a directory gives
 * an mtllib line with that directory). Counters are the 1-based index of the last line written. */
struct vt_synth_scene {
    char dir[4096];
    FILE *obj, *mtl;
    uint32_t v_count, vt_count, vn_count;
    uint64_t face_count;
    bool relative; /* write face indices as negative (relative) ones */
    struct vt_synth_scene_rng rng;
};

/* Creates OUTDIR (and parents), opens both files and writes the header comment and mtllib line. */
void vt_synth_scene_open(struct vt_synth_scene *s, const char *dir, const char *obj_name,
                         const char *mtl_path, const char *kind, uint64_t seed);
/* Closes both files (checking the writes). */
void vt_synth_scene_close(struct vt_synth_scene *s);

/* Numbered lines: return the 1-based index of the line written. Numbers with %.9g. */
uint32_t vt_synth_scene_v(struct vt_synth_scene *s, double x, double y, double z);
uint32_t vt_synth_scene_vt(struct vt_synth_scene *s, double u, double v);
uint32_t vt_synth_scene_vt3(struct vt_synth_scene *s, double u, double v, double w);
uint32_t vt_synth_scene_vn(struct vt_synth_scene *s, double x, double y, double z);

/* f with n corners: v[i] always, vt[i] and vn[i] when the array is not NULL (1-based indices). */
void vt_synth_scene_face(struct vt_synth_scene *s, uint32_t n, const uint32_t *v,
                         const uint32_t *vt, const uint32_t *vn);

/* printf into the OBJ or the MTL file (a newline is not added). */
void vt_synth_scene_obj(struct vt_synth_scene *s, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
void vt_synth_scene_mtl(struct vt_synth_scene *s, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* A texture to write: width x height texels of channels 1..4 (grey, grey + alpha, RGB, RGBA) at
 * bits 8 (uint8_t samples) or 16 (uint16_t, host order), row-major from the top row; or, with
 * palette (palette_size RGB triples, 1..256), one index per texel (uint8_t) written with bits 8 or
 * 4, and trns (palette_size alpha values) when not NULL. */
struct vt_synth_scene_png {
    uint32_t width, height, channels, bits;
    const void *pixels;
    const uint8_t *palette;
    const uint8_t *trns;
    uint32_t palette_size;
};

/* Writes the PNG at OUTDIR/rel (creating its directories). */
void vt_synth_scene_write_png(struct vt_synth_scene *s, const char *rel,
                              const struct vt_synth_scene_png *png);

/* Noise texture of 8-bit samples: every texel and channel an independent random value (so that a
 * texel shifted by one is almost always a different value). Returns a malloc'ed buffer. */
uint8_t *vt_synth_scene_noise8(struct vt_synth_scene *s, uint32_t width, uint32_t height,
                               uint32_t channels);

/* mkdir -p; exits on failure. */
void vt_synth_scene_mkdirs(const char *path);

/* Prints "vt-synth-scene: <message>" and exits 1. */
_Noreturn void vt_synth_scene_die(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

#endif
