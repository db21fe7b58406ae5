// Parameters of the cutters and styles as the viewer edits them: each is a key
// ("adaptive.angle"), a type and range, and a getter and setter on the Scene. The panels draw
// them as sliders and toggles and the script's `set KEY VALUE` goes through the same table,
// so the UI and the script can never disagree on what exists or on its range.
//
// A cutter or style adds its table in parameters/<name>.cpp and lists it in
// parameterGroups(); its panel (panels/<name>_panel.cpp) draws the table.
//
//   const Parameter* p = findParameter("adaptive.angle");
//   p->set(scene, parseParameterValue(*p, "30"));   // throws std::invalid_argument on "120"
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <glm/glm.hpp>

#include "cutaway/scene/scene.hpp"

namespace cutaway::view {

using ParameterValue = std::variant<bool, double, std::string, glm::vec3>;

struct Parameter {
  // Direction: a non-zero vec3, normalised when set. Choice: one of `choices`, a string.
  enum class Type { Bool, Int, Float, Choice, Color, Direction };
  std::string key;    // "<group>.<name>", as in the script
  std::string label;  // for the UI
  Type type = Type::Float;
  double min = 0, max = 1;  // Int and Float: the accepted range (closed)
  // Sliders span [min, sliderMax] when it is given (e.g. world units without a natural
  // bound); values up to `max` are still accepted from the script. Without it, a Float with
  // an unbounded range is dragged instead.
  std::optional<double> sliderMax;
  std::function<std::vector<std::string>()> choices;  // Choice
  std::string help;                                   // tooltip: what it is, which paper
  std::function<ParameterValue(const Scene&)> get;
  std::function<void(Scene&, const ParameterValue&)> set;
  // Whether the parameter applies now (e.g. ghost distance only with ghost lines on); the
  // UI greys it out otherwise. Null: always.
  std::function<bool(const Scene&)> applies;
  // Read by the renderer every frame (a uniform): a change redraws the view and keeps the
  // renderer, instead of building a new one.
  bool live = false;
};

struct ParameterGroup {
  std::string name;   // key prefix, e.g. "adaptive"
  std::string title;  // panel title
  const std::vector<Parameter>* parameters;
};

const std::vector<Parameter>& adaptiveParameters();     // parameters/adaptive.cpp
const std::vector<Parameter>& styleParameters();        // parameters/style.cpp
const std::vector<Parameter>& cutoutParameters();       // parameters/diepstraten.cpp
const std::vector<Parameter>& breakawayParameters();    // parameters/diepstraten.cpp
const std::vector<Parameter>& clipSurfaceParameters();  // parameters/clip_surfaces.cpp
const std::vector<Parameter>& terrainParameters();      // parameters/terrain.cpp
const std::vector<Parameter>& networkParameters();      // parameters/networks.cpp
const std::vector<ParameterGroup>& parameterGroups();
const Parameter* findParameter(const std::string& key);

// Parses script text for `p` ("true"/"false"/"on"/"off", a number, a choice, "r,g,b");
// throws std::invalid_argument with the reason (range, type, unknown choice).
ParameterValue parseParameterValue(const Parameter& p, const std::string& text);
std::string formatParameterValue(const ParameterValue& value);

}  // namespace cutaway::view
