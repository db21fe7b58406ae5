// The scene file's "networks" key (Konev18 pipe networks), read after the objects because
// node heights and shaft rims come from the terrain objects.
#pragma once

#include "core/json_reader.hpp"
#include "cutaway/scene/scene.hpp"

namespace cutaway::json_reader {

// Appends the networks to `scene.networks`, and their meshes (shafts, joints, meshed pipes)
// to `scene.objects`.
void readNetworks(const Context& ctx, const json& j, const std::string& ptr, Scene& scene);

}  // namespace cutaway::json_reader
