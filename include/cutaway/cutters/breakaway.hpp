// cutaway/cutters/breakaway.hpp — breakaway illustrations (Diepstraten, Weiskopf, Ertl 2003,
// §5): the convex hull of the interior objects (one per cluster: objects of one group), grown
// by an offset, is a virtual clipping object. Its foremost surface is rendered into a clip
// depth (two passes: greater-than, then less-than) and exterior fragments in front of it are
// removed, so exactly one hole opens where the interior objects would be hidden. Back faces
// are clipped by a slightly smaller hull, so the cut exterior shows a wall of finite
// thickness.
//
//   scene.cutters.enable<cutaway::BreakawayOptions>().offset = 5.0f;
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cutaway/core/options.hpp"
#include "cutaway/geometry/mesh.hpp"

namespace cutaway {

struct BreakawayOptions {
  static constexpr const char* kKey = "breakaway";
  std::optional<float> offset;         // world units the hulls grow by; default: 5% of the
                                       // interior objects' bounding radius
  std::optional<float> wallThickness;  // the back-face hull is smaller by this; default:
                                       // half the offset; at most the offset
  std::optional<glm::vec3> wallColor;  // default: kDefaultWallColor (cutout.hpp)
  std::optional<glm::vec3> insideColor;
};

const OptionsSchema& breakawaySchema();

// The convex hull of `points` grown by `offset`: the hull of the points moved by `offset`
// along 42 directions (an icosahedron's vertices and edge midpoints), a convex polyhedron
// inside the exact offset body that contains everything within 0.9·offset of the points.
// Points in one plane or on one line grow into a solid too; with offset 0 they throw
// cutaway::Error (no volume).
Mesh inflatedHull(const std::vector<glm::vec3>& points, float offset);

// The breakaway's clusters of interior objects: one per group ("" holds the ungrouped ones),
// each with its outer hull (grown by the offset) and inner hull (grown by offset − wall
// thickness), in world space at the objects' rest pose.
struct BreakawayCluster {
  std::string group;
  std::vector<std::size_t> objects;  // indices into scene.objects
  Mesh outerHull, innerHull;
};
// The offset and wall thickness with defaults resolved for `scene`.
struct BreakawayExtent {
  float offset, wallThickness;
};
BreakawayExtent breakawayExtent(const struct Scene& scene, const BreakawayOptions& options);
// The clusters with their hulls around the objects' pose at `time`.
std::vector<BreakawayCluster> breakawayClusters(const struct Scene& scene,
                                                const BreakawayOptions& options, float time = 0.0f);

}  // namespace cutaway
