// A technique's own std140 uniform block: allocated through the Bindings under a name (its
// GLSL declares `layout(std140, binding = BLOCK_<NAME>)`), filled every frame from the live
// options, bound in the pass that reads it.
#pragma once

#include <string>

#include "cutaway/gl/objects.hpp"
#include "frame/bindings.hpp"

namespace cutaway {

template <class Block>
class UniformBlock {
 public:
  UniformBlock(Bindings& bindings, const std::string& name)
      : binding_(bindings.uniformBlock(name)),
        buffer_(gl::Buffer::create(sizeof(Block), nullptr, GL_DYNAMIC_STORAGE_BIT)) {}
  void update(const Block& block) const { glNamedBufferSubData(buffer_.id(), 0, sizeof block, &block); }
  void bind() const { glBindBufferBase(GL_UNIFORM_BUFFER, binding_, buffer_.id()); }

 private:
  GLuint binding_;
  gl::Buffer buffer_;
};

}  // namespace cutaway
