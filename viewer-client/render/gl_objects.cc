#include "viewer-client/render/gl_objects.h"

#include <vector>

namespace reenact::viewer {
namespace gl_detail {

void DeleteBuffer(GLuint id) { glDeleteBuffers(1, &id); }
void DeleteVertexArray(GLuint id) { glDeleteVertexArrays(1, &id); }
void DeleteTexture(GLuint id) { glDeleteTextures(1, &id); }
void DeleteRenderbuffer(GLuint id) { glDeleteRenderbuffers(1, &id); }
void DeleteFramebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void DeleteProgram(GLuint id) { glDeleteProgram(id); }

}  // namespace gl_detail

namespace {

template <typename Handle, void (*Gen)(GLsizei, GLuint*)>
Handle Generate() {
  GLuint id = 0;
  Gen(1, &id);
  REENACT_CHECK(id != 0, "OpenGL could not create an object (no current context?)");
  return Handle(id);
}

void GenBuffers(GLsizei n, GLuint* ids) { glGenBuffers(n, ids); }
void GenVertexArrays(GLsizei n, GLuint* ids) { glGenVertexArrays(n, ids); }
void GenTextures(GLsizei n, GLuint* ids) { glGenTextures(n, ids); }
void GenRenderbuffers(GLsizei n, GLuint* ids) { glGenRenderbuffers(n, ids); }
void GenFramebuffers(GLsizei n, GLuint* ids) { glGenFramebuffers(n, ids); }

// Shader object owned for the duration of a link.
class ShaderGuard {
 public:
  explicit ShaderGuard(GLenum type) : id_(glCreateShader(type)) {}
  ShaderGuard(const ShaderGuard&) = delete;
  ShaderGuard& operator=(const ShaderGuard&) = delete;
  ~ShaderGuard() {
    if (id_ != 0) glDeleteShader(id_);
  }
  GLuint id() const { return id_; }

 private:
  GLuint id_;
};

std::string ShaderLog(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
  return log.data();
}

std::string ProgramLog(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<size_t>(std::max(length, 1)), '\0');
  glGetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, log.data());
  return log.data();
}

Status Compile(const ShaderGuard& shader, const std::string& name, const char* stage,
               const std::string& source) {
  if (shader.id() == 0) {
    return MakeError("gl_shader", name + ": glCreateShader failed for the " + stage +
                                      " shader (no current GL context?)");
  }
  const char* text = source.c_str();
  glShaderSource(shader.id(), 1, &text, nullptr);
  glCompileShader(shader.id());
  GLint ok = GL_FALSE;
  glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    return MakeError("gl_shader",
                     name + ": " + stage + " shader failed to compile: " + ShaderLog(shader.id()));
  }
  return {};
}

}  // namespace

GlBuffer MakeBuffer() { return Generate<GlBuffer, GenBuffers>(); }
GlVertexArray MakeVertexArray() { return Generate<GlVertexArray, GenVertexArrays>(); }
GlTexture MakeTexture() { return Generate<GlTexture, GenTextures>(); }
GlRenderbuffer MakeRenderbuffer() { return Generate<GlRenderbuffer, GenRenderbuffers>(); }
GlFramebuffer MakeFramebuffer() { return Generate<GlFramebuffer, GenFramebuffers>(); }

Expected<GlProgram> MakeProgram(const std::string& name, const std::string& vertex_source,
                                const std::string& fragment_source) {
  ShaderGuard vertex(GL_VERTEX_SHADER), fragment(GL_FRAGMENT_SHADER);
  if (Status s = Compile(vertex, name, "vertex", vertex_source); !s) return s.error();
  if (Status s = Compile(fragment, name, "fragment", fragment_source); !s) return s.error();
  GlProgram program(glCreateProgram());
  if (!program) return MakeError("gl_shader", name + ": glCreateProgram failed");
  glAttachShader(program.id(), vertex.id());
  glAttachShader(program.id(), fragment.id());
  glLinkProgram(program.id());
  glDetachShader(program.id(), vertex.id());
  glDetachShader(program.id(), fragment.id());
  GLint ok = GL_FALSE;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    return MakeError("gl_shader", name + ": program failed to link: " + ProgramLog(program.id()));
  }
  return program;
}

GLint UniformLocation(const GlProgram& program, const char* name) {
  const GLint location = glGetUniformLocation(program.id(), name);
  REENACT_CHECK(location >= 0, std::string("shader has no active uniform ") + name);
  return location;
}

std::string GlErrorString() {
  switch (glGetError()) {
    case GL_NO_ERROR: return {};
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: return "GL error";
  }
}

}  // namespace reenact::viewer
