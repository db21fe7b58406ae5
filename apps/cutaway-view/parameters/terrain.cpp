// The terrain opening's options (Konev18 §4; cutaway::TerrainOpeningOptions) as viewer
// parameters. The network and the terrain objects come from the scene file.
#include "binding.hpp"

namespace cutaway::view {

namespace {

std::vector<Parameter> makeTerrainParameters() {
  using Type = Parameter::Type;
  using O = TerrainOpeningOptions;
  // The network and terrain come from the scene file: a scene without them that sets one of
  // these gets an opening with no network, which opens nothing.
  const auto b = sceneOptions<O, &Scene::terrainOpening>("terrain");
  std::vector<Parameter> out;
  Parameter w = b.member("w", "width w", Type::Float, &O::w, "Eq. 1's width of the opening.");
  w.min = 0, w.max = 1e6, w.sliderMax = 0.1;
  out.push_back(w);
  Parameter s = b.member("s", "size s", Type::Float, &O::s,
                         "Eq. 1's size: the opening closes at camera distance s².");
  s.min = 1e-6, s.max = 1e6, s.sliderMax = 100;
  out.push_back(s);
  out.push_back(b.member("cameraDistance", "camera distance", Type::Bool, &O::cameraDistance,
                         "Shrink the opening with the camera distance (eq. 1); off: t = w·s."));
  out.push_back(b.choice("metric", "metric", &O::metric,
                         {{"l1", O::Metric::L1}, {"euclidean", O::Metric::Euclidean}},
                         "L1 (zig-zag edges, the paper's default) or exact Euclidean distance."));
  Parameter resolution = b.member("resolution", "texture size T", Type::Int, &O::resolution,
                                  "Texels per side of the distance texture.");
  resolution.min = 16, resolution.max = 8192, resolution.sliderMax = 4096;
  out.push_back(resolution);
  out.push_back(b.member("cutBuildings", "cut buildings", Type::Bool, &O::cutBuildings,
                         "Open the buildings by the same rule, or leave them whole."));
  out.push_back(b.color("thicknessColor", "thickness colour", &O::thicknessColor, kSoilColor,
                        "Colour of the artificial thickness (eq. 3)."));
  return out;
}

}  // namespace

const std::vector<Parameter>& terrainParameters() {
  static const std::vector<Parameter> parameters = makeTerrainParameters();
  return parameters;
}

}  // namespace cutaway::view
