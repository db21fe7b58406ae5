// Rendering one frame of a scene in the tests' shared GL context, and its AOVs by name.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "cutaway/render/renderer.hpp"
#include "gl_test_context.hpp"

namespace cutaway::test {

inline std::vector<Aov> renderAovs(const Scene& scene) {
  Renderer renderer(scene, glContext().info());
  renderer.render();
  return renderer.readAovs();
}

inline const FloatImage& aov(const std::vector<Aov>& aovs, const std::string& name) {
  for (const auto& a : aovs)
    if (a.name == name) return a.image;
  throw std::runtime_error("no AOV " + name);
}

}  // namespace cutaway::test
