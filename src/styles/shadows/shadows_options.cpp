// The shadows' options as the scene file, the viewer and the CLI name them.
#include "cutaway/styles/shadows.hpp"

namespace cutaway {

const OptionsSchema& shadowStyleSchema() {
  using O = ShadowStyle;
  static const OptionsSchema schema =
      OptionsBuilder<O>()
          .number("size", &O::size, 64, 8192,
                  {.doc = "Texels per side of the shadow map (a power of two).", .sliderMax = 4096,
                   .powerOfTwo = true})
          .number("bias", &O::bias, 0, 0.1,
                  {.doc = "Constant bias towards the light, as a fraction of the scene's radius.",
                   .live = true})
          .number("slopeBias", &O::slopeBias, 0, 100,
                  {.label = "slope bias", .doc = "Polygon offset: the bias times the caster's depth slope.",
                   .live = true})
          .number("pcfRadius", &O::pcfRadius, 0, 4,
                  {.label = "PCF radius", .doc = "(2r + 1)² filtered comparisons per lookup.", .live = true})
          .build();
  return schema;
}

}  // namespace cutaway
