// The viewer's Dear ImGui panels, one function per panel and file, each drawing from and
// writing to the ViewerState. Every technique's panel is its parameter group
// (parameters.hpp, generated from the registries' schemas) drawn by techniquePanel, with
// notes on what the scene gives it to work on where there are any (panels/technique_panels.cpp).
#pragma once

#include <optional>
#include <vector>

#include "../parameters.hpp"
#include "../viewer_state.hpp"

namespace cutaway::view {

// One parameter's widget (checkbox, slider, combo, colour); the new value when the user
// changed it.
std::optional<ParameterValue> parameterWidget(const Parameter& parameter, const Scene& scene);
// Every parameter of `table`, greyed out where it does not apply; a change goes through
// setParameter.
void parameterTable(const std::vector<Parameter>& table, ViewerState& state);

void scenePanel(ViewerState& state);   // objects by group, selection, role, importance, angle
void cameraPanel(ViewerState& state);  // projection, fly mode, framing, path, time
void filePanel(ViewerState& state);    // save scene, screenshot
// A technique's parameter group and its notes (counts of the objects it works on, where its
// work runs).
void techniquePanel(const ParameterGroup& group, ViewerState& state);
// The volumes' transfer-function editor (under the volumes' parameters).
void transferPanel(ViewerState& state);
void aovPanel(ViewerState& state);     // AOV inspector: buffer, colour map, range, value
void timingsPanel(const ViewerState& state, float framesPerSecond);

}  // namespace cutaway::view
