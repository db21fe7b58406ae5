// Image-space passes: one triangle covering the viewport (frame/fullscreen.vert), no
// vertex buffers.
#pragma once

#include <map>
#include <string>

#include "cutaway/gl/shader.hpp"

namespace cutaway {

inline gl::Program buildFullscreenProgram(const std::string& fragment,
                                          std::map<std::string, std::string> defines = {}) {
  return gl::buildProgram(
      {.stages = {{GL_VERTEX_SHADER, "frame/fullscreen.vert"}, {GL_FRAGMENT_SHADER, fragment}},
       .defines = std::move(defines)});
}

class FullscreenTriangle {
 public:
  // Draws with the bound program (the core profile needs a vertex array, even an empty one).
  void draw() const {
    glBindVertexArray(vertexArray_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }

 private:
  gl::VertexArray vertexArray_ = gl::VertexArray::create();
};

}  // namespace cutaway
