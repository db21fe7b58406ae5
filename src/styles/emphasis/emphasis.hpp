// Emphasis by importance for every style (Burns11 §3.3.1; emphasis.glsl): its uniform block,
// refilled every frame from the live options (style.emphasis). The geometry programs of the
// mesh kind and the caps call emphasize() with their object's importance
// (emphasisImportance()).
#pragma once

#include "frame/frame_setup.hpp"
#include "frame/uniform_block.hpp"

namespace cutaway {

class Emphasis {
 public:
  explicit Emphasis(FrameSetup& setup) : setup_(setup), block_(setup.bindings, "EMPHASIS") {}
  void beginFrame() const;
  void bindForGeometry() const { block_.bind(); }

 private:
  struct Block {  // std140 mirror of emphasis.glsl's EmphasisUniforms
    glm::vec4 emphasis, paper;
  };
  FrameSetup& setup_;
  UniformBlock<Block> block_;
};

}  // namespace cutaway
