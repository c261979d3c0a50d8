/* bench_gl_context.c — an offscreen llvmpipe context: EGL's surfaceless
 * platform (no window, no display server), a GL 4.5 core context that draws
 * into framebuffer objects only. */
#define GL_GLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench_gl.h"

/* glClipControl (z in [0, 1], as softrast's clip volume) is core in 4.5. */
#define GL_MAJOR 4
#define GL_MINOR 5
#define NAME_MAX_CHARS 256
#define RASTER_THREAD_PREFIX "llvmpipe-"          /* llvmpipe names its rasterizer threads so */
#define MESA_EGL_VENDOR "/usr/share/glvnd/egl_vendor.d/50_mesa.json"

struct bench_gl_context {
    EGLDisplay display;
    EGLContext context;
    char renderer[NAME_MAX_CHARS], version[NAME_MAX_CHARS];
};

static const char *egl_error_name(EGLint e)
{
    switch (e) {
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return "an EGL error";
    }
}

static bool egl_fail(const char *what, sr_error *err)
{
    EGLint e = eglGetError();
    return sr_error_set(err, "%s failed: %s (0x%04x)", what, egl_error_name(e), (unsigned)e);
}

static const char *gl_error_name(GLenum e)
{
    switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: return "a GL error";
    }
}

bool bench_gl_check(const char *what, sr_error *err)
{
    GLenum e = glGetError();
    if (e == GL_NO_ERROR)
        return true;
    while (glGetError() != GL_NO_ERROR) /* GL queues errors; report the first, drop the rest */
        ;
    return sr_error_set(err, "%s: %s (0x%04x)", what, gl_error_name(e), (unsigned)e);
}

/* Mesa reads all of these when the driver loads, so they must be set before
 * eglInitialize. Each one closes a way to end up on something else. */
static bool force_llvmpipe(int lp_threads, sr_error *err)
{
    char threads[16];
    snprintf(threads, sizeof threads, "%d", lp_threads);
    bool ok = setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1) == 0 /* no GPU driver, even with a render node */
              && setenv("GALLIUM_DRIVER", "llvmpipe", 1) == 0 /* not softpipe or zink */
              && setenv("EGL_PLATFORM", "surfaceless", 1) == 0
              && setenv("LP_NUM_THREADS", threads, 1) == 0;
    /* libglvnd might otherwise pick another vendor's EGL (a GPU driver's). */
    if (ok && access(MESA_EGL_VENDOR, R_OK) == 0)
        ok = setenv("__EGL_VENDOR_LIBRARY_FILENAMES", MESA_EGL_VENDOR, 1) == 0;
    return ok || sr_error_set(err, "cannot set llvmpipe's environment variables");
}

static bool open_display(bench_gl_context *c, sr_error *err)
{
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!get_display)
        return sr_error_set(err, "EGL has no eglGetPlatformDisplayEXT (is libegl-mesa0 installed?)");
    c->display = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (c->display == EGL_NO_DISPLAY)
        return egl_fail("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA)", err);
    EGLint major, minor;
    if (!eglInitialize(c->display, &major, &minor)) {
        c->display = EGL_NO_DISPLAY;
        return egl_fail("eglInitialize (surfaceless platform)", err);
    }
    return true;
}

/* No config and no surface: the context only ever draws into FBOs. */
static bool make_context(bench_gl_context *c, sr_error *err)
{
    const EGLint attribs[] = { EGL_CONTEXT_MAJOR_VERSION, GL_MAJOR, EGL_CONTEXT_MINOR_VERSION, GL_MINOR,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE };
    if (!eglBindAPI(EGL_OPENGL_API))
        return egl_fail("eglBindAPI(EGL_OPENGL_API)", err);
    c->context = eglCreateContext(c->display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (c->context == EGL_NO_CONTEXT)
        return egl_fail("eglCreateContext (GL 4.5 core, no config)", err);
    if (!eglMakeCurrent(c->display, EGL_NO_SURFACE, EGL_NO_SURFACE, c->context))
        return egl_fail("eglMakeCurrent (surfaceless)", err);
    return true;
}

static bool read_strings(bench_gl_context *c, sr_error *err)
{
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    const char *version = (const char *)glGetString(GL_VERSION);
    if (!bench_gl_check("glGetString", err))
        return false;
    snprintf(c->renderer, sizeof c->renderer, "%s", renderer ? renderer : "?");
    snprintf(c->version, sizeof c->version, "%s", version ? version : "?");
    if (!strstr(c->renderer, "llvmpipe"))
        return sr_error_set(err, "GL_RENDERER is \"%s\", not llvmpipe", c->renderer);
    return true;
}

bool bench_gl_context_create(bench_gl_context **out, int lp_threads, sr_error *err)
{
    bench_gl_context *c = calloc(1, sizeof *c);
    if (!c)
        return sr_error_set(err, "out of memory for the GL context");
    c->display = EGL_NO_DISPLAY;
    c->context = EGL_NO_CONTEXT;
    if (!(force_llvmpipe(lp_threads, err) && open_display(c, err) && make_context(c, err) &&
          read_strings(c, err))) {
        bench_gl_context_destroy(c);
        return false;
    }
    *out = c;
    return true;
}

/* Terminating the display drops llvmpipe's screen and its threads, so the
 * next context can start with another LP_NUM_THREADS. */
void bench_gl_context_destroy(bench_gl_context *c)
{
    if (!c)
        return;
    if (c->display != EGL_NO_DISPLAY) {
        eglMakeCurrent(c->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (c->context != EGL_NO_CONTEXT)
            eglDestroyContext(c->display, c->context);
        eglTerminate(c->display);
    }
    eglReleaseThread();
    free(c);
}

const char *bench_gl_context_renderer(const bench_gl_context *c)
{
    return c->renderer;
}

const char *bench_gl_context_version(const bench_gl_context *c)
{
    return c->version;
}

static bool thread_is_rasterizer(const char *tid)
{
    char path[NAME_MAX_CHARS + 32], name[NAME_MAX_CHARS] = "";
    snprintf(path, sizeof path, "/proc/self/task/%s/comm", tid);
    FILE *f = fopen(path, "r");
    if (!f)
        return false;
    bool named = fgets(name, sizeof name, f) != NULL;
    fclose(f);
    return named && strncmp(name, RASTER_THREAD_PREFIX, strlen(RASTER_THREAD_PREFIX)) == 0;
}

int bench_gl_count_raster_threads(void)
{
    DIR *dir = opendir("/proc/self/task");
    if (!dir)
        return -1;
    int n = 0;
    for (struct dirent *e; (e = readdir(dir));)
        n += e->d_name[0] != '.' && thread_is_rasterizer(e->d_name);
    closedir(dir);
    return n;
}
