// What every technique of one renderer (geometry kind, cutter, style) is built with: the
// scene, the frame it adds targets and passes to, the binding allocator, the scene's meshes on
// the GPU, the G-buffer, and the hooks through which one technique asks for what another
// provides. The composer (src/render/renderer.cpp) fills the hooks and the geometry programs'
// shading before any pass runs; techniques keep a reference to it.
#pragma once

#include <algorithm>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "cutaway/core/error.hpp"
#include "cutaway/frame/frame.hpp"
#include "cutaway/geometry/mesh.hpp"
#include "cutaway/gl/context.hpp"
#include "cutaway/gl/shader.hpp"
#include "cutaway/scene/scene.hpp"
#include "frame/bindings.hpp"
#include "frame/gbuffer.hpp"
#include "frame/samples.hpp"
#include "frame/scene_meshes.hpp"

namespace cutaway {

// Draw the rear hulls of the objects of interest (Burns08 §5.1), with the depth test set to
// GREATER by the caller: each kind writes the window depth of its rear surface to location 0
// and the seeding object's local angle θ (radians) to location 1.
struct RearHullRequest {
  // θ of an object of interest; null for geometry that is no scene object (a pipe network).
  std::function<float(const SceneObject*)> theta;
};

struct FrameSetup {
  const Scene& scene;
  const gl::ContextInfo& context;
  Frame& frame;
  Bindings& bindings;
  const SceneMeshes& meshes;
  GBuffer& gbuffer;
  Bounds sceneBounds;  // of the visible geometry over the whole animation

  // The shading of the geometry programs (those writing the G-buffer): the active style's GLSL
  // ("style.glsl") and the generated sources (the cutters' composition, the G-buffer's
  // channels). Filled by the composer once every technique has declared itself.
  std::map<std::string, std::string> shadingAliases, shadingSources;
  // A cutter leaves translucent fragments (Cutter::translucentLayers): the kinds build the layer
  // variant of their geometry programs (TRANSLUCENT_LAYER) for frame/translucent_layers.hpp.
  bool translucentLayers = false;
  gl::ProgramDesc geometryProgram(std::vector<std::pair<GLenum, std::string>> stages,
                                  std::map<std::string, std::string> defines = {}) const {
    return bindings.program({.stages = std::move(stages),
                             .defines = sampleDefines(scene.samples, std::move(defines)),
                             .aliases = shadingAliases,
                             .sources = shadingSources});
  }

  // Refuses an image a technique uploads as a 2-D texture that the device cannot hold (GL would
  // leave the texture empty and the picture silently wrong): `place` is its pointer in the
  // scene file, `what` names it ("an offset map").
  void requireTextureFits(const std::string& place, const std::string& what, int width,
                          int height) const {
    if (context.maxTextureSize > 0 && std::max(width, height) > context.maxTextureSize)
      throw Error(scene.file.string(), place,
                  what + " of " + std::to_string(width) + "×" + std::to_string(height) +
                      " texels exceeds the GPU's largest texture, " +
                      std::to_string(context.maxTextureSize) + " on a side");
  }

  // Connected by the composer to every geometry kind.
  std::function<void(const RearHullRequest&)> drawInterestRearHulls;
  std::function<void()> drawShadowCasters;  // with the light's frame uniforms bound
  // Binds what every geometry program's shading reads (the style's block and textures, the
  // shadow map), for passes after the geometry pass that draw into the G-buffer.
  std::function<void()> bindShading;
};

}  // namespace cutaway
