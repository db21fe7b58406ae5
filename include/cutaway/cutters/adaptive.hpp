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

// Burns11 §4.1.3, §5.2.3: the contextual cutaway structure. Besides C₁ (the adaptive cutter's
// surface at θ₁ = angle, the transition–overlay boundary) a second surface C₂ at θ₂ bounds the
// transition region towards the base, and the overlay region reaches d in front of C₁. Each
// fragment gets the occlusion Ω (eq. 5.6) and, from its object's importance, the occlusion
// reduction R (eqs. 7.1–7.3); on polygons R is applied fully or not at all (§5.2.4): a
// fragment is removed where R ≥ ½, so each object is trimmed at a cutaway surface between C₂
// and C₁ − d that its importance chooses.
struct ContextualCutawayOptions {
  float transitionAngle = 60.0f;  // θ₂ in degrees, ≥ θ₁; = θ₁: no transition region
  std::optional<float> overlay;   // d, world units along the view ray; 0: none; unset: 5% of the scene radius
  // How R follows from Ω: eqs. 7.1–7.3 with each object's importance, R = Ω (§7.2: a scene
  // that does not rank its objects), or auto: the former when the cut objects' importances
  // differ (a cut volume's: its transfer function's), else the latter.
  enum class Reduction { Auto, Importance, Occlusion } reduction = Reduction::Auto;
  // How R is applied (ch. 2, §5.2.4): cut, fully or not at all (R ≥ ½ removed, with cut
  // surfaces; Burns08's binary cutaway is R ∈ {0, 1}); translucency, opacity α = 1 − R
  // (eq. 2.1); edge highlights, α = 1 − R (1 − (1 − n̂·v̂)^k) (eq. 2.2); lines, the surface
  // suppressed where R > 0 and its feature lines of opacity 1 − R (§2.3, §7.2). The last three
  // draw the partly reduced material as translucent layers peeled in depth order.
  enum class Application { Cut, Translucency, EdgeHighlights, Lines } apply = Application::Cut;
  float edgeExponent = 2.0f;  // k of eq. 2.2
  int layers = 8;             // the most translucent layers peeled per pixel
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
  enum class CutSurfaces { All, Unmarked, Watertight, None } cutSurfaces = CutSurfaces::All;
  std::optional<glm::vec3> cutSurfaceColor;  // default: the object's colour, slightly darker
  bool outlines = true;                      // cut outlines (Burns08 §4.2)
  glm::vec3 outlineColor{0.0f};
  std::optional<GhostLineOptions> ghostLines;  // Burns08 §4.3 (opt-in: a style choice)
  std::optional<ContextualCutawayOptions> contextual;  // Burns11 §4.1.3 (off: the simple structure)
};
// Its options' schema: the scene file's keys, the viewer's and the CLI's.
const OptionsSchema& adaptiveCutawaySchema();

// The ramp of Burns11 eq. 5.5; where a = b it is the step x > a (so that eq. 7.3 gives R = 0
// for I = 1 and R = 1 wherever Ω > 0 for I = 0, as §7.1.2 says).
float ramp(float a, float b, float x);

// Ω at the transition–overlay boundary (§4.1.3.3): ½ with both regions, 0 without a
// transition region (θ₂ = θ₁), 1 without an overlay (d = 0); with neither, 0 (the simple
// structure: Ω is eq. 5.3's step at C₁).
float transitionOverlayOcclusion(bool transition, bool overlay);

// The contextual structure along one view ray, as distances in front of the eye (view-space
// −z): z₁ = C₁, z₂ = C₂ (z₂ ≥ z₁), overlay thickness d ≥ 0, and t as above.
struct ContextualRay {
  float z1, z2, d, t;
};
// Ω of a fragment at distance z (§4.1.3.3; eq. 5.6 when t = ½): 0 behind C₂, t at C₁, 1 at
// C₁ − d and nearer. Eq. 5.6 measures p_z towards the viewer; here z grows away from it, so
// ramp_[C₂..C₁] p_z is ramp_[−z₂..−z₁](−z).
float contextualOcclusion(const ContextualRay& ray, float z);
// The distance where Ω reaches `omega` in (0, 1]: the cutaway surface an object with that
// threshold is trimmed at.
float occlusionDistance(const ContextualRay& ray, float omega);
// Burns11 eqs. 7.1–7.3: R = ramp_[τ₀..τ₁] Ω with τ₀ = max(2I − 1, 0), τ₁ = I.
float occlusionReduction(float omega, float importance);
// The Ω at which eq. 7.3 reaches R = ½ (the trimming of §5.2.4); above 1: never trimmed.
float trimOcclusion(float importance);
// The opacities of material of opacity 1 reduced by R: its surface's (x) and its feature
// lines' (y). Translucency and edge highlights (eq. 2.1, or eq. 2.2 with exponent k at a
// surface point whose unit normal and view vector make n̂·v̂ = nDotV) give both the same; lines
// 0 and 1 − R where R > 0 (§2.3); Application::Cut 1 below R = ½ and 0 from it.
glm::vec2 reducedOpacity(ContextualCutawayOptions::Application apply, float reduction, float nDotV,
                         float k);

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
// rasteriser, where jump flooding in shaders is slower than the CPU kernel (1024² on llvmpipe:
// 987 ms in compute passes, 1518 ms in the earlier fragment passes, 31 ms on the CPU; `cutaway
// bench` measures both paths on every run).
bool cutawayOnCpu(const AdaptiveCutawayOptions& options, bool softwareRenderer);

// A cutaway depth image C (window depth, n × n over the viewport, rows bottom to top, read
// bilinearly with repeat as its texture is) as a pyramid of maxima, for the greatest C over a
// rectangle of the viewport.
class GreatestDepth {
 public:
  GreatestDepth() = default;
  GreatestDepth(std::vector<float> depth, int n);
  bool empty() const { return levels_.empty(); }
  // At least the greatest C the bilinear samples give in [lo, hi] (texture coordinates): the
  // greatest of a block of texels that holds their footprint.
  float over(glm::vec2 lo, glm::vec2 hi) const;

 private:
  std::vector<std::vector<float>> levels_;  // level k: the greatest of 2^k × 2^k texels
  std::vector<int> sizes_;
};

// Burns11 eq. 5.4 removes a fragment nearer than C at its pixel, and a back face behind C is a
// cut surface only where a front face was removed (an open mesh's marks, kinds/meshes). Whether
// C leaves a world box (holding every point a fragment may be shaded at: shadedBox) as it is:
// every corner in front of the near plane and its nearest window depth at or behind the
// greatest C over the viewport rectangle it covers.
bool cutawayKeepsBox(const struct Bounds& box, const glm::mat4& viewProjection,
                     const GreatestDepth& c);

// The camera quantities above for a resolved camera.
CutawayProjection cutawayProjection(const struct Camera& camera, float aspect);

// The jump-flooding input of an n×n cutaway buffer: seed window depths (0 = no seed) and
// local angles (radians), rows bottom to top, turned into per-seed cones by anchorCone().
fields::SeedImage makeSeedImage(const std::vector<float>& seedDepth,
                                const std::vector<float>& seedAngle, int n,
                                const AdaptiveCutawayOptions& options,
                                const CutawayProjection& camera);

}  // namespace cutaway
