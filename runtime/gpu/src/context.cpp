// Headless EGL context creation and the thin GL helpers of context.hpp.
#include "cga/gpu/context.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string_view>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

namespace cga::gpu {
namespace {

std::string hex(unsigned v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%x", v);
  return buf;
}

std::string egl_error_name(EGLint e) {
  switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return "EGL error " + hex(static_cast<unsigned>(e));
  }
}

bool has_extension(const char* list, std::string_view name) {
  if (!list) return false;
  const std::string_view all(list);
  for (std::size_t pos = 0; pos < all.size();) {
    std::size_t end = all.find(' ', pos);
    if (end == std::string_view::npos) end = all.size();
    if (all.substr(pos, end - pos) == name) return true;
    pos = end + 1;
  }
  return false;
}

// An initialized display: the first EGL device that initializes (a real GPU, or Mesa's software device),
// else Mesa's surfaceless platform. `tried` collects why each attempt failed.
EGLDisplay open_display(std::string& platform, std::string& tried) {
  const char* client_ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!client_ext) {
    tried += "eglQueryString(EGL_EXTENSIONS) failed (" + egl_error_name(eglGetError()) + "); ";
    return EGL_NO_DISPLAY;
  }
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_platform_display) {
    tried += "no eglGetPlatformDisplayEXT; ";
    return EGL_NO_DISPLAY;
  }
  if (has_extension(client_ext, "EGL_EXT_platform_device")) {
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (query_devices && query_devices(16, devices, &count)) {
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        EGLint major = 0, minor = 0;
        if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) {
          platform = "EGL device " + std::to_string(i);
          return d;
        }
        tried += "EGL device " + std::to_string(i) + ": " + egl_error_name(eglGetError()) + "; ";
      }
      if (count == 0) tried += "eglQueryDevicesEXT found no device; ";
    } else {
      tried += "eglQueryDevicesEXT failed; ";
    }
  } else {
    tried += "no EGL_EXT_platform_device; ";
  }
  if (has_extension(client_ext, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    EGLint major = 0, minor = 0;
    if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) {
      platform = "EGL surfaceless (Mesa)";
      return d;
    }
    tried += "surfaceless: " + egl_error_name(eglGetError()) + "; ";
  } else {
    tried += "no EGL_MESA_platform_surfaceless; ";
  }
  return EGL_NO_DISPLAY;
}

std::string info_log(GLuint object, bool program) {
  GLint length = 0;
  if (program)
    glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
  else
    glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
  if (program)
    glGetProgramInfoLog(object, static_cast<GLsizei>(log.size()), nullptr, log.data());
  else
    glGetShaderInfoLog(object, static_cast<GLsizei>(log.size()), nullptr, log.data());
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log.empty() ? "(the driver gave no log)" : log;
}

}  // namespace

const char* stage_name(unsigned stage) {
  switch (stage) {
    case GL_VERTEX_SHADER: return "vertex";
    case GL_FRAGMENT_SHADER: return "fragment";
    case GL_COMPUTE_SHADER: return "compute";
    case GL_GEOMETRY_SHADER: return "geometry";
    default: return "unknown-stage";
  }
}

void Object::release() noexcept {
  if (!name_) return;
  const GLuint n = name_;
  switch (kind_) {
    case ObjectKind::buffer: glDeleteBuffers(1, &n); break;
    case ObjectKind::program: glDeleteProgram(n); break;
    case ObjectKind::vertex_array: glDeleteVertexArrays(1, &n); break;
    case ObjectKind::framebuffer: glDeleteFramebuffers(1, &n); break;
    case ObjectKind::renderbuffer: glDeleteRenderbuffers(1, &n); break;
    case ObjectKind::query: glDeleteQueries(1, &n); break;
  }
  name_ = 0;
}

Object& Object::operator=(Object&& o) noexcept {
  if (this != &o) {
    release();
    kind_ = o.kind_;
    name_ = o.name_;
    o.name_ = 0;
  }
  return *this;
}

Object::~Object() { release(); }

Context::Context() {
  std::string tried;
  EGLDisplay display = open_display(platform_, tried);
  if (display == EGL_NO_DISPLAY)
    throw Unavailable("cga::gpu: no EGL display (needs libEGL and a driver; Mesa: libegl-mesa0 "
                      "libgl1-mesa-dri). Tried: " + tried);
  display_ = display;
  auto fail = [&](const std::string& what) {
    const EGLint err = eglGetError();
    if (context_) eglDestroyContext(display, static_cast<EGLContext>(context_));
    eglTerminate(display);
    throw Unavailable("cga::gpu: " + what + " on " + platform_ + " (" + egl_error_name(err) + ")");
  };
  if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API) failed");
  const char* ext = eglQueryString(display, EGL_EXTENSIONS);
  if (!has_extension(ext, "EGL_KHR_no_config_context") || !has_extension(ext, "EGL_KHR_surfaceless_context"))
    fail("no EGL_KHR_no_config_context / EGL_KHR_surfaceless_context, so no headless GL context");
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT) fail("no OpenGL 4.5 core context");
  context_ = context;
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) fail("eglMakeCurrent failed");
  if (!glGetString(GL_VERSION)) {
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    fail("the context is current but glGetString(GL_VERSION) is null (no GL vendor library behind libOpenGL?)");
  }
  GLuint fbo = 0, rb = 0;
  glCreateFramebuffers(1, &fbo);
  dummy_fbo_ = Object(ObjectKind::framebuffer, fbo);
  glCreateRenderbuffers(1, &rb);
  dummy_rb_ = Object(ObjectKind::renderbuffer, rb);
  glNamedRenderbufferStorage(rb, GL_RGBA8, 4, 4);
  glNamedFramebufferRenderbuffer(fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
  bind_dummy_framebuffer();
  check("creating the dummy framebuffer");
}

Context::~Context() {
  dummy_fbo_ = Object();
  dummy_rb_ = Object();
  auto display = static_cast<EGLDisplay>(display_);
  eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display, static_cast<EGLContext>(context_));
  eglTerminate(display);
}

std::string Context::renderer() const { return reinterpret_cast<const char*>(glGetString(GL_RENDERER)); }
std::string Context::version() const { return reinterpret_cast<const char*>(glGetString(GL_VERSION)); }

void Context::check(const char* what) const {
  const GLenum e = glGetError();
  if (e == GL_NO_ERROR) return;
  std::string more;
  while (glGetError() != GL_NO_ERROR) more = " (and more errors)";
  throw GlError("cga::gpu: GL error " + hex(e) + more + " after " + what);
}

void Context::finish() const {
  glFinish();
  check("glFinish");
}

void Context::bind_dummy_framebuffer() const {
  glBindFramebuffer(GL_FRAMEBUFFER, dummy_fbo_.get());
  glViewport(0, 0, 4, 4);
}

Object Context::make_program(std::span<const ShaderSource> stages, const ProgramOptions& options) const {
  Object program(ObjectKind::program, glCreateProgram());
  std::vector<GLuint> shaders;
  auto cleanup = [&] {
    for (GLuint s : shaders) glDeleteShader(s);  // attached ones live as long as the program
  };
  std::string names;
  for (const ShaderSource& src : stages) names += (names.empty() ? "" : " + ") + src.name;
  for (const ShaderSource& src : stages) {
    const GLuint s = glCreateShader(src.stage);
    if (!s) {
      cleanup();
      throw GlError(std::string("cga::gpu: glCreateShader failed for the ") + stage_name(src.stage) +
                    " shader " + src.name);
    }
    shaders.push_back(s);
    const char* text = src.text.c_str();
    const GLint length = static_cast<GLint>(src.text.size());
    glShaderSource(s, 1, &text, &length);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      const std::string log = info_log(s, false);
      cleanup();
      throw GlError(std::string("cga::gpu: compiling the ") + stage_name(src.stage) + " shader " + src.name +
                    " failed:\n" + log);
    }
    glAttachShader(program.get(), s);
  }
  if (!options.feedback_varyings.empty()) {
    std::vector<const char*> varyings;
    for (const std::string& v : options.feedback_varyings) varyings.push_back(v.c_str());
    glTransformFeedbackVaryings(program.get(), static_cast<GLsizei>(varyings.size()), varyings.data(),
                                GL_INTERLEAVED_ATTRIBS);
  }
  glLinkProgram(program.get());
  cleanup();
  GLint ok = 0;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
  if (!ok) throw GlError("cga::gpu: linking " + names + " failed:\n" + info_log(program.get(), true));
  check(("building program " + names).c_str());
  return program;
}

Buffer Context::make_buffer(std::size_t bytes, const void* data) const {
  GLuint name = 0;
  glCreateBuffers(1, &name);
  Buffer b{Object(ObjectKind::buffer, name), bytes};
  // Zero-sized storage is an error in GL; keep one word so that empty inputs still bind.
  glNamedBufferStorage(name, static_cast<GLsizeiptr>(bytes ? bytes : 4), bytes ? data : nullptr,
                       GL_DYNAMIC_STORAGE_BIT);
  check(("allocating a buffer of " + std::to_string(bytes) + " bytes").c_str());
  return b;
}

void Context::upload(const Buffer& b, const void* data, std::size_t bytes, std::size_t offset) const {
  if (offset + bytes > b.bytes)
    throw std::out_of_range("cga::gpu::Context::upload: " + std::to_string(offset + bytes) + " bytes into a " +
                            std::to_string(b.bytes) + "-byte buffer");
  if (bytes) glNamedBufferSubData(b.get(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
  check("glNamedBufferSubData");
}

void Context::read(const Buffer& b, void* data, std::size_t bytes, std::size_t offset) const {
  if (offset + bytes > b.bytes)
    throw std::out_of_range("cga::gpu::Context::read: " + std::to_string(offset + bytes) + " bytes from a " +
                            std::to_string(b.bytes) + "-byte buffer");
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  if (bytes)
    glGetNamedBufferSubData(b.get(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
  check("glGetNamedBufferSubData");
}

namespace {

// The transform feedback draw of capture_points / feedback_points; `query` (0: none) counts the primitives.
void draw_feedback_points(GLuint program, GLuint vao, std::size_t count, std::size_t instances, GLuint out,
                          GLuint query) {
  if (count > 0x7fffffffu || instances > 0x7fffffffu)
    throw std::invalid_argument("cga::gpu: a draw of " + std::to_string(count) + " vertices x " +
                                std::to_string(instances) + " instances exceeds GLsizei");
  glUseProgram(program);
  glBindVertexArray(vao);
  glEnable(GL_RASTERIZER_DISCARD);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, out);
  if (query) glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, query);
  glBeginTransformFeedback(GL_POINTS);
  glDrawArraysInstanced(GL_POINTS, 0, static_cast<GLsizei>(count), static_cast<GLsizei>(instances));
  glEndTransformFeedback();
  if (query) glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
  glDisable(GL_RASTERIZER_DISCARD);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
  glBindVertexArray(0);
}

}  // namespace

void Context::feedback_points(unsigned program, unsigned vao, std::size_t count, std::size_t instances,
                              const Buffer& out) const {
  bind_dummy_framebuffer();
  draw_feedback_points(program, vao, count, instances, out.get(), 0);
  check("the transform feedback draw");
}

std::size_t Context::capture_points(unsigned program, unsigned vao, std::size_t count, std::size_t instances,
                                    const Buffer& out) const {
  bind_dummy_framebuffer();
  GLuint query = 0;
  glGenQueries(1, &query);
  const Object owned(ObjectKind::query, query);
  draw_feedback_points(program, vao, count, instances, out.get(), query);
  GLuint64 written = 0;
  glGetQueryObjectui64v(query, GL_QUERY_RESULT, &written);
  check("the transform feedback draw");
  if (written != count * instances)
    throw GlError("cga::gpu: transform feedback wrote " + std::to_string(written) + " of " +
                  std::to_string(count * instances) + " vertices (output buffer too small?)");
  return static_cast<std::size_t>(written);
}

void Context::dispatch(unsigned program, unsigned groups_x, unsigned groups_y, unsigned groups_z) const {
  glUseProgram(program);
  glDispatchCompute(groups_x, groups_y, groups_z);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
  check("glDispatchCompute");
}

void Context::copy(const Buffer& src, const Buffer& dst, std::size_t bytes, std::size_t src_offset,
                   std::size_t dst_offset) const {
  if (src_offset + bytes > src.bytes || dst_offset + bytes > dst.bytes)
    throw std::out_of_range("cga::gpu::Context::copy: " + std::to_string(bytes) + " bytes from offset " +
                            std::to_string(src_offset) + " of a " + std::to_string(src.bytes) +
                            "-byte buffer to offset " + std::to_string(dst_offset) + " of a " +
                            std::to_string(dst.bytes) + "-byte buffer");
  if (bytes)
    glCopyNamedBufferSubData(src.get(), dst.get(), static_cast<GLintptr>(src_offset),
                             static_cast<GLintptr>(dst_offset), static_cast<GLsizeiptr>(bytes));
  check("glCopyNamedBufferSubData");
}

void Context::copy_compute(const Buffer& src, const Buffer& dst, std::size_t bytes) const {
  if (bytes > src.bytes || bytes > dst.bytes)
    throw std::out_of_range("cga::gpu::Context::copy_compute: " + std::to_string(bytes) + " bytes from a " +
                            std::to_string(src.bytes) + "-byte buffer to a " + std::to_string(dst.bytes) +
                            "-byte buffer");
  if (bytes % 16 != 0)
    throw std::invalid_argument("cga::gpu::Context::copy_compute: " + std::to_string(bytes) +
                                " bytes, not a multiple of 16");
  if (!copy_program_) {
    static constexpr const char* kCopy = R"glsl(#version 450
// One 16-B element per invocation, grid-stride: what a bandwidth-bound compute dispatch streams.
layout(local_size_x = 256) in;
layout(std430, binding = 0) readonly buffer Src { uvec4 src[]; };
layout(std430, binding = 1) writeonly buffer Dst { uvec4 dst[]; };
uniform uint u_count;
void main() {
  for (uint i = gl_GlobalInvocationID.x; i < u_count; i += gl_NumWorkGroups.x * 256u) dst[i] = src[i];
}
)glsl";
    const ShaderSource stage{GL_COMPUTE_SHADER, "cga::gpu::Context::copy_compute", kCopy};
    copy_program_ = make_program(std::span<const ShaderSource>(&stage, 1));
  }
  const GLuint prog = copy_program_.get();
  // Ranges within the SSBO block limit, a multiple of 64 KiB (any offset alignment a driver asks for).
  const std::size_t chunk = std::max<std::size_t>(max_storage_block_bytes() / 65536 * 65536, 65536);
  for (std::size_t at = 0; at < bytes; at += chunk) {
    const std::size_t n = std::min(chunk, bytes - at);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, src.get(), static_cast<GLintptr>(at), static_cast<GLsizeiptr>(n));
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 1, dst.get(), static_cast<GLintptr>(at), static_cast<GLsizeiptr>(n));
    const auto count = static_cast<GLuint>(n / 16);
    glProgramUniform1ui(prog, glGetUniformLocation(prog, "u_count"), count);
    dispatch(prog, std::min<GLuint>((count + 255) / 256, 65535));
  }
  check("copy_compute");
}

std::size_t Context::max_storage_block_bytes() const {
  GLint64 v = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &v);
  check("glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE)");
  return static_cast<std::size_t>(v);
}

GpuTimer::GpuTimer(const Context& context) : context_(&context) {
  GLuint q = 0;
  glGenQueries(1, &q);
  query_ = Object(ObjectKind::query, q);
  context.check("glGenQueries (timer)");
}

void GpuTimer::begin() {
  if (running_) throw GlError("cga::gpu::GpuTimer::begin: the timer is already running");
  glBeginQuery(GL_TIME_ELAPSED, query_.get());
  context_->check("glBeginQuery(GL_TIME_ELAPSED) (is another timer running?)");
  running_ = true;
  ended_ = false;
}

void GpuTimer::end() {
  if (!running_) throw GlError("cga::gpu::GpuTimer::end: the timer was not started");
  glEndQuery(GL_TIME_ELAPSED);
  context_->check("glEndQuery(GL_TIME_ELAPSED)");
  running_ = false;
  ended_ = true;
}

double GpuTimer::seconds() const {
  if (!ended_) throw GlError("cga::gpu::GpuTimer::seconds: begin() and end() were not both called");
  GLuint64 ns = 0;
  glGetQueryObjectui64v(query_.get(), GL_QUERY_RESULT, &ns);
  context_->check("glGetQueryObjectui64v(GL_TIME_ELAPSED result)");
  return static_cast<double>(ns) * 1e-9;
}

}  // namespace cga::gpu
