// cutaway/gl/objects.hpp — move-only owners of OpenGL objects (direct state access only).
//
// Each wrapper creates its object with glCreate* and deletes it in the destructor; a
// moved-from wrapper is empty (id() == 0) and deletes nothing.
//
//   cutaway::gl::Texture depth = cutaway::gl::Texture::create2D(GL_DEPTH_COMPONENT32F, 640, 480);
//   cutaway::gl::Framebuffer fbo = cutaway::gl::Framebuffer::create();
//   glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
#pragma once

#include <epoxy/gl.h>

#include <utility>

namespace cutaway::gl {

template <void (*Delete)(GLuint)>
class Object {
 public:
  Object() = default;
  explicit Object(GLuint id) : id_(id) {}
  ~Object() { reset(); }
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;
  Object(Object&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  Object& operator=(Object&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_) Delete(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

namespace detail {
inline void deleteBuffer(GLuint id) {
  glDeleteBuffers(1, &id);
}
inline void deleteTexture(GLuint id) {
  glDeleteTextures(1, &id);
}
inline void deleteFramebuffer(GLuint id) {
  glDeleteFramebuffers(1, &id);
}
inline void deleteVertexArray(GLuint id) {
  glDeleteVertexArrays(1, &id);
}
inline void deleteQuery(GLuint id) {
  glDeleteQueries(1, &id);
}
inline void deleteProgram(GLuint id) {
  glDeleteProgram(id);
}
inline void deleteShader(GLuint id) {
  glDeleteShader(id);
}
}  // namespace detail

// Whether the GL calls in `allocate` ran out of device memory (GL_OUT_OF_MEMORY); errors
// from before it are cleared first, so that they are not taken for its own.
template <class Allocate>
bool outOfMemory(Allocate allocate) {
  while (glGetError() != GL_NO_ERROR) {
  }
  allocate();
  bool out = false;
  for (GLenum e; (e = glGetError()) != GL_NO_ERROR;) out = out || e == GL_OUT_OF_MEMORY;
  return out;
}

class Buffer : public Object<detail::deleteBuffer> {
 public:
  using Object::Object;
  // Immutable storage (glNamedBufferStorage) holding `bytes` bytes copied from `data`.
  static Buffer create(GLsizeiptr bytes, const void* data, GLbitfield flags = 0) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    glNamedBufferStorage(id, bytes, data, flags);
    return Buffer(id);
  }
};

class Texture : public Object<detail::deleteTexture> {
 public:
  using Object::Object;
  static Texture create(GLenum target) {
    GLuint id = 0;
    glCreateTextures(target, 1, &id);
    return Texture(id);
  }
  // A 2-D texture with one level; `samples` ≥ 1 makes a multisample texture (also with one
  // sample, so that sampler2DMS code paths serve every sample count).
  static Texture create2D(GLenum internalFormat, int width, int height, int samples = 0) {
    if (samples >= 1) {
      Texture t = create(GL_TEXTURE_2D_MULTISAMPLE);
      glTextureStorage2DMultisample(t.id(), samples, internalFormat, width, height, GL_TRUE);
      return t;
    }
    Texture t = create(GL_TEXTURE_2D);
    glTextureStorage2D(t.id(), 1, internalFormat, width, height);
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
  }
};

class Framebuffer : public Object<detail::deleteFramebuffer> {
 public:
  using Object::Object;
  static Framebuffer create() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return Framebuffer(id);
  }
};

class VertexArray : public Object<detail::deleteVertexArray> {
 public:
  using Object::Object;
  static VertexArray create() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return VertexArray(id);
  }
};

class Query : public Object<detail::deleteQuery> {
 public:
  using Object::Object;
  static Query create(GLenum target) {
    GLuint id = 0;
    glCreateQueries(target, 1, &id);
    return Query(id);
  }
};

class Shader : public Object<detail::deleteShader> {
 public:
  using Object::Object;
};

class Program : public Object<detail::deleteProgram> {
 public:
  using Object::Object;
};

}  // namespace cutaway::gl
