// The one interface every shading style implements, and its entry in the registry
// (src/styles/registry.cpp). A style decides how a kept fragment is shaded, independently of
// the cut (Diepstraten03): its GLSL file, included as "style.glsl" into every geometry
// program, defines
//   vec3 shadeSurface(SurfacePoint s);   // styles/surface.glsl
// and reads its own uniform block (binding BLOCK_STYLE, filled every frame from the live
// options, so a colour or a weight changes without a new renderer) and textures.
//
// Adding a style: its folder (options header in include/cutaway/styles, schema, GLSL, this
// interface, README) and one line in registry.cpp (docs/architecture.md).
#pragma once

#include <memory>
#include <string>

#include "cutaway/core/options.hpp"
#include "frame/frame_setup.hpp"
#include "frame/frame_uniforms.hpp"

namespace cutaway {

class ShadingStyle {
 public:
  virtual ~ShadingStyle() = default;
  // Per frame: its uniform block from the live options.
  virtual void beginFrame(const FrameState&) {}
  // In every pass with geometry programs: binds its block and textures.
  virtual void bindForGeometry() const {}
};

struct StyleType {
  std::string name;   // the scene file's style.name: "blinn-phong"
  std::string key;    // the key of its options under "style", the viewer's and CLI's prefix
  std::string title;  // for panels
  std::string glsl;   // e.g. "styles/gooch/gooch.glsl"
  const OptionsSchema* schema;
  std::unique_ptr<ShadingStyle> (*create)(FrameSetup&);
};

}  // namespace cutaway
