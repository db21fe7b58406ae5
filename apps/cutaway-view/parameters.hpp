// Parameters as the viewer edits them: every registered technique's options
// (cutaway/render/techniques.hpp: the scene file's paths, types, ranges, defaults and docs,
// as `cutaway render --set` takes them, the pipe networks' and volumes' among them), grouped by
// technique. The panels draw them as sliders and toggles and the script's
// `set KEY VALUE` goes through the same table, so the UI, the script, the CLI and the scene
// file can never disagree on what exists or on its range. A parameter whose spec is live
// (a uniform) redraws with the same renderer; any other builds a new one.
//
//   const Parameter* p = findParameter("cutters.adaptive.angle");
//   p->assign(scene, parseOptionValue(*p, "30"));   // throws std::invalid_argument on "120"
#pragma once

#include <string>
#include <vector>

#include "cutaway/core/options.hpp"
#include "cutaway/scene/scene.hpp"

namespace cutaway::view {

using ParameterValue = OptionValue;

// An option whose get, set and applies take the Scene.
struct Parameter : OptionSpec {
  ParameterValue value(const Scene& s) const { return get(&s); }
  void assign(Scene& s, const ParameterValue& v) const { set(&s, v); }
  bool appliesTo(const Scene& s) const { return !applies || applies(&s); }
};

struct ParameterGroup {
  std::string name;   // key prefix: a technique's path ("cutters.adaptive"), or "networks"
  std::string title;  // panel title
  std::string style;  // shading styles: the style.name they belong to
  std::vector<Parameter> parameters;
};

const std::vector<ParameterGroup>& parameterGroups();
const ParameterGroup* findGroup(const std::string& name);
const Parameter* findParameter(const std::string& key);

}  // namespace cutaway::view
