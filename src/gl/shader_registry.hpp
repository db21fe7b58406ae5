// The table of embedded shader files, generated at build time by cmake/EmbedShaders.cmake.
#pragma once

#include <map>
#include <string_view>

namespace cutaway::gl {
const std::map<std::string_view, std::string_view>& embeddedShaders();
}
