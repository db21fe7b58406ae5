// The camera panel: projection, field of view or height, fly mode, framing, the camera path
// recorded for `cutaway render --frames`, and the scene time.
#include <imgui.h>

#include <algorithm>

#include "../camera_controller.hpp"
#include "cutaway/core/error.hpp"
#include "panels.hpp"

namespace cutaway::view {

void cameraPanel(ViewerState& state) {
  Camera& c = state.scene.camera;
  int projection = c.projection == Projection::Orthographic ? 1 : 0;
  bool switched = ImGui::RadioButton("perspective", &projection, 0);
  ImGui::SameLine();
  switched |= ImGui::RadioButton("orthographic (P)", &projection, 1);
  if (switched) {
    c.setProjection(projection ? Projection::Orthographic : Projection::Perspective);
    state.viewChanged = true;
  }
  if (c.projection == Projection::Perspective)
    state.viewChanged |= ImGui::SliderFloat("fov (°)", &c.fovY, 5.0f, 120.0f, "%.1f");
  else
    state.viewChanged |=
        ImGui::DragFloat("height", &c.height, c.height * 0.01f, 1e-6f, 1e9f, "%.4g");
  state.viewChanged |= ImGui::DragFloat3("eye", &c.eye[0], 0.01f * c.viewHeightAtTarget());
  state.viewChanged |= ImGui::DragFloat3("target", &c.target[0], 0.01f * c.viewHeightAtTarget());
  ImGui::Checkbox("fly mode (Tab): WASD, Q/E", &state.flyMode);
  if (ImGui::Button(state.selection.empty() ? "Frame scene (F)" : "Frame selection (F)"))
    state.frameRequested = true;

  ImGui::Separator();
  ImGui::TextDisabled("camera path");
  float& keyTime = state.nextKeyTime;
  // The next key must come later than the last one: suggest a second after it.
  if (!state.cameraPath.empty() && keyTime <= state.cameraPath.back().time)
    keyTime = state.cameraPath.back().time + 1.0f;
  ImGui::SetNextItemWidth(80);
  ImGui::DragFloat("s", &keyTime, 0.1f, 0.0f, 1e6f, "%.2f");
  ImGui::SameLine();
  if (ImGui::Button("Add key")) {
    try {
      addCameraKey(state, keyTime);
      keyTime += 1.0f;
      state.status = "camera key at " + std::to_string(state.cameraPath.back().time) + " s";
    } catch (const Error& e) {
      state.status = e.what();
    }
  }
  ImGui::SameLine();
  ImGui::BeginDisabled(state.cameraPath.empty());
  if (ImGui::Button("Clear")) state.cameraPath.clear(), state.previewPath = false, keyTime = 0;
  ImGui::EndDisabled();
  ImGui::Text("%zu keys%s", state.cameraPath.size(),
              state.cameraPath.empty() ? "" : " (saved as camera.path)");
  if (ImGui::Checkbox("preview path", &state.previewPath)) state.viewChanged = true;

  float duration = state.scene.duration();
  if (!state.cameraPath.empty()) duration = std::max(duration, state.cameraPath.back().time);
  if (duration > 0) {
    ImGui::Separator();
    ImGui::TextDisabled("time");
    state.viewChanged |= ImGui::SliderFloat("t (s)", &state.time, 0.0f, duration, "%.2f");
    ImGui::SameLine();
    if (ImGui::Button(state.playing ? "Pause" : "Play")) state.playing = !state.playing;
  }
}

}  // namespace cutaway::view
