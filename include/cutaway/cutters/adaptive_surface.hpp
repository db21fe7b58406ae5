// cutaway/cutters/adaptive_surface.hpp — the adaptive cutaway surface (Burns08 §5, Burns11
// eq. 4.2 with eqs. 5.7, 5.8, 6.1–6.4) for another OpenGL 4.5 application: it hands over the
// depth of its objects of interest, and gets back the depth of the cutaway surface to clip
// its other objects against. No scene, no renderer: the application draws everything.
//
//   // Once, with the application's context current:
//   cutaway::AdaptiveCutawaySurface surface({.angle = 30.0f, .bufferSize = 512});
//
//   // Every frame: the objects of interest into a depth texture of any size, cleared to 0 and
//   // drawn with the greater-than test so that it keeps their rear hull (0 = no object):
//   glClearDepth(0.0); glClear(GL_DEPTH_BUFFER_BIT); glDepthFunc(GL_GREATER); drawInterest();
//   const GLuint cut = surface.compute(interestDepth, projection, view);
//
//   // In the fragment shader of the other objects (uv = gl_FragCoord.xy / viewport size):
//   //   float c = gl_FrontFacing ? texture(uCut, uv).r : texture(uCutDilated, uv).r;
//   //   if (gl_FragCoord.z < c) discard;   // in front of the cutaway surface: removed
//   // with uCut = cut and uCutDilated = surface.dilatedTexture().
//
// Depths are window depths in [0, 1] under the application's own projection (perspective or
// orthographic), with OpenGL's default depth range and clip control (NDC z = 2·depth − 1). The
// result is linearly filtered (Burns08 §6), 0 where nothing is cut. compute() runs the passes
// the renderer's adaptive cutter runs (cutawayAnchors, jump flooding, cutawayDepth,
// cutawayDilate; or the same math on the CPU on software rasterisers) after one seed pass that
// takes, for each cutaway-buffer texel, the farthest depth in its footprint. It puts back the
// application's framebuffers, program, vertex array, viewport, colour mask, depth test, blend,
// scissor, stencil, culling, rasteriser discard and pixel-transfer state (none of which
// changes the result); it rebinds texture units 0–2 and (on the GPU path) image unit 0, and
// runs no timer queries.
#pragma once

#include <memory>

#include <glm/glm.hpp>

#include "cutaway/cutters/adaptive.hpp"
#include "cutaway/gl/objects.hpp"

namespace cutaway {

class AdaptiveCutawaySurface {
 public:
  // Needs a current OpenGL 4.5 core context (epoxy resolves the entry points). bufferSize,
  // variant and compute are fixed here (Compute::Auto: the CPU kernel on a software
  // rasteriser); angle, perspectiveCompensation, edgeCompression, edgeRegion,
  // directionalConstraint and floorNormal may change between frames through options().
  // Throws cutaway::Error for options out of their schema's range.
  explicit AdaptiveCutawaySurface(const AdaptiveCutawayOptions& options = {});
  ~AdaptiveCutawaySurface();
  AdaptiveCutawaySurface(const AdaptiveCutawaySurface&) = delete;
  AdaptiveCutawaySurface& operator=(const AdaptiveCutawaySurface&) = delete;

  // C(p) from `interestDepth` (a depth or red-channel float texture: the rear hull's window
  // depth, 0 where there is none) seen through `projection` and `view` (world → eye; its
  // rotation turns the floor normal). `interestAngle`, if not 0, is a texture of the same
  // size holding each object's local angle θ in radians (Burns11 §6.2.1); else every seed
  // has options().angle. Returns cutawayTexture().
  GLuint compute(GLuint interestDepth, const glm::mat4& projection, const glm::mat4& view,
                 GLuint interestAngle = 0);

  // bufferSize² R32F textures: the cutaway surface, and its 1-pixel minimum for back faces.
  GLuint cutawayTexture() const;
  GLuint dilatedTexture() const;
  // The seed compute() last took (window depth, 0 = none), as the cutaway buffer holds it.
  GLuint seedTexture() const;
  int bufferSize() const;
  // "gpu" or "cpu": where the jump flooding runs.
  const char* computePath() const;

  AdaptiveCutawayOptions& options();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cutaway
