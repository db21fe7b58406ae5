// The adaptive cutter's panel (Burns & Finkelstein 2008; Burns 2011 ch. 4–6): its options
// from parameters/adaptive.cpp, and where its jump flooding runs.
#include <imgui.h>

#include "panels.hpp"

namespace cutaway::view {

void adaptivePanel(ViewerState& state) {
  parameterTable(adaptiveParameters(), state);
  if (!state.computePath.empty())
    ImGui::TextDisabled("jump flooding runs on the %s", state.computePath.c_str());
  ImGui::TextDisabled("local angles: select objects of interest (Scene panel)");
}

}  // namespace cutaway::view
