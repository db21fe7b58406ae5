// The registered cutters, and the GLSL that composes the active ones into every geometry
// program.
#pragma once

#include <string>
#include <vector>

#include "cutters/cutter.hpp"

namespace cutaway {

// In the order the composition evaluates them: a fragment is removed when any cutter that cuts
// its object removes it; a back face seen through a cut takes the first cut surface of a cutter
// whose cut surfaces are asked for.
const std::vector<CutterType>& cutterTypes();

// "cutters/composition.glsl" for `active`: their GLSL files; cutFragment(cutBy, surfacesBy, f,
// cutPosition, cutNormal, cutter), the cut surfaces only of the slots in surfacesBy, which also
// names the slot whose cut surface it is; writeCutterChannels(
// cutBy, f) for the G-buffer channels they added. CUTTER_SLOTS is the registry's size.
std::string cutterComposition(const std::vector<ActiveCutter>& active);

}  // namespace cutaway
