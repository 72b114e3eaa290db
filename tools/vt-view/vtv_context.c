/* vt-view GL contexts: EGL surfaceless through libepoxy, or GLFW (X11, GLX). */
#include "vtv_context.h"
#include "vt_error.h"

#include <stdlib.h>
#include <string.h>

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

struct vtv_context {
    EGLDisplay dpy;
    EGLContext ctx;
    GLFWwindow *win;
    double last_x, last_y;
    bool prev_f, prev_g; /* key states of the last frame (toggles act on presses) */
    double scroll;
};

struct vtv_context *vtv_context_headless(struct vts_error *err)
{
    struct vtv_context *c = calloc(1, sizeof(*c));
    if (!c) {
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        return NULL;
    }
    c->dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (c->dpy == EGL_NO_DISPLAY || !eglInitialize(c->dpy, NULL, NULL)) {
        vt_error_set(err, VTS_ERR_UNSUPPORTED, "no EGL surfaceless display (error 0x%x)",
                     (unsigned)eglGetError());
        free(c);
        return NULL;
    }
    eglBindAPI(EGL_OPENGL_API);
    EGLint ca[] = {EGL_SURFACE_TYPE, 0, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig cfg;
    EGLint n = 0;
    EGLint xa[] = {EGL_CONTEXT_MAJOR_VERSION,
                   3,
                   EGL_CONTEXT_MINOR_VERSION,
                   3,
                   EGL_CONTEXT_OPENGL_PROFILE_MASK,
                   EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                   EGL_NONE};
    if (!eglChooseConfig(c->dpy, ca, &cfg, 1, &n) || n < 1 ||
        (c->ctx = eglCreateContext(c->dpy, cfg, EGL_NO_CONTEXT, xa)) == EGL_NO_CONTEXT ||
        !eglMakeCurrent(c->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, c->ctx)) {
        vt_error_set(err, VTS_ERR_UNSUPPORTED,
                     "cannot create an OpenGL 3.3 core EGL context (0x%x)",
                     (unsigned)eglGetError());
        vtv_context_destroy(c);
        return NULL;
    }
    return c;
}

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
    (void)dx;
    struct vtv_context *c = glfwGetWindowUserPointer(w);
    c->scroll += dy;
}

struct vtv_context *vtv_context_window(uint32_t width, uint32_t height, const char *title,
                                       struct vts_error *err)
{
    if (!glfwInit()) {
        const char *msg = NULL;
        glfwGetError(&msg);
        vt_error_set(err, VTS_ERR_UNSUPPORTED, "cannot open a window: %s (use --headless)",
                     msg ? msg : "glfwInit failed");
        return NULL;
    }
    struct vtv_context *c = calloc(1, sizeof(*c));
    if (!c) {
        glfwTerminate();
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        return NULL;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    c->win = glfwCreateWindow((int)width, (int)height, title, NULL, NULL);
    if (!c->win) {
        const char *msg = NULL;
        glfwGetError(&msg);
        vt_error_set(err, VTS_ERR_UNSUPPORTED, "cannot create a window: %s",
                     msg ? msg : "unknown error");
        free(c);
        glfwTerminate();
        return NULL;
    }
    glfwSetWindowUserPointer(c->win, c);
    glfwSetScrollCallback(c->win, on_scroll);
    glfwMakeContextCurrent(c->win);
    glfwSwapInterval(1);
    glfwGetCursorPos(c->win, &c->last_x, &c->last_y);
    return c;
}

void vtv_context_destroy(struct vtv_context *c)
{
    if (!c)
        return;
    if (c->win) {
        glfwDestroyWindow(c->win);
        glfwTerminate();
    }
    if (c->dpy != EGL_NO_DISPLAY && c->dpy) {
        eglMakeCurrent(c->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (c->ctx != EGL_NO_CONTEXT && c->ctx)
            eglDestroyContext(c->dpy, c->ctx);
        /* No eglTerminate: it unloads Mesa's driver, whose llvmpipe keeps two 56-byte objects
         * per large framebuffer that LeakSanitizer then reports as leaks from an unknown module
         * (ASan builds of the tests). The display is per process; the process ends next. */
        eglReleaseThread();
    }
    free(c);
}

bool vtv_context_is_window(const struct vtv_context *c)
{
    return c->win != NULL;
}

static bool key(GLFWwindow *w, int k)
{
    return glfwGetKey(w, k) == GLFW_PRESS;
}

void vtv_context_frame(struct vtv_context *c, struct vtv_input *in, uint32_t *w, uint32_t *h)
{
    memset(in, 0, sizeof(*in));
    in->zoom = 1.0;
    if (!c->win)
        return;
    glfwSwapBuffers(c->win);
    glfwPollEvents();
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(c->win, &fw, &fh);
    *w = (uint32_t)(fw > 0 ? fw : 1);
    *h = (uint32_t)(fh > 0 ? fh : 1);
    double x, y;
    glfwGetCursorPos(c->win, &x, &y);
    if (glfwGetMouseButton(c->win, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) {
        in->pan_x = x - c->last_x;
        in->pan_y = y - c->last_y;
        in->orbit_x = in->pan_x;
        in->orbit_y = in->pan_y;
    }
    c->last_x = x;
    c->last_y = y;
    double step = 8.0;
    if (key(c->win, GLFW_KEY_LEFT) || key(c->win, GLFW_KEY_A))
        in->pan_x += step;
    if (key(c->win, GLFW_KEY_RIGHT) || key(c->win, GLFW_KEY_D))
        in->pan_x -= step;
    if (key(c->win, GLFW_KEY_UP) || key(c->win, GLFW_KEY_W))
        in->pan_y += step;
    if (key(c->win, GLFW_KEY_DOWN) || key(c->win, GLFW_KEY_S))
        in->pan_y -= step;
    if (key(c->win, GLFW_KEY_EQUAL) || key(c->win, GLFW_KEY_KP_ADD))
        in->zoom *= 1.03;
    if (key(c->win, GLFW_KEY_MINUS) || key(c->win, GLFW_KEY_KP_SUBTRACT))
        in->zoom /= 1.03;
    if (c->scroll != 0.0) {
        for (double s = c->scroll; s > 0; s -= 1)
            in->zoom *= 1.2;
        for (double s = c->scroll; s < 0; s += 1)
            in->zoom /= 1.2;
        c->scroll = 0.0;
    }
    bool f = key(c->win, GLFW_KEY_F), d = key(c->win, GLFW_KEY_G);
    in->toggle_filter = f && !c->prev_f;
    in->cycle_debug = d && !c->prev_g;
    c->prev_f = f;
    c->prev_g = d;
    in->quit =
        glfwWindowShouldClose(c->win) || key(c->win, GLFW_KEY_ESCAPE) || key(c->win, GLFW_KEY_Q);
}

void vtv_context_set_title(struct vtv_context *c, const char *title)
{
    if (c->win)
        glfwSetWindowTitle(c->win, title);
}
