// The box cut's options as the scene file, the viewer and the CLI name them.
#include "cutaway/cutters/box_cut.hpp"

namespace cutaway {

const OptionsSchema& boxCutSchema() {
  using O = BoxCutOptions;
  using Type = OptionSpec::Type;
  static const OptionsSchema schema =
      OptionsBuilder<O>()
          .vec3("center", &O::center, -1e30, 1e30,
                {.doc = "The box's centre, world units.", .live = true})
          .vec3("size", &O::size, 1e-6, 1e30,
                {.doc = "Its edge lengths along its own axes, world units.", .live = true})
          .vec3("rotate", &O::rotation, -360, 360,
                {.doc = "Its orientation: degrees about x, then y, then z (as an object's "
                        "transform).",
                 .live = true})
          .optional("cutSurfaceColor", &O::cutSurfaceColor, Type::Color, 0, 1, glm::vec3(0.8f),
                    {.label = "cut surface colour",
                     .doc = "Colour of the cut walls of solid objects; unset: the object's "
                            "colour, darker.",
                     .live = true})
          .value("outlines", &O::outlines,
                 {.label = "cut outlines", .doc = "Outline the cut walls (Burns08 §4.2)."})
          .build();
  return schema;
}

}  // namespace cutaway
