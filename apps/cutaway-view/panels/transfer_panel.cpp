// The volumes' transfer-function editor: per volume (and gradient row of a two-dimensional
// function), the opacity curve over the value range with the colours beneath, its points
// dragged, added and removed with the mouse, and the chosen point's value, colour, opacity
// and importance. The next frame draws the edit (kinds/volumes re-uploads its table).
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "../transfer_edit.hpp"
#include "cutaway/cutters/cutout.hpp"
#include "cutaway/kinds/volume_ray_cast.hpp"
#include "panels.hpp"

namespace cutaway::view {

namespace {

constexpr float kCanvasHeight = 120.0f, kBarHeight = 12.0f, kPickRadius = 7.0f;

ImU32 rgb(glm::vec3 c, float alpha = 1.0f) {
  return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, alpha));
}

// The opacity curve over [lo, hi] in the canvas at `origin` of `size`; the point the mouse
// picks, moves, adds or removes. Whether the row changed.
bool curveCanvas(std::vector<TransferPoint>& row, bool labels, float lo, float hi,
                 ViewerState& state) {
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImVec2 size(std::max(ImGui::GetContentRegionAvail().x, 120.0f), kCanvasHeight);
  ImGui::InvisibleButton("curve", size,
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
  const float plot = size.y - kBarHeight;
  const auto x = [&](float value) { return origin.x + (value - lo) / (hi - lo) * size.x; };
  const auto y = [&](float a) { return origin.y + (1.0f - a) * plot; };
  const auto valueAt = [&](float px) { return lo + (px - origin.x) / size.x * (hi - lo); };
  const auto opacityAt = [&](float py) { return 1.0f - (py - origin.y) / plot; };
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + plot),
                      IM_COL32(30, 30, 34, 255));
  // The colours beneath, at full strength, and faded by opacity above them.
  const TransferFunction single{{{0.0f, row}}};
  for (float px = 0.0f; px < size.x; px += 2.0f) {
    const TransferPoint m = single.at(valueAt(origin.x + px));
    draw->AddRectFilled(ImVec2(origin.x + px, origin.y + plot),
                        ImVec2(origin.x + px + 2.0f, origin.y + size.y), rgb(m.color));
    draw->AddRectFilled(ImVec2(origin.x + px, y(m.opacity)),
                        ImVec2(origin.x + px + 2.0f, origin.y + plot), rgb(m.color, 0.35f));
  }
  // Opacity (solid) and importance (dim) through the points, held to the edges.
  for (const bool importance : {true, false}) {
    std::vector<ImVec2> line{
        {origin.x, y(importance ? row.front().importance : row.front().opacity)}};
    for (const TransferPoint& p : row)
      line.emplace_back(x(p.value), y(importance ? p.importance : p.opacity));
    line.emplace_back(origin.x + size.x, line.back().y);
    draw->AddPolyline(line.data(), int(line.size()),
                      importance ? IM_COL32(120, 200, 255, 140) : IM_COL32(255, 255, 255, 230),
                      ImDrawFlags_None, importance ? 1.0f : 2.0f);
  }
  for (std::size_t i = 0; i < row.size(); ++i)
    draw->AddCircleFilled(
        ImVec2(x(row[i].value), y(row[i].opacity)), int(i) == state.transferPoint ? 6.0f : 4.0f,
        int(i) == state.transferPoint ? IM_COL32(255, 200, 60, 255) : IM_COL32(255, 255, 255, 255));
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const auto picked = [&]() -> int {
    int best = -1;
    float nearest = kPickRadius;
    for (std::size_t i = 0; i < row.size(); ++i) {
      const float d = std::hypot(x(row[i].value) - mouse.x, y(row[i].opacity) - mouse.y);
      if (d < nearest) nearest = d, best = int(i);
    }
    return best;
  };
  bool changed = false;
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "value %.4g, opacity %.3f\ndrag a point; double-click: add one; "
        "right-click: remove one\nwhite: opacity, blue: importance",
        valueAt(mouse.x), std::clamp(opacityAt(mouse.y), 0.0f, 1.0f));
    if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left) && picked() < 0) {
      const int i = insertTransferPoint(row, valueAt(mouse.x), opacityAt(mouse.y), labels);
      if (i >= 0) state.transferPoint = i, changed = true;
    } else if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
      state.transferPoint = picked();
    } else if (ImGui::IsMouseClicked(ImGuiMouseButton_Right)) {
      const int i = picked();
      if (i >= 0 && removeTransferPoint(row, std::size_t(i)))
        state.transferPoint = -1, changed = true;
    }
  }
  if (ImGui::IsItemActive() && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 1.0f) &&
      state.transferPoint >= 0 && state.transferPoint < int(row.size())) {
    moveTransferPoint(row, std::size_t(state.transferPoint), valueAt(mouse.x), opacityAt(mouse.y),
                      labels);
    changed = true;
  }
  return changed;
}

}  // namespace

void transferPanel(ViewerState& state) {
  Scene& scene = state.scene;
  if (scene.volumes.empty()) return;
  ImGui::Separator();
  ImGui::TextUnformatted("transfer function");
  state.transferVolume = std::min(state.transferVolume, scene.volumes.size() - 1);
  if (scene.volumes.size() > 1 &&
      ImGui::BeginCombo("volume", scene.volumes[state.transferVolume].name.c_str())) {
    for (std::size_t i = 0; i < scene.volumes.size(); ++i)
      if (ImGui::Selectable(scene.volumes[i].name.c_str(), i == state.transferVolume))
        state.transferVolume = i, state.transferRow = 0, state.transferPoint = -1;
    ImGui::EndCombo();
  }
  SceneVolume& v = scene.volumes[state.transferVolume];
  TransferFunction& tf = v.transfer;
  state.transferRow = std::min(state.transferRow, tf.rows.size() - 1);
  bool changed = false;
  // Gradient rows (a two-dimensional function, not for labels): which one, where it lies.
  if (!v.labels) {
    if (tf.twoDimensional()) {
      int r = int(state.transferRow);
      if (ImGui::SliderInt("gradient row", &r, 0, int(tf.rows.size()) - 1))
        state.transferRow = std::size_t(r), state.transferPoint = -1;
      float g = tf.rows[state.transferRow].gradient;
      if (ImGui::DragFloat("row gradient", &g, std::max(g, 1.0f) * 0.01f, 0.0f, 1e9f, "%.4g")) {
        setTransferRowGradient(tf, state.transferRow, g);
        changed = true;
      }
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("the gradient magnitude of this row, value units per world unit");
    }
    if (ImGui::SmallButton("add gradient row")) {
      // A tenth of the value range per voxel above the last row.
      const float voxel = std::max(smallestVoxelSpacing(v), 1e-6f);
      const float step =
          std::max((v.volume->maxValue - v.volume->minValue) / (10.0f * voxel), 1.0f);
      const int r = insertTransferRow(tf, tf.rows.back().gradient + step);
      if (r >= 0) state.transferRow = std::size_t(r), state.transferPoint = -1, changed = true;
    }
    if (tf.twoDimensional()) {
      ImGui::SameLine();
      if (ImGui::SmallButton("remove row") && removeTransferRow(tf, state.transferRow))
        state.transferRow = 0, state.transferPoint = -1, changed = true;
    }
  }
  std::vector<TransferPoint>& row = tf.rows[state.transferRow].points;
  float lo = std::min(v.volume->minValue, row.front().value);
  float hi = std::max(v.volume->maxValue, row.back().value);
  if (!(hi > lo)) hi = lo + 1.0f;
  changed |= curveCanvas(row, v.labels, lo, hi, state);
  bool released = ImGui::IsItemDeactivated();
  if (state.transferPoint >= int(row.size())) state.transferPoint = -1;
  if (state.transferPoint >= 0) {
    const std::size_t i = std::size_t(state.transferPoint);
    TransferPoint& p = row[i];
    float value = p.value;
    if (ImGui::DragFloat("value", &value, (hi - lo) * 0.001f, lo, hi, "%.4g")) {
      moveTransferPoint(row, i, value, p.opacity, v.labels);
      changed = true;
    }
    released |= ImGui::IsItemDeactivatedAfterEdit();
    changed |= ImGui::ColorEdit3("colour", &p.color[0], ImGuiColorEditFlags_Float);
    changed |= ImGui::SliderFloat("opacity", &p.opacity, 0.0f, 1.0f, "%.3f");
    released |= ImGui::IsItemDeactivatedAfterEdit();
    changed |= ImGui::SliderFloat("importance", &p.importance, 0.0f, 1.0f, "%.2f");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "the material's importance (Burns11 §3.2, §7.1): emphasis and "
          "occlusion reduction");
  } else {
    ImGui::TextDisabled("click a point to edit it");
  }
  if (changed) state.viewChanged = true;
  // The cutout's wedge lies on the main axis of an exterior volume's material, made with the
  // renderer: an edit that may change what is material makes a new one when it ends.
  if (released && v.role == Role::Exterior && scene.cutters.find<CutoutOptions>())
    state.sceneChanged = true;
}

}  // namespace cutaway::view
