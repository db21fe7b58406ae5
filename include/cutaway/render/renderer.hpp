// cutaway/render/renderer.hpp — renders a Scene headless (or into a window's context).
//
// The frame: with the adaptive cutter, its preparation passes first (seed, jump flooding,
// dilation: src/cutters/adaptive/README.md); "geometry" draws the visible objects with the
// scene's style and the cutter's clipping into multisampled targets (colour, normal, world
// position + view depth, object id, cut mask, depth); "ghostGeometry" / "ghostLines" draw
// removed material as faded lines; "lines" finds silhouettes, creases and cut outlines per
// sample (styles/lines); "composite" resolves the samples into the final colour and copies
// sample 0 of every intermediate buffer into single-sample AOVs. With style.shadows, a
// "shadowMap" pass before "geometry" draws the shadow casters from the key light
// (src/styles/shadows/README.md).
//
//   auto context = cutaway::gl::HeadlessContext::create();
//   cutaway::Scene scene = cutaway::loadScene("examples/engine.json");
//   cutaway::Renderer renderer(scene, context->info());
//   renderer.render();
//   cutaway::writePng("engine.png", renderer.readColor());
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cutaway/core/image.hpp"
#include "cutaway/gl/context.hpp"
#include "cutaway/frame/aov.hpp"
#include "cutaway/frame/frame.hpp"
#include "cutaway/scene/scene.hpp"

namespace cutaway {

class Renderer {
 public:
  // Uploads the meshes and compiles the programs; the scene must outlive the renderer.
  Renderer(const Scene& scene, const gl::ContextInfo& info);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders one frame with `camera` (already resolved: near/far set) and the objects'
  // animation at `time` seconds; or the scene's own camera at `time`.
  void render(const Camera& camera, float time = 0.0f);
  void render() { renderAt(0.0f); }
  void renderAt(float time) { render(scene_.resolvedCamera(time), time); }

  Rgba8Image readColor() const;
  // Every AOV: the frame's targets with a meaning, then the cutters' own (extraAovs), rows
  // top-down.
  std::vector<Aov> readAovs() const;
  // The AOVs that are no frame target: the clip surfaces' depth sprites, the terrain
  // opening's distance texture.
  std::vector<Aov> extraAovs() const;
  std::vector<PassTiming> timings();
  const Frame& frame() const;
  // The final colour texture (single sample, RGBA8), e.g. for a window's blit.
  GLuint colorTexture() const;
  // Where the adaptive cutter's jump flooding runs ("gpu" or "cpu"), or null without it.
  const char* cutawayComputePath() const;

 private:
  struct Impl;
  const Scene& scene_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cutaway
