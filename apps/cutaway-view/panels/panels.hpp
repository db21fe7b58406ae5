// The viewer's Dear ImGui panels, one function per panel and file, each drawing from and
// writing to the ViewerState. A new cutter's panel is a file like adaptive_panel.cpp that
// draws its parameter table (parameters/<cutter>.cpp) with parameterTable() and whatever
// the cutter needs besides; the viewer calls it from its "Cutters" section.
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

void scenePanel(ViewerState& state);        // objects by group, selection, role, importance, angle
void cameraPanel(ViewerState& state);       // projection, fly mode, framing, path, time
void filePanel(ViewerState& state);         // save scene, screenshot
void adaptivePanel(ViewerState& state);     // the adaptive cutter (Burns08/11)
void cutoutPanel(ViewerState& state);       // Diepstraten03 cutout (panels/cutter_panels.cpp)
void breakawayPanel(ViewerState& state);    // Diepstraten03 breakaway
void clipSurfacePanel(ViewerState& state);  // Trapp13 clip surfaces
void terrainPanel(ViewerState& state);      // Konev18 terrain opening
void networkPanel(ViewerState& state);      // Konev18 pipe networks
void stylePanel(ViewerState& state);        // shading and lines
void aovPanel(ViewerState& state);          // AOV inspector: buffer, colour map, range, value
void timingsPanel(const ViewerState& state, float framesPerSecond);

}  // namespace cutaway::view
