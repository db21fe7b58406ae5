// The AOV inspector: any of the frame's intermediate buffers (Renderer AOVs: depth, view
// depth, normals, positions, object ids, cut mask, line coverages, and the adaptive cutter's
// seed and cutaway depths) shown in the view through a colour map, with its meaning, its
// value range and the value under the cursor.
#include <imgui.h>

#include <cmath>

#include "panels.hpp"

namespace cutaway::view {

void aovPanel(ViewerState& state) {
  const char* shown = state.aov.empty() ? "final colour" : state.aov.c_str();
  if (ImGui::BeginCombo("buffer", shown)) {
    if (ImGui::Selectable("final colour", state.aov.empty()))
      state.aov.clear(), state.aovChanged = true;
    for (const auto& name : state.aovNames)
      if (ImGui::Selectable(name.c_str(), state.aov == name))
        state.aov = name, state.aovChanged = true;
    ImGui::EndCombo();
  }
  if (state.aov.empty()) return;
  int map = int(state.colormap);
  std::vector<const char*> names;
  for (const auto& n : colormapNames()) names.push_back(n.c_str());
  if (ImGui::Combo("colour map", &map, names.data(), int(names.size())))
    state.colormap = Colormap(map), state.aovChanged = true;
  if (ImGui::Checkbox("auto range", &state.autoRange)) state.aovChanged = true;
  ImGui::BeginDisabled(state.autoRange);
  // ValueRange is two adjacent floats, min then max, as DragFloat2 edits them.
  if (ImGui::DragFloat2("range", &state.range.min, 0.001f * (std::abs(state.range.max) + 1e-3f), 0,
                        0, "%.5g"))
    state.aovChanged = true;
  ImGui::EndDisabled();
  if (state.shownColormap == Colormap::Turbo || state.shownColormap == Colormap::Gray) {
    // The scale: the range's minimum on the left, its maximum on the right.
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const ImVec2 at = ImGui::GetCursorScreenPos();
    const float width = ImGui::CalcItemWidth(), height = ImGui::GetFrameHeight() * 0.5f;
    constexpr int kSteps = 64;
    for (int i = 0; i < kSteps; ++i) {
      const float t = (float(i) + 0.5f) / kSteps;
      const glm::vec3 c = state.shownColormap == Colormap::Turbo ? turbo(t) : glm::vec3(t);
      draw->AddRectFilled(ImVec2(at.x + width * float(i) / kSteps, at.y),
                          ImVec2(at.x + width * float(i + 1) / kSteps + 1.0f, at.y + height),
                          ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, 1.0f)));
    }
    ImGui::Dummy(ImVec2(width, height));
  }
  const auto meaning = state.aovMeanings.find(state.aov);
  if (meaning != state.aovMeanings.end()) ImGui::TextWrapped("%s", meaning->second.c_str());
  ImGui::Separator();
  ImGui::TextWrapped("%s", state.cursorValue.empty() ? "(move the cursor over the view)"
                                                     : state.cursorValue.c_str());
}

}  // namespace cutaway::view
