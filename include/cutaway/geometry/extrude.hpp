// cutaway/geometry/extrude.hpp — building blocks from footprints: a polygon with holes in the
// horizontal plane extruded to a closed prism (Konev18 §5's city: "building footprints
// extruded to blocks" over the terrain, so that the cutaway has solid walls to cut).
//
// The footprint lies in the scene's x/z plane (y up; GeoFrame::toScene maps GIS points there).
// Rings may be given in either orientation, with or without repeated or collinear nodes;
// they must be simple and the holes must lie inside the outer ring without touching each
// other. Roof and floor are triangulated by ear clipping (holes joined to the outer ring by
// bridges first), the walls are quads with flat normals; the result is watertight and its
// triangles face outwards.
//
//   cutaway::Footprint f{.outer = {{0, 0}, {10, 0}, {10, 8}, {0, 8}},
//                        .holes = {{{3, 3}, {5, 3}, {5, 5}, {3, 5}}}};
//   cutaway::Mesh block = cutaway::extrudeFootprint(f, 0.0f, 12.0f);   // 12 m high
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "cutaway/geometry/mesh.hpp"

namespace cutaway {

struct Footprint {
  std::vector<glm::vec2> outer;               // (x, z) of the scene
  std::vector<std::vector<glm::vec2>> holes;  // (x, z), inside `outer`
};

// Twice the signed area of a ring in the (x, z) plane (positive when counter-clockwise with x
// to the right and z up), by the shoelace formula in double.
double twiceSignedArea(const std::vector<glm::vec2>& ring);

// Triangles (index triples into the concatenation outer, holes[0], holes[1], …) covering the
// footprint, each counter-clockwise in (x, z). Repeated and collinear nodes keep their index
// but may be left out of the triangles. Empty when the outer ring has no area.
std::vector<glm::uvec3> triangulateFootprint(const Footprint& footprint);

// The prism between y = base and y = top (top > base): roof and floor from
// `triangulateFootprint`, one quad per remaining ring edge. Repeated and collinear nodes are
// removed first so that the roof's and the walls' edges meet exactly; a hole with a node
// outside the outer ring (an invalid polygon) is left out. Empty when nothing with area is
// left.
Mesh extrudeFootprint(const Footprint& footprint, float base, float top);

}  // namespace cutaway
