// cutaway/geometry/convex_hull.hpp — 3-D convex hulls (quickhull, through Qhull's
// reentrant C API `qhull_r`).
//
// Used for invisible proxy objects (Burns11 §4.2.2: the hull of named objects stands in as
// region of interest) and for Diepstraten03's breakaway hulls and main-axis computation.
//
//   cutaway::Mesh hull = cutaway::convexHull(points);   // outward-facing, watertight
#pragma once

#include <vector>

#include "cutaway/geometry/mesh.hpp"

namespace cutaway {

// Throws cutaway::Error when the points span no volume (fewer than 4, coplanar, collinear).
Mesh convexHull(const std::vector<glm::vec3>& points);

}  // namespace cutaway
