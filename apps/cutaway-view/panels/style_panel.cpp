// The style's panel: shading (the names of cutaway::styleNames()), lines, Gooch and
// Blinn-Phong parameters, from parameters/style.cpp.
#include <imgui.h>

#include "panels.hpp"

namespace cutaway::view {

void stylePanel(ViewerState& state) {
  parameterTable(styleParameters(), state);
}

}  // namespace cutaway::view
