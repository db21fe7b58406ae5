// Per-pass GPU and CPU times of the last rendered frame (Renderer::timings(), GL_TIME_ELAPSED
// queries), the frame rate of the window, and the reduced size of a frame drawn while the
// view moves.
#include <imgui.h>

#include "panels.hpp"

namespace cutaway::view {

void timingsPanel(const ViewerState& state, float framesPerSecond) {
  ImGui::Text("%.1f fps (UI)   last render %.1f ms", framesPerSecond, state.renderMs);
  ImGui::TextDisabled("%s", state.rendererName.c_str());
  if (state.shownDivisor > 1)
    ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "moving: %d×%d (1/%d size), full %.0f ms",
                       state.movingWidth, state.movingHeight, state.shownDivisor, state.fullMs);
  if (!ImGui::BeginTable("passes", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit))
    return;
  ImGui::TableSetupColumn("pass", ImGuiTableColumnFlags_WidthStretch);
  ImGui::TableSetupColumn("GPU ms");
  ImGui::TableSetupColumn("CPU ms");
  ImGui::TableHeadersRow();
  double gpu = 0, cpu = 0;
  for (const auto& t : state.timings) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(t.name.c_str());
    ImGui::TableNextColumn();
    ImGui::Text("%7.2f", t.gpuMs);
    ImGui::TableNextColumn();
    ImGui::Text("%7.2f", t.cpuMs);
    gpu += t.gpuMs, cpu += t.cpuMs;
  }
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  ImGui::TextDisabled("total");
  ImGui::TableNextColumn();
  ImGui::Text("%7.2f", gpu);
  ImGui::TableNextColumn();
  ImGui::Text("%7.2f", cpu);
  ImGui::EndTable();
}

}  // namespace cutaway::view
