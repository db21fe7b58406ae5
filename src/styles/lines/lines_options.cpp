// The feature lines' options as the scene file, the viewer and the CLI name them.
#include "cutaway/styles/lines.hpp"

namespace cutaway {

const OptionsSchema& lineStyleSchema() {
  using O = LineStyle;
  static const OptionsSchema schema =
      OptionsBuilder<O>()
          .value("silhouettes", &O::silhouettes,
                 {.doc = "Object-id changes and depth discontinuities.", .live = true})
          .value("creases", &O::creases, {.doc = "Normal discontinuities within an object.", .live = true})
          .number("creaseAngle", &O::creaseAngle, 0, 180,
                  {.label = "crease angle (°)", .doc = "Normals meeting at more than this make a crease.",
                   .live = true})
          .number("depthThreshold", &O::depthThreshold, 0, 1,
                  {.label = "depth threshold",
                   .doc = "Relative view-depth jump that counts as a silhouette.",
                   .live = true,
                   .sliderMax = 0.1})
          .number("width", &O::width, 0.5, 8,
                  {.label = "line width (px)", .doc = "Drawn rounded to whole pixels.", .live = true})
          .color("color", &O::color, {.label = "line colour", .doc = "Colour of the lines.", .live = true})
          .build();
  return schema;
}

}  // namespace cutaway
