// The options of the scene's pipe networks and volumes as scene options (render/techniques.cpp:
// "networks.<key>", "volumes.<key>"), each set on every network or volume of the scene at once.
// get, set and applies take a (const) Scene*.
#pragma once

#include <vector>

#include "cutaway/core/options.hpp"
#include "cutaway/scene/scene.hpp"

namespace cutaway {

std::vector<OptionSpec> networkOptions();  // kinds/pipes/network_options.cpp
std::vector<OptionSpec> volumeOptions();   // kinds/volumes/volume_options.cpp

}  // namespace cutaway
