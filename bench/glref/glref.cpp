// glref.cpp - the benchmark scenes in OpenGL 3.3 core on Mesa's llvmpipe (EGL, surfaceless): the reference that
// `facet bench` is timed and compared against.
#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "options.hpp"
#include "scenes.hpp"
#include "stb_image_write.h"

namespace {

// The contract's shading: a white light from (0.4, 0.7, 0.6), ambient 0.15, Phong's reflection vector, exponent 32.
constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec2 uv;
uniform mat4 clip_from_object;
uniform mat4 world_from_object;
uniform mat3 normal_from_object;
out vec3 world_position;
out vec3 world_normal;
out vec2 texcoord;
void main() {
  world_position = (world_from_object * vec4(position, 1.0)).xyz;
  world_normal = normal_from_object * normal;
  texcoord = uv;
  gl_Position = clip_from_object * vec4(position, 1.0);
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
in vec3 world_position;
in vec3 world_normal;
in vec2 texcoord;
uniform sampler2D albedo_map;
out vec4 color;
void main() {
  vec3 n = normalize(world_normal);
  vec3 l = normalize(vec3(0.4, 0.7, 0.6));
  vec3 v = normalize(vec3(0.0, 0.0, 3.0) - world_position);
  vec3 r = reflect(-l, n);
  vec3 albedo = texture(albedo_map, texcoord).rgb;
  vec3 c = 0.15 * albedo + max(dot(n, l), 0.0) * albedo + 0.4 * pow(max(dot(r, v), 0.0), 32.0) * vec3(1.0);
  color = vec4(clamp(c, 0.0, 1.0), 1.0);
}
)";

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "glref: %s\n", message.c_str());
  std::exit(1);
}

GLuint compile(GLenum kind, const char* source) {
  const GLuint shader = glCreateShader(kind);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    fail(std::string("shader does not compile: ") + log);
  }
  return shader;
}

// An EGL context on the surfaceless platform: no display, no window, rendering into framebuffer objects.
void create_context() {
  const EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr))
    fail("no EGL surfaceless display (is Mesa's libegl-mesa0 installed?)");
  if (!eglBindAPI(EGL_OPENGL_API)) fail("EGL cannot bind OpenGL");
  const EGLint config_attributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config;
  EGLint configs = 0;
  if (!eglChooseConfig(display, config_attributes, &config, 1, &configs) || configs < 1)
    fail("no EGL configuration for OpenGL");
  const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                       EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                       EGL_NONE};
  const EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
  if (context == EGL_NO_CONTEXT) fail("no OpenGL 3.3 core context");
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) fail("cannot make the context current");
}

// The contract's 1024 x 1024 texture: a checker of 128-texel squares, light grey against a colour ramp.
GLuint make_texture() {
  constexpr int kSize = 1024;
  std::vector<unsigned char> texels(static_cast<std::size_t>(kSize) * kSize * 4);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      unsigned char* t = &texels[(static_cast<std::size_t>(y) * kSize + static_cast<std::size_t>(x)) * 4];
      const bool light = (((x / 128) ^ (y / 128)) & 1) != 0;
      t[0] = static_cast<unsigned char>(light ? 230 : 40 + x / 8);
      t[1] = static_cast<unsigned char>(light ? 230 : 60);
      t[2] = static_cast<unsigned char>(light ? 230 : 40 + y / 8);
      t[3] = 255;
    }
  GLuint texture;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, kSize, kSize, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return texture;
}

// A framebuffer of RGBA8 colour and 24-bit depth, multisampled when samples > 1.
GLuint make_framebuffer(int width, int height, int samples, bool depth) {
  GLuint framebuffer, buffers[2];
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glGenRenderbuffers(2, buffers);
  const GLenum formats[2] = {GL_RGBA8, GL_DEPTH_COMPONENT24};
  const GLenum attachments[2] = {GL_COLOR_ATTACHMENT0, GL_DEPTH_ATTACHMENT};
  for (int b = 0; b < (depth ? 2 : 1); ++b) {
    glBindRenderbuffer(GL_RENDERBUFFER, buffers[b]);
    if (samples > 1) glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, formats[b], width, height);
    else glRenderbufferStorage(GL_RENDERBUFFER, formats[b], width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, attachments[b], GL_RENDERBUFFER, buffers[b]);
  }
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    fail("the framebuffer is incomplete (" + std::to_string(width) + "x" + std::to_string(height) + ", " +
         std::to_string(samples) + " samples)");
  return framebuffer;
}

// The renderer as the result line names it: "glref llvmpipe (LLVM ..., 256 bits) Mesa 22.3.6".
std::string renderer_name() {
  const std::string renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const std::string version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  const std::size_t mesa = version.find("Mesa");
  return "glref " + renderer + (mesa == std::string::npos ? " " + version : " " + version.substr(mesa));
}

// Frame 0's colour, top row first, as a PNG.
void write_png(const std::string& path, GLuint framebuffer, int width, int height) {
  std::vector<unsigned char> pixels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  // OpenGL's rows go up from the bottom; an image's top row is the top of the screen.
  stbi_flip_vertically_on_write(1);
  if (!stbi_write_png(path.c_str(), width, height, 4, pixels.data(), width * 4)) fail(path + ": cannot write the image");
}

// Frame 0's window-space depth as a NumPy array: version 1.0, little-endian float32, shape (height, width), top row
// first.
void write_depth(const std::string& path, GLuint framebuffer, int width, int height) {
  const std::size_t w = static_cast<std::size_t>(width), h = static_cast<std::size_t>(height);
  std::vector<float> depth(w * h);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(height) + ", " +
                       std::to_string(width) + "), }";
  header.append(63 - (10 + header.size()) % 64, ' ');  // the whole preamble a multiple of 64 bytes
  header += '\n';
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) fail(path + ": cannot write the depth");
  const unsigned char preamble[10] = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0, static_cast<unsigned char>(header.size()),
                                      static_cast<unsigned char>(header.size() >> 8)};
  bool ok = std::fwrite(preamble, 1, sizeof preamble, file) == sizeof preamble &&
            std::fwrite(header.data(), 1, header.size(), file) == header.size();
  for (std::size_t row = h; ok && row-- > 0;) ok = std::fwrite(&depth[row * w], sizeof(float), w, file) == w;
  if (std::fclose(file) != 0 || !ok) fail(path + ": cannot write the depth");
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

std::string json_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;
    out += c;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const glref::Options options = glref::parse_options(argc, argv);
  glref::Scene scene;
  try {
    scene = options.scene == glref::SceneKind::sphere  ? glref::make_sphere(options.count)
            : options.scene == glref::SceneKind::quads ? glref::make_quads(options.count, options.front_to_back)
                                                       : glref::load_mesh(options.mesh);
  } catch (const glref::SceneError& e) {
    std::fprintf(stderr, "glref: %s\n", e.what());
    return 2;
  }

  // llvmpipe reads its thread count when the context is made; T = 0 and T = 1 both mean one rendering thread here.
  const int threads = options.threads >= 0
                          ? options.threads
                          : (std::getenv("LP_NUM_THREADS") ? std::atoi(std::getenv("LP_NUM_THREADS"))
                                                           : static_cast<int>(std::thread::hardware_concurrency()));
  setenv("LP_NUM_THREADS", std::to_string(threads).c_str(), 1);
  setenv("GALLIUM_DRIVER", std::getenv("GALLIUM_DRIVER") ? std::getenv("GALLIUM_DRIVER") : "llvmpipe", 1);
  create_context();

  const GLuint program = glCreateProgram();
  glAttachShader(program, compile(GL_VERTEX_SHADER, kVertexShader));
  glAttachShader(program, compile(GL_FRAGMENT_SHADER, kFragmentShader));
  glLinkProgram(program);
  GLint linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  if (!linked) fail("the shader program does not link");
  glUseProgram(program);

  GLuint array, buffers[2];
  glGenVertexArrays(1, &array);
  glBindVertexArray(array);
  glGenBuffers(2, buffers);
  glBindBuffer(GL_ARRAY_BUFFER, buffers[0]);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(scene.vertices.size() * sizeof(glref::Vertex)),
               scene.vertices.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers[1]);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(scene.indices.size() * sizeof(std::uint32_t)),
               scene.indices.data(), GL_STATIC_DRAW);
  const GLsizei stride = sizeof(glref::Vertex);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(glref::Vertex, position)));
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(glref::Vertex, normal)));
  glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(glref::Vertex, uv)));
  for (GLuint a = 0; a < 3; ++a) glEnableVertexAttribArray(a);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, make_texture());
  glUniform1i(glGetUniformLocation(program, "albedo_map"), 0);

  const int width = options.width, height = options.height;
  const GLuint target = make_framebuffer(width, height, options.samples, true);
  const GLuint resolved = options.samples > 1 ? make_framebuffer(width, height, 1, true) : target;
  glBindFramebuffer(GL_FRAMEBUFFER, target);
  glViewport(0, 0, width, height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glClearColor(0.1f, 0.1f, 0.15f, 1.0f);
  glClearDepth(1.0);

  // The contract's camera: 45 degrees vertically, near 0.1, far 100, the eye at (0, 0, 3) looking down -Z.
  const glm::mat4 clip_from_view =
      glm::perspective(glm::radians(45.0f), static_cast<float>(width) / static_cast<float>(height), 0.1f, 100.0f);
  const glm::mat4 view_from_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -3.0f));
  const GLint clip_from_object = glGetUniformLocation(program, "clip_from_object");
  const GLint world_from_object = glGetUniformLocation(program, "world_from_object");
  const GLint normal_from_object = glGetUniformLocation(program, "normal_from_object");
  const auto draw_frame = [&](int f) {
    glm::mat4 world(1.0f);
    if (scene.animated) {
      world = glm::rotate(glm::mat4(1.0f), 0.6f + 0.02f * static_cast<float>(f), glm::vec3(0, 1, 0)) *
              glm::rotate(glm::mat4(1.0f), -0.3f, glm::vec3(1, 0, 0)) * glm::scale(glm::mat4(1.0f), glm::vec3(options.scale));
    }
    glUniformMatrix4fv(clip_from_object, 1, GL_FALSE, glm::value_ptr(clip_from_view * view_from_world * world));
    glUniformMatrix4fv(world_from_object, 1, GL_FALSE, glm::value_ptr(world));
    glUniformMatrix3fv(normal_from_object, 1, GL_FALSE, glm::value_ptr(glm::mat3(world)));
    const auto start = std::chrono::steady_clock::now();
    glBindFramebuffer(GL_FRAMEBUFFER, target);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(scene.indices.size()), GL_UNSIGNED_INT, nullptr);
    if (options.samples > 1) {
      glBindFramebuffer(GL_READ_FRAMEBUFFER, target);
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolved);
      glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    glFinish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  };

  std::vector<double> times;
  for (int f = 0; f < options.warmup + options.frames; ++f) {
    const double ms = draw_frame(f);
    if (f >= options.warmup) times.push_back(ms);
  }
  if (glGetError() != GL_NO_ERROR) fail("OpenGL reported an error while drawing");

  if (!options.png.empty() || !options.depth.empty() || options.stats) {
    GLuint queries[2];
    glGenQueries(2, queries);
    glBeginQuery(GL_SAMPLES_PASSED, queries[0]);
    glBeginQuery(GL_PRIMITIVES_GENERATED, queries[1]);
    draw_frame(0);
    glEndQuery(GL_PRIMITIVES_GENERATED);
    glEndQuery(GL_SAMPLES_PASSED);
    if (options.stats) {
      GLuint64 passed = 0, primitives = 0;
      glGetQueryObjectui64v(queries[0], GL_QUERY_RESULT, &passed);
      glGetQueryObjectui64v(queries[1], GL_QUERY_RESULT, &primitives);
      std::fprintf(stderr, "glref: frame 0: samples_passed %llu, primitives_generated %llu\n",
                   static_cast<unsigned long long>(passed), static_cast<unsigned long long>(primitives));
    }
    if (!options.png.empty()) write_png(options.png, resolved, width, height);
    if (!options.depth.empty()) {
      // A multisampled depth resolves by a blit, which keeps one sample of each pixel.
      if (options.samples > 1) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, target);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolved);
        glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
      }
      write_depth(options.depth, resolved, width, height);
    }
  }

  const std::string name = renderer_name();
  if (options.json) {
    std::printf(
        "{\"renderer\":\"%s\",\"scene\":\"%s\",\"triangles\":%zu,\"width\":%d,\"height\":%d,\"threads\":%d,"
        "\"warmup\":%d,\"frames\":%d,\"samples\":%d,\"median_ms\":%.3f,\"min_ms\":%.3f,\"max_ms\":%.3f}\n",
        json_escape(name).c_str(), json_escape(scene.name).c_str(), scene.indices.size() / 3, width, height,
        threads, options.warmup, options.frames, options.samples, median(times),
        *std::min_element(times.begin(), times.end()), *std::max_element(times.begin(), times.end()));
  } else {
    std::printf("%s: %s, %zu triangles, %dx%d, %d samples, %d threads: median %.3f ms over %d frames\n",
                name.c_str(), scene.name.c_str(), scene.indices.size() / 3, width, height, options.samples, threads,
                median(times), options.frames);
  }
  return 0;
}
