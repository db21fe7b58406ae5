// Polygon offsets (glPolygonOffset units: steps of depth resolution) by which passes draw
// surfaces nearer than they lie, to win exact ties, and what occlusion culling's boxes allow
// for them.
#pragma once

namespace cutaway {

// A cap inside another solid's box, per box, at most kMostNestedCaps boxes deep, against the
// outer solid's cap in its plane (cutters/clip_surfaces/clip_surfaces.cpp; cap.frag applies it
// to the depth it writes, as a polygon offset would).
constexpr float kNestedCapUnits = 4.0f;
constexpr int kMostNestedCaps = 4;
// The most any surface is drawn nearer.
constexpr float kMostUnitsNearer = kNestedCapUnits * float(kMostNestedCaps);

}  // namespace cutaway
