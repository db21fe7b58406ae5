// cutaway/core/geo_frame.hpp — the scene's geographic frame: how projected GIS coordinates
// become scene coordinates (y up, north towards −z), with a double-precision offset.
//
//   cutaway::GeoFrame geo{.crs = "EPSG:27700", .offset = {265000, 145000, 0}};
//   glm::vec3 p = cutaway::GeoFrame::toScene(importedPoint);   // x = E − E0, y = H, z = −(N − N0)
#pragma once

#include <string>

#include <glm/glm.hpp>

namespace cutaway {

// The scene's geographic frame (Konev18 §5 input): every GIS layer and raster is reprojected
// to `crs` (when given), then a projected point (easting E, northing N, height H) becomes the
// scene point x = E − E0, y = H − H0, z = −(N − N0): y up, north towards −z. The offset is
// subtracted in double precision, so large projected coordinates (British National Grid, UTM)
// keep their centimetres as floats.
struct GeoFrame {
  std::string crs;         // anything OGR's SetFromUserInput takes; empty: keep each layer's
  glm::dvec3 offset{0.0};  // E0, N0, H0
  // A layer's point as imported with `importOptions` (x = E − E0, y = N − N0, z = H − H0).
  static glm::vec3 toScene(const glm::vec3& p) { return {p.x, p.z, -p.y}; }
  static glm::vec3 fromScene(const glm::vec3& p) { return {p.x, -p.z, p.y}; }
};

}  // namespace cutaway
