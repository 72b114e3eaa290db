/* vt-view GL programs: compile and link with the log in the error. */
#include "vtv_program.h"

static GLuint compile(GLenum type, const char *const *src, int pieces, const char *what,
                      struct vts_error *err)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, pieces, src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        glGetShaderInfoLog(s, sizeof(log), NULL, log);
        vt_error_set(err, VTS_ERR_UNSUPPORTED, "cannot compile the %s %s shader: %s", what,
                     type == GL_VERTEX_SHADER ? "vertex" : "fragment", log);
        glDeleteShader(s);
        return 0;
    }
    return s;
}

GLuint vtv_program_build(const char *const *vs_src, int vs_count, const char *const *fs_src,
                         int fs_count, const char *what, struct vts_error *err)
{
    GLuint vs = compile(GL_VERTEX_SHADER, vs_src, vs_count, what, err);
    GLuint fs = vs ? compile(GL_FRAGMENT_SHADER, fs_src, fs_count, what, err) : 0;
    if (!fs) {
        glDeleteShader(vs);
        return 0;
    }
    GLuint p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    glLinkProgram(p);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        glGetProgramInfoLog(p, sizeof(log), NULL, log);
        vt_error_set(err, VTS_ERR_UNSUPPORTED, "cannot link the %s program: %s", what, log);
        glDeleteProgram(p);
        return 0;
    }
    return p;
}
