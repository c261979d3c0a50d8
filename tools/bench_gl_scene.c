/* bench_gl_scene.c — a bench scene on llvmpipe: uploaded once, then drawn
 * per frame with the matrices softrast uses and the same fixed-function
 * conventions (z in [0, 1], LESS, clear to 1, the scene's face culling). */
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_gl.h"

enum { ATTR_POSITION, ATTR_NORMAL, ATTR_UV, ATTR_COLOR, ATTR_COUNT };
#define LOG_CHARS 512     /* of a shader's info log: its first line is reported */
#define DEFINES_CHARS 256 /* the #version and #define lines before a shader body */

struct bench_gl_scene {
    GLuint vao, attr_buffers[ATTR_COUNT], index_buffer, texture, program;
    GLuint fbo, color_rb, depth_rb, query;
    GLint clip_loc, normal_loc;
    GLenum mode;
    GLsizei index_count;
    int width, height;
    bool depth_only;
};

/* One source for every scene; the #defines in front of it pick what the
 * shading mode reads, as softrast's varying layout does (sr_vertex_layout). */
static const char VERTEX_BODY[] =
    "layout(location = 0) in vec3 position;\n"
    "layout(location = 1) in vec3 normal;\n"
    "layout(location = 2) in vec2 uv;\n"
    "layout(location = 3) in vec3 color;\n"
    "uniform mat4 clip_from_object;\n"
    "uniform mat3 normal_matrix;\n"
    "out vec3 v_normal; out vec2 v_uv; out vec3 v_color;\n"
    "void main() {\n"
    "    gl_Position = clip_from_object * vec4(position, 1.0);\n"
    "#ifdef USE_NORMAL\n    v_normal = normal_matrix * normal;\n#endif\n"
    "#ifdef USE_UV\n    v_uv = uv;\n#endif\n"
    "#ifdef USE_COLOR\n    v_color = color;\n#endif\n"
    "}\n";

/* softrast's 10_shade.h in GLSL: sr_shade_lambert_intensity and sr_shade_albedo.
 * softrast's v = 0 is the image's bottom row and its texels are stored top
 * row first, as uploaded here (GL's t = 0 row): so t = 1 - v. */
static const char FRAGMENT_BODY[] =
    "in vec3 v_normal; in vec2 v_uv; in vec3 v_color;\n"
    "uniform sampler2D albedo_map;\n"
    "uniform vec3 light_dir;\n"
    "out vec4 frag_color;\n"
    "vec3 albedo() {\n"
    "#if defined(USE_UV)\n    return texture(albedo_map, vec2(v_uv.x, 1.0 - v_uv.y)).rgb;\n"
    "#elif defined(USE_COLOR)\n    return v_color;\n"
    "#else\n    return vec3(GRAY);\n#endif\n"
    "}\n"
    "void main() {\n"
    "#if defined(SHADE_LAMBERT)\n"
    "    float len2 = dot(v_normal, v_normal);\n"
    "    float d = len2 > 0.0 ? dot(v_normal, light_dir) / sqrt(len2) : 0.0;\n"
    "    frag_color = vec4((AMBIENT + (1.0 - AMBIENT) * max(d, 0.0)) * albedo(), 1.0);\n"
    "#elif defined(SHADE_TEXTURE) || defined(SHADE_COLOR)\n"
    "    frag_color = vec4(albedo(), 1.0);\n"
    "#elif defined(SHADE_ID)\n"
    "    uint id = uint(gl_PrimitiveID) + 1u;\n"
    "    frag_color = vec4(uvec4(id >> 16, id >> 8, id, 255u) & 255u) / 255.0;\n"
    "#endif\n"
    "}\n";

static bool compile_shader(GLenum type, const char *defines, const char *body, GLuint *out, sr_error *err)
{
    const char *sources[] = { defines, body };
    GLuint sh = glCreateShader(type);
    glShaderSource(sh, 2, sources, NULL);
    glCompileShader(sh);
    GLint ok = GL_FALSE;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[LOG_CHARS] = "";
        glGetShaderInfoLog(sh, sizeof log, NULL, log);
        log[strcspn(log, "\n")] = '\0';
        glDeleteShader(sh);
        return sr_error_set(err, "%s shader does not compile: %s", type == GL_VERTEX_SHADER ? "vertex" : "fragment",
                            log);
    }
    *out = sh;
    return bench_gl_check("glCompileShader", err);
}

/* The depth view defines neither mode: its fragment shader writes nothing. */
static const char *shade_define(sr_shade shade)
{
    switch (shade) {
    case SR_SHADE_LAMBERT: return "#define SHADE_LAMBERT\n";
    case SR_SHADE_TEXTURE: return "#define SHADE_TEXTURE\n";
    case SR_SHADE_ID:      return "#define SHADE_ID\n";
    case SR_SHADE_COLOR:   return "#define SHADE_COLOR\n";
    default: return "";
    }
}

static void shader_defines(const sr_bench_scene *s, const sr_varying_layout *l, char *out, size_t size)
{
    snprintf(out, size, "#version 450 core\n#define AMBIENT %.9g\n#define GRAY %.9g\n%s%s%s%s",
             (double)SR_LAMBERT_AMBIENT, (double)SR_LAMBERT_GRAY, shade_define(s->shade),
             l->normal >= 0 ? "#define USE_NORMAL\n" : "", l->uv >= 0 ? "#define USE_UV\n" : "",
             l->color >= 0 ? "#define USE_COLOR\n" : "");
}

/* The light as softrast's shading context holds it: SR_DEFAULT_LIGHT, unit length. */
static bool set_constant_uniforms(GLuint program, sr_error *err)
{
    vec3 light = SR_DEFAULT_LIGHT;
    glm_vec3_normalize(light);
    glUseProgram(program);
    glUniform3fv(glGetUniformLocation(program, "light_dir"), 1, light);
    glUniform1i(glGetUniformLocation(program, "albedo_map"), 0);
    return bench_gl_check("glUniform (light, sampler)", err);
}

static bool make_program(bench_gl_scene *g, const sr_bench_scene *s, const sr_varying_layout *l, sr_error *err)
{
    char defines[DEFINES_CHARS];
    GLuint vs = 0, fs = 0;
    shader_defines(s, l, defines, sizeof defines);
    bool ok = compile_shader(GL_VERTEX_SHADER, defines, VERTEX_BODY, &vs, err) &&
              compile_shader(GL_FRAGMENT_SHADER, defines, FRAGMENT_BODY, &fs, err);
    if (ok) {
        g->program = glCreateProgram();
        glAttachShader(g->program, vs);
        glAttachShader(g->program, fs);
        glLinkProgram(g->program);
        GLint linked = GL_FALSE;
        glGetProgramiv(g->program, GL_LINK_STATUS, &linked);
        ok = linked || sr_error_set(err, "the shader program does not link");
    }
    glDeleteShader(vs); /* the program keeps them while it lives */
    glDeleteShader(fs);
    if (!ok || !bench_gl_check("glLinkProgram", err))
        return false;
    g->clip_loc = glGetUniformLocation(g->program, "clip_from_object");
    g->normal_loc = glGetUniformLocation(g->program, "normal_matrix");
    return set_constant_uniforms(g->program, err);
}

static void upload_attribute(bench_gl_scene *g, int attr, const void *data, int floats, uint32_t count)
{
    glGenBuffers(1, &g->attr_buffers[attr]);
    glBindBuffer(GL_ARRAY_BUFFER, g->attr_buffers[attr]);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)count * floats * (GLsizeiptr)sizeof(float), data, GL_STATIC_DRAW);
    glVertexAttribPointer((GLuint)attr, floats, GL_FLOAT, GL_FALSE, 0, NULL);
    glEnableVertexAttribArray((GLuint)attr);
}

/* Only the attributes the shading reads, as softrast's vertex stage. */
static bool upload_mesh(bench_gl_scene *g, const sr_mesh *m, const sr_varying_layout *l, sr_error *err)
{
    glGenVertexArrays(1, &g->vao);
    glBindVertexArray(g->vao);
    upload_attribute(g, ATTR_POSITION, m->positions, 3, m->vertex_count);
    if (l->normal >= 0)
        upload_attribute(g, ATTR_NORMAL, m->normals, 3, m->vertex_count);
    if (l->uv >= 0)
        upload_attribute(g, ATTR_UV, m->uvs, 2, m->vertex_count);
    if (l->color >= 0)
        upload_attribute(g, ATTR_COLOR, m->colors, 3, m->vertex_count);
    glGenBuffers(1, &g->index_buffer);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g->index_buffer);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)m->index_count * (GLsizeiptr)sizeof(uint32_t), m->indices,
                 GL_STATIC_DRAW);
    /* GL's strip makes odd triangles (k+1, k, k+2), softrast's (k, k+2, k+1):
     * both an odd permutation of (k, k+1, k+2), so the same winding. */
    g->mode = m->topology == SR_TRIANGLE_STRIP ? GL_TRIANGLE_STRIP
              : m->topology == SR_POINT_LIST   ? GL_POINTS
                                               : GL_TRIANGLES;
    g->index_count = (GLsizei)m->index_count;
    return bench_gl_check("uploading the mesh", err);
}

/* softrast texels are 0x00RRGGBB words: in memory (little-endian) B, G, R, 0,
 * which is GL_BGRA bytes. Bilinear, repeat, no mipmaps: softrast's sampler. */
static bool upload_texture(bench_gl_scene *g, const sr_texture *t, sr_error *err)
{
    glGenTextures(1, &g->texture);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, g->texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, t->width, t->height, 0, GL_BGRA, GL_UNSIGNED_BYTE, t->texels);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    return bench_gl_check("uploading the texture", err);
}

/* softrast's framebuffer in GL terms: 32-bit color, float32 depth. */
static bool make_framebuffer(bench_gl_scene *g, sr_error *err)
{
    glGenRenderbuffers(1, &g->color_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, g->color_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, g->width, g->height);
    glGenRenderbuffers(1, &g->depth_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, g->depth_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, g->width, g->height);
    glGenFramebuffers(1, &g->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, g->color_rb);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, g->depth_rb);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return sr_error_set(err, "the %dx%d RGBA8 + DEPTH32F framebuffer is incomplete (0x%04x)", g->width,
                            g->height, (unsigned)status);
    return bench_gl_check("making the framebuffer", err);
}

/* softrast's conventions as GL state. Winding: softrast's front faces are
 * clockwise on its y-down screen (area2 > 0 in sr_cull_area2). GL's window y
 * points up, but its viewport maps NDC +y up too, where softrast's maps it to
 * row 0 at the top: both flip together, the picture is the same way up in
 * both, and a triangle clockwise in one is clockwise in the other. So GL_CW
 * is front (GL_CCW culls the torus's outside: other depths, ~all colors off). */
static bool set_fixed_state(bench_gl_scene *g, const sr_bench_scene *s, sr_error *err)
{
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE); /* clip volume 0 <= z <= w, depth = z_ndc */
    glViewport(0, 0, g->width, g->height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearDepth(1.0);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    if (s->cull == SR_CULL_NONE)
        glDisable(GL_CULL_FACE);
    else
        glEnable(GL_CULL_FACE);
    glCullFace(s->cull == SR_CULL_FRONT ? GL_FRONT : GL_BACK);
    glFrontFace(GL_CW);
    glDisable(GL_DITHER);
    glDisable(GL_MULTISAMPLE);
    glGenQueries(1, &g->query);
    return bench_gl_check("setting the fixed-function state", err);
}

bool bench_gl_scene_create(bench_gl_scene **out, const sr_bench_scene *s, sr_error *err)
{
    if (s->shade != SR_SHADE_LAMBERT && s->shade != SR_SHADE_TEXTURE && s->shade != SR_SHADE_DEPTH &&
        s->shade != SR_SHADE_ID && s->shade != SR_SHADE_COLOR)
        return sr_error_set(err, "scene %s: bench-gl has shaders for lambert, texture, color, depth and id only",
                            s->name);
    if (s->mesh.topology != SR_TRIANGLE_LIST && s->mesh.topology != SR_TRIANGLE_STRIP &&
        s->mesh.topology != SR_POINT_LIST)
        return sr_error_set(err, "scene %s: bench-gl draws triangles and points only", s->name);
    bench_gl_scene *g = calloc(1, sizeof *g);
    if (!g)
        return sr_error_set(err, "out of memory for the GL scene");
    bool textured = s->texture.texels != NULL;
    sr_varying_layout layout = sr_vertex_layout(s->shade, &s->mesh, textured);
    *g = (bench_gl_scene){ .width = s->width, .height = s->height, .depth_only = s->shade == SR_SHADE_DEPTH };
    bool ok = make_program(g, s, &layout, err) && upload_mesh(g, &s->mesh, &layout, err) &&
              (!textured || upload_texture(g, &s->texture, err)) && make_framebuffer(g, err) &&
              set_fixed_state(g, s, err);
    if (!ok) {
        bench_gl_scene_destroy(g);
        return false;
    }
    *out = g;
    return true;
}

void bench_gl_scene_destroy(bench_gl_scene *g)
{
    if (!g)
        return;
    glDeleteQueries(1, &g->query);
    glDeleteFramebuffers(1, &g->fbo);
    glDeleteRenderbuffers(1, &g->color_rb);
    glDeleteRenderbuffers(1, &g->depth_rb);
    glDeleteTextures(1, &g->texture);
    glDeleteBuffers(1, &g->index_buffer);
    glDeleteBuffers(ATTR_COUNT, g->attr_buffers);
    glDeleteVertexArrays(1, &g->vao);
    glDeleteProgram(g->program);
    free(g);
}

/* The same clip = P·V·W and normal matrix softrast's vertex stage makes. */
bool bench_gl_scene_prepare(bench_gl_scene *g, const sr_bench_scene *s, int f, int n, sr_error *err)
{
    mat4 world = GLM_MAT4_IDENTITY_INIT, view, projection;
    sr_vertex_transform xf;
    bench_gl_frame_camera(s, f, n, view, projection);
    sr_vertex_make_transform(world, view, projection, &xf);
    glUseProgram(g->program);
    glBindVertexArray(g->vao);
    glBindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    glUniformMatrix4fv(g->clip_loc, 1, GL_FALSE, (const GLfloat *)xf.clip_from_object);
    glUniformMatrix3fv(g->normal_loc, 1, GL_FALSE, (const GLfloat *)xf.normal_matrix);
    return bench_gl_check("glUniformMatrix (frame matrices)", err);
}

/* Clear color and depth, as softrast's frame. The depth view writes no
 * color, as softrast's depth shading; the clear still clears color (the
 * color mask would block it). */
static void clear(const bench_gl_scene *g)
{
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (g->depth_only)
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
}

bool bench_gl_scene_draw(bench_gl_scene *g, sr_error *err)
{
    clear(g);
    glDrawElements(g->mode, g->index_count, GL_UNSIGNED_INT, NULL);
    glFinish(); /* llvmpipe defers rasterization: the frame ends when the pixels are in */
    return bench_gl_check("a frame (glClear, glDrawElements, glFinish)", err);
}

bool bench_gl_scene_count_fragments(bench_gl_scene *g, uint64_t *fragments, sr_error *err)
{
    GLuint64 samples = 0;
    clear(g);
    glBeginQuery(GL_SAMPLES_PASSED, g->query);
    glDrawElements(g->mode, g->index_count, GL_UNSIGNED_INT, NULL);
    glEndQuery(GL_SAMPLES_PASSED);
    glGetQueryObjectui64v(g->query, GL_QUERY_RESULT, &samples); /* waits for the draw */
    *fragments = samples;
    return bench_gl_check("GL_SAMPLES_PASSED query", err);
}

/* Both buffers have 4-byte pixels (BGRA8 color, float32 depth); memcpy
 * moves them whatever their type. */
#define PIXEL_BYTES 4

static void flip_rows(void *pixels, int width, int height)
{
    unsigned char *p = pixels;
    size_t row = (size_t)width * PIXEL_BYTES;
    for (int y = 0; y < height / 2; y++) {
        unsigned char *a = p + (size_t)y * row, *b = p + (size_t)(height - 1 - y) * row;
        for (size_t x = 0; x < row; x += PIXEL_BYTES) {
            unsigned char t[PIXEL_BYTES];
            memcpy(t, a + x, PIXEL_BYTES);
            memcpy(a + x, b + x, PIXEL_BYTES);
            memcpy(b + x, t, PIXEL_BYTES);
        }
    }
}

/* GL's row 0 is the bottom one; softrast's is the top one. */
bool bench_gl_scene_read(bench_gl_scene *g, uint32_t *color, float *depth, sr_error *err)
{
    glBindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, g->width, g->height, GL_BGRA, GL_UNSIGNED_BYTE, color);
    glReadPixels(0, 0, g->width, g->height, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
    if (!bench_gl_check("glReadPixels", err))
        return false;
    flip_rows(color, g->width, g->height);
    flip_rows(depth, g->width, g->height);
    for (size_t i = 0; i < (size_t)g->width * g->height; i++)
        color[i] &= 0xFFFFFFu; /* GL's alpha byte; softrast has none */
    return true;
}
