#pragma once
// Move-only RAII owners of OpenGL objects (buffer, vertex array, texture, renderbuffer,
// framebuffer, shader program). Each is created and destroyed in the GL context current at
// that time; the owner of the context must destroy these before the context (the renderer
// keeps its context alive longer than its objects). A default-constructed object owns
// nothing (id 0).

#include <string>
#include <utility>

#include <epoxy/gl.h>

#include "common/error/expected.h"

namespace reenact::viewer {

// One GL name with its delete function; Delete(GLuint) must accept its own id only.
template <void (*Delete)(GLuint)>
class GlHandle {
 public:
  GlHandle() = default;
  explicit GlHandle(GLuint id) : id_(id) {}
  GlHandle(const GlHandle&) = delete;
  GlHandle& operator=(const GlHandle&) = delete;
  GlHandle(GlHandle&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  GlHandle& operator=(GlHandle&& other) noexcept {
    if (this != &other) {
      Reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  ~GlHandle() { Reset(); }

  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void Reset() {
    if (id_ != 0) Delete(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

namespace gl_detail {
void DeleteBuffer(GLuint id);
void DeleteVertexArray(GLuint id);
void DeleteTexture(GLuint id);
void DeleteRenderbuffer(GLuint id);
void DeleteFramebuffer(GLuint id);
void DeleteProgram(GLuint id);
}  // namespace gl_detail

using GlBuffer = GlHandle<gl_detail::DeleteBuffer>;
using GlVertexArray = GlHandle<gl_detail::DeleteVertexArray>;
using GlTexture = GlHandle<gl_detail::DeleteTexture>;
using GlRenderbuffer = GlHandle<gl_detail::DeleteRenderbuffer>;
using GlFramebuffer = GlHandle<gl_detail::DeleteFramebuffer>;
using GlProgram = GlHandle<gl_detail::DeleteProgram>;

GlBuffer MakeBuffer();
GlVertexArray MakeVertexArray();
GlTexture MakeTexture();
GlRenderbuffer MakeRenderbuffer();
GlFramebuffer MakeFramebuffer();

// Compiles a vertex and a fragment shader (GLSL 330 core) and links them. A compile or
// link failure is an Error with code "gl_shader" whose message names the stage and quotes
// the driver's info log. `name` labels the program in messages.
Expected<GlProgram> MakeProgram(const std::string& name, const std::string& vertex_source,
                                const std::string& fragment_source);

// Location of a uniform that the program must have (a missing one is a bug: CHECK).
GLint UniformLocation(const GlProgram& program, const char* name);

// The current GL error as text ("GL_INVALID_OPERATION"), or empty if there is none.
std::string GlErrorString();

}  // namespace reenact::viewer
