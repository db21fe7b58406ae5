// The options of the scene's pipe networks and volumes as scene options (render/techniques.cpp:
// "networks.<key>", "volumes.<key>"), each set on every network or volume of the scene at once.
// get, set and applies take a (const) Scene*.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "cutaway/core/options.hpp"
#include "cutaway/scene/scene.hpp"

namespace cutaway {

std::vector<OptionSpec> networkOptions();  // kinds/pipes/network_options.cpp
std::vector<OptionSpec> volumeOptions();   // kinds/volumes/volume_options.cpp

// Such an option before its get, set and applies: all of them are live (read every frame).
inline OptionSpec liveMemberOption(std::string path, std::string label, OptionSpec::Type type,
                                   std::string doc) {
  OptionSpec p;
  p.key = std::move(path);
  p.label = std::move(label);
  p.type = type;
  p.doc = std::move(doc);
  p.live = true;
  return p;
}

}  // namespace cutaway
