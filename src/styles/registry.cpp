#include "styles/registry.hpp"

#include "cutaway/scene/scene.hpp"

namespace cutaway {

// Defined in each style's folder.
StyleType goochStyleType();
StyleType blinnPhongStyleType();
StyleType toonStyleType();
StyleType hatchingStyleType();

const std::vector<StyleType>& styleTypes() {
  static const std::vector<StyleType> types{goochStyleType(), blinnPhongStyleType(),
                                            toonStyleType(), hatchingStyleType()};
  return types;
}

const std::vector<std::string>& styleNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const StyleType& t : styleTypes()) out.push_back(t.name);
    return out;
  }();
  return names;
}

const OptionsSchema& styleSchema() {
  static const OptionsSchema schema =
      OptionsBuilder<Style>()
          .choice("name", &Style::name, styleNames(),
                  {.label = "shading", .doc = "How kept fragments are shaded."})
          .group("lines", &Style::lines, lineStyleSchema(),
                 {.doc = "Image-space silhouette and crease lines (styles/lines): true, false or "
                         "their options."})
          .group("shadows", &Style::shadows, &ShadowStyle::enabled, shadowStyleSchema(),
                 {.doc = "Shadows from the key light for every style (styles/shadows)."})
          .group("emphasis", &Style::emphasis, emphasisStyleSchema(),
                 {.doc = "Emphasis by importance for every style (Burns11 §3.3.1, "
                         "styles/emphasis): desaturation, shading suppression, line drawing."})
          .build();
  return schema;
}

const StyleType* findStyle(const std::string& name) {
  for (const StyleType& t : styleTypes())
    if (t.name == name) return &t;
  return nullptr;
}

}  // namespace cutaway
