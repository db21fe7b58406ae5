// Saving: the scene with the viewer's parameters (cutaway/scene/scene_writer.hpp), and the rendered image
// as `cutaway render` writes it.
#include <imgui.h>
#include <imgui_stdlib.h>

#include "panels.hpp"

namespace cutaway::view {

void filePanel(ViewerState& state) {
  if (ImGui::Button("Reload scene")) state.reloadRequested = true;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Reads the scene file again, keeping this view (F5); a file that fails to load "
        "leaves the last good scene on screen");
  ImGui::InputText("##scene", &state.savePath);
  ImGui::SameLine();
  if (ImGui::Button("Save scene")) state.saveRequested = true;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Writes the scene file with this camera, the roles, importance, cutter and "
        "style options (Ctrl+S)");
  ImGui::InputText("##png", &state.screenshotPath);
  ImGui::SameLine();
  if (ImGui::Button("Screenshot")) state.screenshotRequested = true;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("The rendered image, without the panels, as PNG");
  if (!state.status.empty()) ImGui::TextWrapped("%s", state.status.c_str());
}

}  // namespace cutaway::view
