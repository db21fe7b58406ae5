// cutaway/cutters/adaptive.hpp — adaptive cutaways (Burns & Finkelstein 2008; Burns 2011
// ch. 4–6): a view-dependent cutaway surface grown from the rear hulls of the objects of
// interest by jump flooding, that clips secondary objects and shows their cut surfaces.
//
// The per-seed cone ("anchor") math lives here in C++ so that the CPU path and the tests use
// the same equations as src/cutters/adaptive/anchors.frag.
//
//   scene.cutters.enable<cutaway::AdaptiveCutawayOptions>() = {.angle = 30.0f, .bufferSize = 512};
//   cutaway::Renderer renderer(scene, context->info());   // adds the cutter's passes
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cutaway/core/options.hpp"
#include "cutaway/fields/cutaway_surface.hpp"

namespace cutaway {

// Burns08 §4.3: lines of the removed material, fading with the distance in front of the cut.
struct GhostLineOptions {
  float distance = 0.0f;  // world units in front of the cutaway surface; 0: 5% of the scene radius
  float opacity = 0.4f;
};

struct AdaptiveCutawayOptions {
  static constexpr const char* kKey = "adaptive";  // under "cutters" in the scene file

  float angle = 45.0f;   // θ in degrees, [0, 90] (per object: param "cutawayAngle")
  int bufferSize = 512;  // cutaway buffer is bufferSize² (Burns08 §6), independent of the screen
  bool perspectiveCompensation = true;      // Burns08 eq. 3 / Burns11 eq. 5.7
  bool edgeCompression = true;              // Burns11 eq. 5.8
  float edgeRegion = 0.1f;                  // r of eq. 5.8
  bool directionalConstraint = false;       // Burns11 eqs. 6.1–6.4
  glm::vec3 floorNormal{0.0f, 1.0f, 0.0f};  // world space
  fields::JumpFloodingVariant variant = fields::JumpFloodingVariant::jfaPlus1;
  enum class Compute { Auto, Gpu, Cpu } compute = Compute::Auto;
  enum class CutSurfaces { All, Watertight, None } cutSurfaces = CutSurfaces::All;
  std::optional<glm::vec3> cutSurfaceColor;  // default: the object's colour, slightly darker
  bool outlines = true;                      // cut outlines (Burns08 §4.2)
  glm::vec3 outlineColor{0.0f};
  std::optional<GhostLineOptions> ghostLines;  // Burns08 §4.3 (opt-in: a style choice)
};
// Its options' schema: the scene file's keys, the viewer's and the CLI's.
const OptionsSchema& adaptiveCutawaySchema();

// The camera quantities the cone math needs.
struct CutawayProjection {
  glm::mat4 projection;    // OpenGL projection matrix
  glm::mat3 viewRotation;  // world → view rotation (for the floor normal)
  bool orthographic = false;
};

// One seed pixel's cone: slopes mE (all directions) and mF (towards the floor), in NDC depth
// per view-plane unit, and the projected floor direction f (unit, or zero).
struct AnchorCone {
  float slopeE, slopeF;
  glm::vec2 floor;
};

// Cone of a seed at NDC position `ndc` (x, y in [−1,1], z NDC depth) with local angle θ
// (radians): edge compression (eq. 5.8), directional constraint (eqs. 6.1–6.2, floor
// direction of eq. 6.3) and slope (eq. 5.7 with compensation, else the screen-space slope
// of Burns08 §3).
AnchorCone anchorCone(const glm::vec3& ndc, float theta, const AdaptiveCutawayOptions& options,
                      const CutawayProjection& camera);

// Whether jump flooding runs on the CPU: when asked to, or, for Compute::Auto, on a software
// rasteriser, where a jump-flooding fragment shader is slower than the CPU kernel (the issue
// measured 355 ms for a naive shader vs 105 ms for naive C at 1024² on llvmpipe; `cutaway
// bench` measures both paths on every run).
bool cutawayOnCpu(const AdaptiveCutawayOptions& options, bool softwareRenderer);

// The camera quantities above for a resolved camera.
CutawayProjection cutawayProjection(const struct Camera& camera, float aspect);

// The jump-flooding input of an n×n cutaway buffer: seed window depths (0 = no seed) and
// local angles (radians), rows bottom to top, turned into per-seed cones by anchorCone().
fields::SeedImage makeSeedImage(const std::vector<float>& seedDepth,
                                const std::vector<float>& seedAngle, int n,
                                const AdaptiveCutawayOptions& options,
                                const CutawayProjection& camera);

}  // namespace cutaway
