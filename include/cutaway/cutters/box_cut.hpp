// cutaway/cutters/box_cut.hpp — the box cut: Li et al.'s cutting convention that Konev18 §7
// uses to open its sewer pipes, a box described by a few half-spaces (Diepstraten03 rule 2).
// An oriented box removes what lies inside it from the objects it cuts; solid objects show
// their cut walls on the box's faces (rule 5), drawn on their back faces seen through the
// box. The objects of interest are never cut.
//
//   auto& box = scene.cutters.enable<cutaway::BoxCutOptions>();
//   box.center = {0, 1, 0};
//   box.size = {2, 2, 4};
//   box.rotation = {0, 30, 0};
//
// The C++ mirror of its GLSL (src/cutters/box_cut/box_cut.glsl) is boxCutFragment.
#pragma once

#include <optional>

#include <glm/glm.hpp>

#include "cutaway/core/options.hpp"
#include "cutaway/geometry/mesh.hpp"

namespace cutaway {

struct BoxCutOptions {
  static constexpr const char* kKey = "boxCut";  // under "cutters" in the scene file

  glm::vec3 center{0.0f};
  glm::vec3 size{1.0f};      // edge lengths along the box's axes, world units
  glm::vec3 rotation{0.0f};  // degrees about x, then y, then z (R = Rz·Ry·Rx, as transforms)
  std::optional<glm::vec3> cutSurfaceColor;  // default: the object's colour, darker
  bool outlines = true;                      // cut outlines (Burns08 §4.2)
};
const OptionsSchema& boxCutSchema();

// The box's unit axes (columns of the rotation).
glm::mat3 boxCutAxes(const BoxCutOptions& options);

// Whether any point of `box` (world space, axis-aligned) may lie inside the cut box: false
// only where an axis of either box separates them, by more than 1e-5 of their reach.
bool boxCutMeetsBox(const BoxCutOptions& options, const Bounds& box);

// What the box cut decides about a fragment at world point `x` of an object it cuts, seen
// along the ray from `rayOrigin` (Camera::rayOrigin(x)): removed inside the box; on a back
// face behind the box, the cut wall where the view ray left the box (its point and the
// face's normal, towards the viewer).
struct BoxCutFate {
  enum class Fate { Keep, Discard, CutSurface } fate = Fate::Keep;
  glm::vec3 position{0.0f}, normal{0.0f};
};
BoxCutFate boxCutFragment(const BoxCutOptions& options, const glm::vec3& x, bool frontFacing,
                          const glm::vec3& rayOrigin);

}  // namespace cutaway
