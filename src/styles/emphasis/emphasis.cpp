#include "styles/emphasis/emphasis.hpp"

#include "cutaway/scene/scene.hpp"

namespace cutaway {

void Emphasis::beginFrame() const {
  const EmphasisStyle& e = setup_.scene.style.emphasis;
  block_.update({glm::vec4(e.color, e.shading, e.linesOnlyBelow, 0.0f), glm::vec4(e.paper, 1.0f)});
}

}  // namespace cutaway
