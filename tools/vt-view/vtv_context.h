/* vt-view GL contexts: EGL surfaceless (headless, Mesa) or a GLFW window. Both give a current
 * OpenGL 3.3 core context; rendering always goes to the renderer's own framebuffer. */
#ifndef VTV_CONTEXT_H
#define VTV_CONTEXT_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"

struct vtv_input {
    double pan_x, pan_y; /* screen pixels dragged or keyed this frame */
    double zoom;         /* multiplicative zoom this frame (1 = none) */
    double orbit_x, orbit_y;
    bool toggle_filter, cycle_debug, quit;
};

struct vtv_context;

struct vtv_context *vtv_context_headless(struct vts_error *err);
struct vtv_context *vtv_context_window(uint32_t width, uint32_t height, const char *title,
                                       struct vts_error *err);
void vtv_context_destroy(struct vtv_context *c);

bool vtv_context_is_window(const struct vtv_context *c);
/* Window: swaps, polls events and fills *in (zeroed first); framebuffer size in *w, *h. */
void vtv_context_frame(struct vtv_context *c, struct vtv_input *in, uint32_t *w, uint32_t *h);
void vtv_context_set_title(struct vtv_context *c, const char *title);

#endif
