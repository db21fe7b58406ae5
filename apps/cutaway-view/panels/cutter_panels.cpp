// The panels of the Diepstraten03, Trapp13 and Konev18 cutters: their parameter tables
// (parameters/diepstraten.cpp, parameters/clip_surfaces.cpp, parameters/terrain.cpp,
// parameters/networks.cpp) and what the scene gives them to work on.
#include <imgui.h>

#include <algorithm>

#include "panels.hpp"

namespace cutaway::view {

namespace {

std::size_t countRole(const Scene& scene, Role role) {
  return std::size_t(
      std::count_if(scene.objects.begin(), scene.objects.end(),
                    [&](const SceneObject& o) { return !o.proxy && o.role == role; }));
}

}  // namespace

void cutoutPanel(ViewerState& state) {
  parameterTable(cutoutParameters(), state);
  ImGui::TextDisabled("%zu exterior objects (roles: Scene panel); groups share one wedge",
                      countRole(state.scene, Role::Exterior));
}

void breakawayPanel(ViewerState& state) {
  parameterTable(breakawayParameters(), state);
  ImGui::TextDisabled("%zu interior objects around %zu exterior ones; one hull per group",
                      countRole(state.scene, Role::Interior),
                      countRole(state.scene, Role::Exterior));
}

void clipSurfacePanel(ViewerState& state) {
  if (!state.scene.clipSurfaces) {
    ImGui::TextDisabled("no clip surfaces in this scene (cutters.clipSurfaces)");
    return;
  }
  parameterTable(clipSurfaceParameters(), state);
}

void terrainPanel(ViewerState& state) {
  if (!state.scene.terrainOpening) {
    ImGui::TextDisabled("no terrain opening in this scene (cutters.terrainOpening)");
    return;
  }
  parameterTable(terrainParameters(), state);
  ImGui::TextDisabled("%zu network polylines", state.scene.terrainOpening->lines.size());
}

void networkPanel(ViewerState& state) {
  if (state.scene.networks.empty()) {
    ImGui::TextDisabled("no pipe networks in this scene (networks)");
    return;
  }
  parameterTable(networkParameters(), state);
  for (const PipeNetwork& net : state.scene.networks)
    ImGui::TextDisabled("%s: %zu pipes, %zu shafts, %s", net.name.c_str(), net.pipes.size(),
                        net.shafts.size(),
                        net.mode == PipeNetwork::Mode::Billboards ? "billboards" : "meshed");
}

}  // namespace cutaway::view
