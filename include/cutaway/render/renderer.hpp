// cutaway/render/renderer.hpp — renders a Scene headless (or into a window's context).
//
// The Renderer composes the scene's techniques into one frame (src/render/renderer.cpp,
// buildFrame): the shading style, the cutters in registry order (src/cutters/registry.cpp),
// the geometry kinds (meshes, pipe networks, volumes). Its pass graph, in execution order; a
// bracketed group runs where the scene asks for it (tests/test_pass_graph.cpp matches the
// frame of every example against these lines):
//
// clang-format off
//   [cutawaySeed (cutawayCpu | cutawayAnchors jumpFloodingInit jumpFlooding/N... cutawayDepth) cutawayDilate]
//   [(cutawayCpuC2 | cutawayAnchorsC2 jumpFloodingInitC2 jumpFloodingC2/N... cutawayDepthC2) cutawayDilateC2]
//   [cutawayReaches]
//   [cutawayAtPixel]
//   [breakawayClip breakawayInnerClip]
//   [clipSurfaceSprites]
//   [shadowMap]
//   geometry
//   visibleObjects
//   [pipeOwners pipeProxies pipeStencilMasks pipes pipeAovs]
//   [ghostGeometry visibleGhosts]
//   [clipMask capMask]
//   [translucentLayers]
//   [lines]
//   [ghostLines]
//   composite
//   aovs
//   [channels]
//   [volumes]
//   [volumeLineSurfaces volumeLines]
//   [translucentComposite]
// clang-format on
//
// - cutawaySeed … cutawayDilate: the adaptive cutter (Burns08 §5): the region of interest's
//   rear hulls, the cutaway surface by jump flooding on the CPU or in compute passes (one per
//   step size N), dilated (src/cutters/adaptive/README.md).
// - cutawayCpuC2 … cutawayDilateC2: the contextual structure's second surface C₂ from the same
//   seed, every seed's angle raised to θ₂ (Burns11 §4.1.3, §5.2.3).
// - cutawayReaches: on the CPU path of the simple structure, the objects C may cut this frame
//   (Cutter::reaches): the others draw without the cutter's code.
// - cutawayAtPixel: the cutaway surfaces' depths at each pixel centre, which every fragment's
//   decision reads with one unfiltered fetch, and the simple structure's cut surface
//   (position, normal) there, for the back faces seen through the cut (Burns11 §5.2.4.1).
// - breakawayClip, breakawayInnerClip: Diepstraten03 §5's hull clip depths (outer, inner).
// - clipSurfaceSprites: Trapp13 §6.3's depth sprites, rebuilt per frame for animated parity.
// - shadowMap: style.shadows, the key light's depth (src/styles/shadows/README.md).
// - geometry: the background, every kind's objects with the style and the cutters' clipping
//   composed, Trapp13's caps, into the multisampled G-buffer (colour, normal, world position
//   + view depth, object id, cut mask, depth, and the cutters' channels).
// - visibleObjects: the objects with a sample in the G-buffer, which the next frame's geometry
//   pass draws before it tests the others' boxes (src/frame/occlusion_culling.hpp).
// - pipeOwners … pipeAovs: Konev18 §6's billboard pipes into the same G-buffer: the proxies
//   mark the stencil, which pipeStencilMasks turns into per-pixel sample masks for the
//   billboards' outside pass (src/kinds/pipes/README.md).
// - ghostGeometry, ghostLines: Burns08 §4.3's removed material as faded lines; visibleGhosts
//   marks the objects the ghost geometry shows, culled as the geometry pass's.
// - clipMask, capMask: Trapp13's clip-surface and cap coverage AOVs; clipMask runs only when
//   read: the geometry pass leaves out what a surface removes whole (Cutter::slab), so the
//   clipped objects are drawn again, whole, to mark where a surface clips them.
// - translucentLayers, translucentComposite: Burns11 ch. 2's occlusion reduction by
//   translucency, edge highlights or lines: the material a cutter reduces only partly, peeled
//   front to back into layers with their own feature lines (frame/translucent_layers.hpp),
//   blended over the final colour.
// - lines: silhouettes, creases and cut outlines per sample (styles/lines), only at the
//   pixels with an object or cut-mask sample (marked first in a depth buffer, `linePixels`,
//   so that the rasteriser skips the background; ghostLines does the same).
// - composite: the colour samples resolved, the line overlays blended.
// - aovs: sample 0 of every other G-buffer buffer copied into single-sample AOVs, run only
//   when an AOV is read (Frame's onRead passes: a frame that only shows its picture skips it).
// - channels: the same for the cutters' G-buffer channels (the cutout's signed distance, the
//   contextual structure's Ω and R), also when read.
// - volumes: the scene's volumes ray cast over the final colour up to the opaque depth, each
//   sample decided by the cutters (src/kinds/volumes).
// - volumeLineSurfaces, volumeLines: the volumes' line drawings (Burns11 §2.4): what hides a
//   line, then the lines with their halos over the final colour, clipped by the cutters.
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

// The deepest perspective depth range (far / near) the scene's active cutters resolve, for
// Camera::unresolvable (the adaptive cutaway keeps its cut in window depths: 1e4); 0: any.
float deepestDepthRange(const Scene& scene);

class Renderer {
 public:
  // Uploads the meshes and compiles the programs; the scene must outlive the renderer. Every
  // member runs OpenGL: the context `info` describes must be current on the calling thread
  // (without a current context, libepoxy aborts the process), from construction to
  // destruction.
  Renderer(const Scene& scene, const gl::ContextInfo& info);
  // The renderer refers to its scene: a temporary one would dangle by the first frame.
  Renderer(const Scene&& scene, const gl::ContextInfo& info) = delete;
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
  // The last frame's volume lines (a volume's "lines") as drawn, each run of segments the
  // cutters keep, visible or hidden, for vector output (writeVolumeLineSvg).
  VolumeLineDrawing volumeLineDrawing() const;
  // Occlusion culling of the scene's meshes by the last frame's visibility (on by default):
  // the same images, exactly so for a still view (src/frame/occlusion_culling.hpp).
  void setOcclusionCulling(bool on);
  // Scene objects the last frame's geometry pass did not draw, found hidden by that culling.
  std::size_t culledObjects() const;
  // Object draws the last frame's translucent layers (Burns11 ch. 2) left out by that culling:
  // objects whose fragments all lay at or in front of an earlier layer, peeled already.
  std::size_t peeledLayerDraws() const;
  // Where the adaptive cutter's jump flooding runs ("gpu" or "cpu"), or null without it.
  const char* cutawayComputePath() const;
  // Triangles of the scene's meshes as the last frame drew them: grid meshes (terrains) and
  // objects with coarser versions (shafts) at the detail its view selected (Scene::pixelError).
  std::size_t meshTriangles() const;

 private:
  struct Impl;
  const Scene& scene_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cutaway
