// The breakaway cutter's options as the scene file, the viewer and the CLI name them.
#include "core/json_reader.hpp"
#include "cutaway/cutters/breakaway.hpp"
#include "cutaway/cutters/cutout.hpp"

namespace cutaway {

const OptionsSchema& breakawaySchema() {
  using O = BreakawayOptions;
  using Type = OptionSpec::Type;
  static const OptionsSchema schema =
      OptionsBuilder<O>()
          .optional("offset", &O::offset, Type::Float, 0, 1e30, 0.0f,
                    {.label = "hull offset",
                     .doc = "Scene units the interior objects' convex hulls grow by; unset: 5% "
                            "of their bounding radius."})
          .optional("wallThickness", &O::wallThickness, Type::Float, 0, 1e30, 0.0f,
                    {.label = "wall thickness",
                     .doc = "The back-face hull is smaller by this: the hole's wall (at most the "
                            "offset); unset: half the offset."})
          .optional("wallColor", &O::wallColor, Type::Color, 0, 1, kDefaultWallColor,
                    {.label = "wall colour", .doc = "Colour of the cut walls of solid exteriors.",
                     .live = true})
          .optional("insideColor", &O::insideColor, Type::Color, 0, 1, glm::vec3(0.4f),
                    {.label = "inside colour",
                     .doc = "Back faces of hollow exteriors; unset: the object's colour, darker.",
                     .live = true})
          .check([](const json_reader::Context& ctx, json_reader::ObjectReader& r, O& o) {
            if (o.offset && o.wallThickness && *o.wallThickness > *o.offset)
              ctx.fail(r.at("wallThickness"),
                       "the wall thickness must not exceed the offset (the back-face hull is the "
                       "outer hull shrunk by it)");
          })
          .build();
  return schema;
}

}  // namespace cutaway
