// The terrain opening's options as the scene file, the viewer and the CLI name them.
#include <nlohmann/json.hpp>

#include "core/json_reader.hpp"
#include "cutaway/cutters/terrain_opening.hpp"
#include "cutaway/io/gis_import.hpp"

namespace cutaway {

namespace {

using namespace json_reader;
using O = TerrainOpeningOptions;

// "network": GIS line layers in the scene's frame (x = E − E0, z = −(N − N0)); "lines":
// inline polylines of [x, z] nodes.
void readNetwork(const Context& ctx, ObjectReader& r, O& o) {
  if (const json* v = r.take("network")) {
    if (!v->is_array()) ctx.fail(r.at("network"), "expected an array of layers");
    for (std::size_t i = 0; i < v->size(); ++i) {
      const std::string p = r.at("network") + "/" + std::to_string(i);
      ObjectReader nr(ctx, (*v)[i], p);
      const std::filesystem::path file = ctx.baseDir / string(ctx, nr.require("file"), nr.at("file"));
      GisImportOptions gis = gisImportOptions(ctx.geo);
      if (const json* x = nr.take("layer")) gis.layer = string(ctx, *x, nr.at("layer"));
      nr.finish();
      try {
        for (const auto& line : importGisLines(file, gis).polylines) {
          std::vector<glm::vec2> xz;
          for (const auto& q : line.points) xz.emplace_back(q.x, -q.y);
          o.lines.push_back(std::move(xz));
        }
      } catch (const Error& e) {
        ctx.fail(p, e.what());
      }
    }
  }
  if (const json* v = r.take("lines")) {
    if (!v->is_array()) ctx.fail(r.at("lines"), "expected an array of polylines");
    for (std::size_t i = 0; i < v->size(); ++i) {
      const std::string p = r.at("lines") + "/" + std::to_string(i);
      const json& line = (*v)[i];
      if (!line.is_array() || line.size() < 2) ctx.fail(p, "a polyline needs at least two [x, z] nodes");
      std::vector<glm::vec2> xz;
      for (std::size_t k = 0; k < line.size(); ++k) {
        const std::string q = p + "/" + std::to_string(k);
        if (!line[k].is_array() || line[k].size() != 2) ctx.fail(q, "expected [x, z]");
        const glm::vec2 node(float(number(ctx, line[k][0], q + "/0", -1e9, 1e9)),
                             float(number(ctx, line[k][1], q + "/1", -1e9, 1e9)));
        if (xz.empty() || node != xz.back()) xz.push_back(node);  // as a GIS layer's repeats
      }
      if (xz.size() < 2) ctx.fail(p, "a polyline needs at least two distinct [x, z] nodes");
      o.lines.push_back(std::move(xz));
    }
  }
}

}  // namespace

const OptionsSchema& terrainOpeningSchema() {
  static const OptionsSchema schema =
      OptionsBuilder<O>()
          .readHook(readNetwork)
          .text("terrain", &O::terrain,
                {.doc = "Regular expression: the terrain objects' names (whole match).",
                 .required = true})
          .text("buildings", &O::buildings,
                {.doc = "Regular expression: the building objects' names; empty: none."})
          .value("cutBuildings", &O::cutBuildings,
                 {.label = "cut buildings",
                  .doc = "Open the buildings by the same rule, or leave them whole."})
          .number("resolution", &O::resolution, 16, 8192,
                  {.label = "texture size T",
                   .doc = "Texels per side of the distance texture.",
                   .sliderMax = 4096})
          .choice("metric", &O::metric,
                  {{"l1", O::Metric::L1}, {"euclidean", O::Metric::Euclidean}},
                  {.doc = "L1 (the paper's default; diamond-shaped ends) or Euclidean distance."})
          .value("rough", &O::rough,
                 {.doc = "The paper's texture as built: the network drawn into texels, distances "
                         "between texel centres, the nearest texel looked up (zig-zag edges a "
                         "texel wide, its \"rough cutaway\"); off: distances to the lines "
                         "themselves, interpolated (smooth at any zoom)."})
          .number("w", &O::w, 0, 1e6,
                  {.label = "width w",
                   .doc = "Eq. 1's width of the opening.",
                   .live = true,
                   .sliderMax = 0.1})
          .number("s", &O::s, 1e-6, 1e6,
                  {.label = "size s",
                   .doc = "Eq. 1's size: the opening closes at camera distance s².",
                   .live = true,
                   .sliderMax = 100})
          .number("wall", &O::wall, 0, 1000,
                  {.label = "wall depth",
                   .doc = "The artificial thickness as a trench wall this many half-widths of the "
                          "opening deep (beyond the paper); 0: eq. 3's one-texel peek.",
                   .live = true,
                   .sliderMax = 4})
          .value("cameraDistance", &O::cameraDistance,
                 {.label = "camera distance",
                  .doc = "Shrink the opening with the camera distance (eq. 1); off: t = w·s.",
                  .live = true})
          .optional("thicknessColor", &O::thicknessColor, OptionSpec::Type::Color, 0, 1, kSoilColor,
                    {.label = "thickness colour",
                     .doc = "Colour of the artificial thickness (eq. 3).",
                     .live = true})
          .check([](const Context& ctx, ObjectReader& r, O& o) {
            (void)regex(ctx, o.terrain, r.at("terrain"));
            if (!o.buildings.empty()) (void)regex(ctx, o.buildings, r.at("buildings"));
          })
          .build();
  return schema;
}

}  // namespace cutaway
