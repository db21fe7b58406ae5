// The scene panel: objects grouped as in the scene (the `group` of objects and overrides),
// selection by click (Ctrl adds) or a whole group at once, and the selection's role,
// importance and local cutaway angle (Burns08 §5.3, Burns11 §6.2.1).
#include <imgui.h>

#include <algorithm>

#include "cutaway/cutters/adaptive.hpp"
#include "panels.hpp"

namespace cutaway::view {

namespace {

ImVec4 roleColor(Role role) {
  switch (role) {
    case Role::Interest:
      return {0.95f, 0.55f, 0.2f, 1.0f};
    case Role::Exterior:
      return {0.5f, 0.7f, 1.0f, 1.0f};
    case Role::Interior:
      return {0.6f, 0.9f, 0.6f, 1.0f};
    case Role::Context:
      break;
  }
  return {0.7f, 0.7f, 0.7f, 1.0f};
}

void objectRow(ViewerState& state, std::size_t i) {
  const SceneObject& o = state.scene.objects[i];
  const bool selected = state.selection.count(i) != 0;
  ImGui::PushID(int(i));
  ImGui::TextColored(roleColor(o.role), "%-8s", roleName(o.role));
  ImGui::SameLine();
  const std::string label = o.proxy ? o.name + " (proxy)" : o.name;
  if (ImGui::Selectable(label.c_str(), selected)) {
    if (!ImGui::GetIO().KeyCtrl) state.selection.clear();
    if (selected && ImGui::GetIO().KeyCtrl)
      state.selection.erase(i);
    else
      state.selection.insert(i);
  }
  ImGui::PopID();
}

void selectionControls(ViewerState& state) {
  if (state.selection.empty()) {
    ImGui::TextDisabled("Click an object here or in the view (Ctrl adds).");
    return;
  }
  const SceneObject& first = state.scene.objects[*state.selection.begin()];
  if (state.selection.size() == 1)
    ImGui::Text("%s", first.name.c_str());
  else
    ImGui::Text("%zu objects selected", state.selection.size());

  int role = int(first.role);
  const char* roles[] = {"context", "interest", "exterior", "interior"};
  if (ImGui::Combo("role", &role, roles, 4)) setRole(state, Role(role));
  float importance = first.importance;
  if (ImGui::SliderFloat("importance", &importance, 0.0f, 1.0f, "%.2f"))
    setImportance(state, importance);

  const auto it = first.params.find("cutawayAngle");
  bool local = it != first.params.end();
  const auto* adaptive = state.scene.cutters.find<AdaptiveCutawayOptions>();
  const float global = adaptive ? adaptive->angle : AdaptiveCutawayOptions{}.angle;
  float angle = local ? float(std::get<double>(it->second)) : global;
  ImGui::BeginDisabled(!adaptive);
  if (ImGui::Checkbox("own cutaway angle", &local))
    setLocalAngle(state, local ? std::optional<float>(angle) : std::nullopt);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Local angle θ of objects of interest (Burns08 §5.3); applies to every "
        "selected object, e.g. a whole group.");
  ImGui::BeginDisabled(!local);
  if (ImGui::SliderFloat("angle θ (°)", &angle, 0.0f, 90.0f, "%.1f")) setLocalAngle(state, angle);
  ImGui::EndDisabled();
  ImGui::EndDisabled();
  if (ImGui::Button("Deselect")) state.selection.clear();
  ImGui::SameLine();
  if (ImGui::Button("Frame (F)")) state.frameRequested = true;
}

}  // namespace

void scenePanel(ViewerState& state) {
  ImGui::TextDisabled("%s", state.scene.file.filename().string().c_str());
  const float listHeight =
      ImGui::GetContentRegionAvail().y - 7.0f * ImGui::GetFrameHeightWithSpacing();
  ImGui::BeginChild("objects", ImVec2(0, std::max(listHeight, 80.0f)), true);
  for (const auto& group : groupsOf(state.scene)) {
    std::vector<std::size_t> members;
    for (std::size_t i = 0; i < state.scene.objects.size(); ++i)
      if (state.scene.objects[i].group == group) members.push_back(i);
    const std::string title = (group.empty() ? std::string("(no group)") : group) + " (" +
                              std::to_string(members.size()) + ")";
    ImGui::PushID(group.c_str());
    // Groups are what the author singled out: open. The ungrouped rest (often the many parts
    // of the context) starts closed unless it is short.
    constexpr std::size_t kShortList = 20;
    const bool open = ImGui::TreeNodeEx(
        title.c_str(),
        !group.empty() || members.size() <= kShortList ? ImGuiTreeNodeFlags_DefaultOpen : 0);
    if (!group.empty()) {
      ImGui::SameLine();
      if (ImGui::SmallButton("select")) {
        if (!ImGui::GetIO().KeyCtrl) state.selection.clear();
        state.selection.insert(members.begin(), members.end());
      }
    }
    if (open) {
      for (std::size_t i : members) objectRow(state, i);
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
  ImGui::EndChild();
  selectionControls(state);
}

}  // namespace cutaway::view
