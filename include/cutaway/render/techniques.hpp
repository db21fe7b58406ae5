// cutaway/render/techniques.hpp — every registered technique's options by one path, as the
// CLI's --set, the viewer's panels and script and the bindings name them. The path is the
// scene file's: "cutters.<key>.<option>" for a cutter ("cutters.<key>" alone switches it),
// "style.<option>" for the style's own (its name, lines, shadows), "style.<key>.<option>" for
// a shading style's; "networks.<option>" and "volumes.<option>" for every pipe network's or
// volume's. Each option's type, range, default, documentation and liveness come from the
// technique's schema (cutaway/core/options.hpp), written once.
//
//   cutaway::setOption(scene, "cutters.adaptive.angle", "30");   // turns the cutter on first
//   cutaway::setOption(scene, "style.lines.width", "2");
//   for (const cutaway::SceneOption& o : cutaway::sceneOptions()) std::puts(o.path.c_str());
#pragma once

#include <string>
#include <vector>

#include "cutaway/core/options.hpp"
#include "cutaway/scene/scene.hpp"

namespace cutaway {

// A registered technique as the outside sees it.
struct TechniqueInfo {
  std::string path;   // "cutters.adaptive", "style", "style.gooch"
  std::string title;  // for panels
  std::string name;   // shading styles: their style.name ("blinn-phong"); else empty
  const OptionsSchema* schema;  // null for "networks" and "volumes" (members of each)
};
// In registry order: the cutters with options of their own, the style's own keys, each
// shading style; then the pipe networks' and the volumes' options.
const std::vector<TechniqueInfo>& techniques();
// The shading styles' names (style.name), in registry order.
const std::vector<std::string>& styleNames();

// One option with `get` and `set` re-rooted on a Scene: reading a cutter that is off gives its
// default; setting any of its options turns it on with its defaults first.
struct SceneOption {
  std::string path;       // "cutters.adaptive.angle"
  std::string technique;  // the TechniqueInfo::path it belongs to
  OptionSpec spec;        // its key is the path; get/set/applies take a (const) Scene*
};
const std::vector<SceneOption>& sceneOptions();
const SceneOption* findSceneOption(const std::string& path);
// Parses `text` for the option at `path` and sets it; throws cutaway::Error naming the path
// and the reason (an unknown path lists the known ones near it).
void setOption(Scene& scene, const std::string& path, const std::string& text);

}  // namespace cutaway
