// The emphasis options as the scene file, the viewer and the CLI name them.
#include "cutaway/styles/emphasis.hpp"

namespace cutaway {

const OptionsSchema& emphasisStyleSchema() {
  using O = EmphasisStyle;
  static const OptionsSchema schema =
      OptionsBuilder<O>()
          .number("color", &O::color, 0, 1,
                  {.label = "colour E_c",
                   .doc = "Desaturation of less important objects (Burns11 eqs. 3.1–3.2): 1 greys "
                          "objects of importance 0 fully, 0 changes nothing.",
                   .live = true})
          .number("shading", &O::shading, 0, 1,
                  {.label = "shading E_s",
                   .doc = "Shading suppression of less important objects (eqs. 3.3–3.4): 1 "
                          "leaves objects of importance 0 in their flat colour, 0 changes nothing.",
                   .live = true})
          .number("linesOnlyBelow", &O::linesOnlyBelow, 0, 1,
                  {.label = "lines only below",
                   .doc = "Objects of lower importance are drawn as a line drawing: their feature "
                          "lines over the paper colour (§3.3.1.3); 0: none.",
                   .live = true})
          .color("paper", &O::paper,
                 {.doc = "The fill of objects drawn as lines only.", .live = true})
          .build();
  return schema;
}

}  // namespace cutaway
