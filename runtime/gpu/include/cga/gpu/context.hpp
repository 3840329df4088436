// The small OpenGL 4.5 backend: a headless EGL context (EGL device platform, else Mesa's surfaceless
// platform), programs compiled with the driver's log in the exception, buffers, transform feedback capture
// and compute dispatch. Everything throws: Unavailable when no EGL display/GL 4.5 context can be made,
// GlError for a failed compile/link or a GL error after a call.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace cga::gpu {

// No EGL display, no OpenGL 4.5 core context, or a required entry point is missing. The message says which
// step failed and with which EGL error.
struct Unavailable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A GL call failed: shader compile/link (with the driver's log), framebuffer incomplete, glGetError != 0.
struct GlError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An owned GL object name; moves, never copies. The deleter is chosen by the kind.
enum class ObjectKind { buffer, program, vertex_array, framebuffer, renderbuffer, query };
class Object {
 public:
  Object() = default;
  Object(ObjectKind kind, unsigned name) : kind_(kind), name_(name) {}
  Object(Object&& o) noexcept : kind_(o.kind_), name_(o.name_) { o.name_ = 0; }
  Object& operator=(Object&& o) noexcept;
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;
  ~Object();
  unsigned get() const { return name_; }
  explicit operator bool() const { return name_ != 0; }

 private:
  void release() noexcept;
  ObjectKind kind_ = ObjectKind::buffer;
  unsigned name_ = 0;
};

// A GPU buffer of `bytes` bytes (immutable storage with dynamic updates and readback).
struct Buffer {
  Object object;
  std::size_t bytes = 0;
  unsigned get() const { return object.get(); }
};

// One stage's source text and where it comes from (for error messages).
struct ShaderSource {
  unsigned stage = 0;   // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER
  std::string name;     // e.g. the assembled file's path
  std::string text;
};

struct ProgramOptions {
  // Transform feedback: the vertex shader outputs to capture, interleaved into one buffer, in order.
  std::vector<std::string> feedback_varyings;
};

// A headless OpenGL 4.5 core context, current on the creating thread for its lifetime. One at a time.
class Context {
 public:
  // Throws Unavailable with the reason (which platforms were tried, the EGL errors) when it cannot be made.
  Context();
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  std::string renderer() const;   // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version() const;    // GL_VERSION
  std::string platform() const { return platform_; }  // "EGL device 0" or "EGL surfaceless (Mesa)"

  // Compiles and links; GlError names the stage and the file and carries the driver's log.
  Object make_program(std::span<const ShaderSource> stages, const ProgramOptions& options = {}) const;

  Buffer make_buffer(std::size_t bytes, const void* data = nullptr) const;
  void upload(const Buffer& b, const void* data, std::size_t bytes, std::size_t offset = 0) const;
  void read(const Buffer& b, void* data, std::size_t bytes, std::size_t offset = 0) const;
  template <class T>
  Buffer make_buffer(std::span<const T> data) const {
    return make_buffer(data.size_bytes(), data.data());
  }
  template <class T>
  std::vector<T> read_all(const Buffer& b) const {
    std::vector<T> out(b.bytes / sizeof(T));
    read(b, out.data(), out.size() * sizeof(T));
    return out;
  }

  // Throws GlError naming `what` when glGetError reports an error.
  void check(const char* what) const;
  // glFinish: waits until the GPU has executed every command issued so far.
  void finish() const;

  // Binds a tiny framebuffer object so that draws (including rasterizer-discarded transform feedback
  // draws) are legal without a default framebuffer (GL_INVALID_FRAMEBUFFER_OPERATION otherwise).
  void bind_dummy_framebuffer() const;

  // Runs `count` vertices (times `instances`) of `vao` through `program` as points with rasterization
  // discarded, capturing the program's feedback varyings into `out` from offset 0. Checks with a query that
  // count * instances vertices were written and returns that number.
  std::size_t capture_points(unsigned program, unsigned vao, std::size_t count, std::size_t instances,
                             const Buffer& out) const;
  // The same draw without the query: nothing waits for the GPU (for timing). The caller makes `out` large
  // enough (transform feedback silently stops at the end of the buffer).
  void feedback_points(unsigned program, unsigned vao, std::size_t count, std::size_t instances,
                       const Buffer& out) const;

  // glCopyNamedBufferSubData of `bytes` bytes from `src` at `src_offset` to `dst` at `dst_offset`, on the GPU
  // (queued; nothing waits). Throws std::out_of_range when a range leaves its buffer.
  void copy(const Buffer& src, const Buffer& dst, std::size_t bytes, std::size_t src_offset = 0,
            std::size_t dst_offset = 0) const;

  // The same copy done by a compute shader (16-B loads and stores, one per invocation, in ranges of at most
  // the SSBO block limit): the memory bandwidth a compute dispatch can reach, which on some drivers differs
  // a lot from the buffer copy's (NVIDIA: 177 GB/s glCopyNamedBufferSubData on an H200). `bytes` and the
  // offsets must be multiples of 16 (std::invalid_argument otherwise); queued, nothing waits.
  void copy_compute(const Buffer& src, const Buffer& dst, std::size_t bytes) const;

  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE: the largest buffer range one SSBO binding may expose to a shader.
  std::size_t max_storage_block_bytes() const;

  // glDispatchCompute followed by the barriers buffer reads need.
  void dispatch(unsigned program, unsigned groups_x, unsigned groups_y = 1, unsigned groups_z = 1) const;

 private:
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string platform_;
  Object dummy_fbo_, dummy_rb_;
  mutable Object copy_program_;  // copy_compute's, compiled on first use
};

// GPU time of the commands issued between begin() and end() (a GL_TIME_ELAPSED query): the time the GPU
// spent on them, not the caller's. One timer may be running at a time in a context (GL allows one active
// GL_TIME_ELAPSED query). seconds() waits for the result; begin() may be called again afterwards.
class GpuTimer {
 public:
  explicit GpuTimer(const Context& context);
  void begin();
  void end();
  double seconds() const;  // throws GlError when begin/end were not both called

 private:
  const Context* context_;
  Object query_;
  bool running_ = false, ended_ = false;
};

// The name of a shader stage constant, for messages.
const char* stage_name(unsigned stage);

}  // namespace cga::gpu
