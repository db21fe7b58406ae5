#include "frame/bindings.hpp"

#include "cutaway/core/error.hpp"

namespace cutaway {

namespace {
GLint limit(GLenum what) {
  GLint value = 0;
  glGetIntegerv(what, &value);
  return value;
}
}  // namespace

GLuint Bindings::allocate(const std::string& prefix, const std::string& name, GLuint& next,
                          int count, GLint max) {
  const std::string key = prefix + "_" + name;
  if (const auto it = defines_.find(key); it != defines_.end()) return GLuint(std::stoul(it->second));
  if (max > 0 && GLint(next) + count > max)
    throw Error("bindings", key,
                "the driver offers only " + std::to_string(max) + " of these binding points");
  const GLuint point = next;
  next += GLuint(count);
  defines_[key] = std::to_string(point);
  return point;
}

GLuint Bindings::textureUnit(const std::string& name, int count) {
  return allocate("UNIT", name, nextTextureUnit_, count,
                  limit(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS));
}

GLuint Bindings::imageUnit(const std::string& name) {
  return allocate("IMAGE", name, nextImageUnit_, 1, limit(GL_MAX_IMAGE_UNITS));
}

GLuint Bindings::uniformBlock(const std::string& name) {
  return allocate("BLOCK", name, nextUniformBlock_, 1, limit(GL_MAX_UNIFORM_BUFFER_BINDINGS));
}

GLuint Bindings::storageBlock(const std::string& name) {
  return allocate("SSBO", name, nextStorageBlock_, 1,
                  limit(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS));
}

GLint Bindings::uniformLocation(const std::string& name, int count) {
  return GLint(allocate("LOC", name, nextLocation_, count, limit(GL_MAX_UNIFORM_LOCATIONS)));
}

gl::ProgramDesc Bindings::program(gl::ProgramDesc desc) const {
  desc.defines.insert(defines_.begin(), defines_.end());  // keeps the desc's own
  return desc;
}

}  // namespace cutaway
