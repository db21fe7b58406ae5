// cutaway/styles/blinn_phong.hpp — the Blinn-Phong shading style's options (src/styles/blinn_phong).
//
//   scene.style.name = "blinn-phong";
//   scene.style.edit<cutaway::BlinnPhongStyle>().ambient = 0.2f;
#pragma once

#include <glm/glm.hpp>

#include "cutaway/core/options.hpp"

namespace cutaway {

struct BlinnPhongStyle {
  static constexpr const char* kKey = "blinnPhong";  // under "style" in the scene file
  float ambient = 0.15f;
};
const OptionsSchema& blinnPhongSchema();

}  // namespace cutaway
