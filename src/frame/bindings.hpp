// The binding points of one renderer's programs, allocated in one place. A technique (cutter,
// style, geometry kind) asks for the texture units, image units, buffer bindings and explicit
// uniform locations its shared GLSL declares, by name; the GLSL names them by the #define the
// allocator injects into every program built through it:
//
//   const GLuint unit = bindings.textureUnit("CUTAWAY_DEPTH");       // C++: bind here
//   layout(binding = UNIT_CUTAWAY_DEPTH) uniform sampler2D uCutawayDepth;   // GLSL
//
// Asking again for a name returns the same point, so every program that includes the same
// GLSL agrees. The ranges:
//   texture units   0–7 belong to the pass that is drawing (a full-screen pass's inputs, bound
//                   right before its draw); 8 and up are allocated here, for what programs of
//                   several techniques read in the same draw (the geometry pass).
//   image units     0 belongs to the pass that is running (a compute pass's output, bound
//                   right before its dispatch); 1 and up are allocated here.
//   uniform blocks  0 is the frame's (frame/frame_uniforms.glsl); the rest allocated here.
//   storage blocks  all allocated here.
//   uniform locations  0–63 belong to the program's own stages (a geometry kind's vertex and
//                   fragment shader, a pass's full-screen shader); 64 and up are allocated
//                   here, for technique GLSL included into another technique's program.
#pragma once

#include <map>
#include <string>

#include <epoxy/gl.h>

#include "cutaway/gl/shader.hpp"

namespace cutaway {

class Bindings {
 public:
  static constexpr GLuint kFrameUniformBlock = 0;

  GLuint textureUnit(const std::string& name, int count = 1);
  GLuint imageUnit(const std::string& name);
  GLuint uniformBlock(const std::string& name);
  GLuint storageBlock(const std::string& name);
  GLint uniformLocation(const std::string& name, int count = 1);

  // UNIT_*, IMAGE_*, BLOCK_*, SSBO_*, LOC_* for everything allocated so far.
  const std::map<std::string, std::string>& defines() const { return defines_; }
  // `desc` with the allocated defines added (its own take precedence).
  gl::ProgramDesc program(gl::ProgramDesc desc) const;
  gl::Program build(gl::ProgramDesc desc) const { return gl::buildProgram(program(std::move(desc))); }

 private:
  GLuint allocate(const std::string& prefix, const std::string& name, GLuint& next, int count,
                  GLint limit);
  std::map<std::string, std::string> defines_;
  GLuint nextTextureUnit_ = 8, nextImageUnit_ = 1, nextUniformBlock_ = 1, nextStorageBlock_ = 0,
         nextLocation_ = 64;
};

}  // namespace cutaway
