/* vt-view cameras: 2D (orthographic pan/zoom over the virtual texture) and 3D (perspective
 * look-at), their matrices, and camera files (one frame per line; the last line repeats):
 *   2D: "CX CY ZOOM"  centre in level-0 texels, screen pixels per texel
 *   3D: "EX EY EZ TX TY TZ FOVY"  eye, target, vertical field of view in degrees */
#ifndef VTV_CAMERA_H
#define VTV_CAMERA_H

#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"

struct vtv_camera {
    double v[7]; /* 2D: cx, cy, zoom; 3D: eye xyz, target xyz, fovy */
};

struct vtv_camera_path {
    struct vtv_camera *frames;
    size_t count;
};

/* Reads a camera file with `values` numbers per line (3 or 7); '#' starts a comment. */
int vtv_camera_path_read(struct vtv_camera_path *p, const char *path, unsigned values,
                         struct vts_error *err);
void vtv_camera_path_free(struct vtv_camera_path *p);
const struct vtv_camera *vtv_camera_path_at(const struct vtv_camera_path *p, uint64_t frame);

/* Column-major matrices. 2D maps level-0 texel (x, y, 0) so that row 0 is at the top. */
void vtv_camera_matrix_2d(const struct vtv_camera *c, uint32_t w, uint32_t h, float out[16]);
void vtv_camera_matrix_3d(const struct vtv_camera *c, uint32_t w, uint32_t h, double near_z,
                          double far_z, float out[16]);

/* Orbit: frame i of n around the box [lo, hi] (eye on a circle above the centre). */
void vtv_camera_orbit(const double lo[3], const double hi[3], uint64_t i, uint64_t n,
                      struct vtv_camera *out);

#endif
