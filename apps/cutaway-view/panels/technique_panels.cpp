// Every technique's panel: its parameter group, then notes on what the scene gives it to work
// on. A technique without notes gets its table alone.
#include <imgui.h>

#include <algorithm>

#include "cutaway/cutters/terrain_opening.hpp"
#include "panels.hpp"

namespace cutaway::view {

namespace {

std::size_t countRole(const Scene& scene, Role role) {
  return std::size_t(
      std::count_if(scene.objects.begin(), scene.objects.end(),
                    [&](const SceneObject& o) { return !o.proxy && o.role == role; }));
}

void notes(const std::string& group, const ViewerState& state) {
  const Scene& scene = state.scene;
  if (group == "cutters.adaptive") {
    if (!state.computePath.empty())
      ImGui::TextDisabled("jump flooding runs on the %s", state.computePath.c_str());
    ImGui::TextDisabled("local angles: select objects of interest (Scene panel)");
  } else if (group == "cutters.cutout") {
    ImGui::TextDisabled("%zu exterior objects (roles: Scene panel); groups share one wedge",
                        countRole(scene, Role::Exterior));
  } else if (group == "cutters.breakaway") {
    ImGui::TextDisabled("%zu interior objects around %zu exterior ones; one hull per group",
                        countRole(scene, Role::Interior), countRole(scene, Role::Exterior));
  } else if (group == "cutters.terrainOpening") {
    if (const auto* t = scene.cutters.find<TerrainOpeningOptions>())
      ImGui::TextDisabled("%zu network polylines", t->lines.size());
  } else if (group == "networks") {
    for (const PipeNetwork& net : scene.networks)
      ImGui::TextDisabled("%s: %zu pipes, %zu shafts, %s", net.name.c_str(), net.pipes.size(),
                          net.shafts.size(),
                          net.mode == PipeNetwork::Mode::Billboards ? "billboards" : "meshed");
  } else if (group == "volumes") {
    for (const SceneVolume& v : scene.volumes)
      ImGui::TextDisabled("%s: %d×%d×%d %s, %s%s", v.name.c_str(), v.volume->dims.x,
                          v.volume->dims.y, v.volume->dims.z, v.volume->voxelType.c_str(),
                          roleName(v.role), v.labels ? ", labels" : "");
  }
}

}  // namespace

void techniquePanel(const ParameterGroup& group, ViewerState& state) {
  if (group.name == "networks" && state.scene.networks.empty()) {
    ImGui::TextDisabled("no pipe networks in this scene (networks)");
    return;
  }
  if (group.name == "volumes" && state.scene.volumes.empty()) {
    ImGui::TextDisabled("no volumes in this scene (volumes)");
    return;
  }
  parameterTable(group.parameters, state);
  notes(group.name, state);
  if (group.name == "volumes") transferPanel(state);
}

}  // namespace cutaway::view
