// The registered shading styles.
#pragma once

#include <string>
#include <vector>

#include "styles/style.hpp"

namespace cutaway {

const std::vector<StyleType>& styleTypes();
// Their names (the scene file's style.name), in registry order.
const std::vector<std::string>& styleNames();
// The style's own keys: its name, the feature lines and the shadows (every shading style's
// options are read under its key beside them).
const OptionsSchema& styleSchema();
// The style named `name`, or null.
const StyleType* findStyle(const std::string& name);

}  // namespace cutaway
