// The techniques' test scenes: for each registered technique (cutter, style, the networks' and
// volumes' options), scenes where it
// is on, shared by the tests that go through every option of every schema
// (test_live_options.cpp, test_options_round_trip.cpp). A technique without scenes here
// fails those tests, so a new cutter or style must name its scenes.
#pragma once

#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "cutaway/render/techniques.hpp"

namespace cutaway::test {

struct Case {
  std::string technique;              // TechniqueInfo::path
  std::vector<std::string> examples;  // each of its live options must show in one of them
  std::vector<std::pair<std::string, std::string>> setup;  // setOption before the first frame
  int width = 96, height = 72;
};

inline void PrintTo(const Case& c, std::ostream* os) {
  *os << c.technique;
}

// Scenes (examples/, or tests/data/ where an example would be slow) where the technique is
// on and, between them, each of its live options shows: the engine's pistons lie far from the
// image's edges, so the city's pipes show the adaptive cutter's edge compression; three
// squares stacked in front of a box show the edge highlights' exponent and the layer budget;
// the contextual engine's graded importance shows every emphasis; the engine's casing is
// hollow (its inside colour) and the bunny's box solid (its walls, which the breakaway leaves
// a few pixels wide at 240²).
inline std::vector<Case> cases() {
  std::vector<Case> out;
  for (const TechniqueInfo& t : techniques()) {
    Case c{t.path, {}, {}, 96, 72};
    if (t.path == "cutters.adaptive")
      c.examples = {"examples/engine-cutaway.json", "examples/ss64ne-city-cutaway.json",
                    "examples/engine-contextual.json",
                    "tests/data/render/edge-highlights-stack.json"},
      c.setup = {{"cutters.adaptive.ghostLines", "true"}};
    else if (t.path == "cutters.cutout")
      c.examples = {"examples/bunny-box-cutout.json", "examples/engine-cutout.json"},
      c.setup = {{"cutters.cutout.jitter.pattern", "noise"}, {"cutters.cutout.jitter.amplitude", "0.05"}};
    else if (t.path == "cutters.breakaway")
      c.examples = {"examples/bunny-box-breakaway.json", "examples/engine-breakaway.json"},
      c.width = c.height = 240;
    else if (t.path == "cutters.clipSurfaces")
      c.examples = {"tests/data/render/two-clip-surfaces.json"},
      c.setup = {{"cutters.clipSurfaces.capStyle.solidTexture", "true"}};
    else if (t.path == "cutters.terrainOpening")
      c.examples = {"examples/pipes-street.json", "examples/ss64ne-terrain.json"};
    else if (t.path == "cutters.boxCut") c.examples = {"examples/house-box-cut.json"};
    else if (t.path == "style")
      c.examples = {"examples/engine.json", "examples/engine-contextual.json"},
      c.setup = {{"style.shadows", "true"}, {"style.emphasis.linesOnlyBelow", "0.2"}};
    else if (t.path == "networks")
      c.examples = {"examples/pipes-street.json"};
    // Without lines: those follow the last frame's (Burns11 §2.4.1.3's walks, each segment's
    // fate decided the frame before), so a live change takes frames to reach a new renderer's.
    else if (t.path == "volumes")
      c.examples = {"examples/mri-head-clip.json"};
    else if (!t.name.empty())
      c.examples = {"examples/bunny.json"}, c.setup = {{"style.name", t.name}};
    out.push_back(c);
  }
  return out;
}

inline Scene small(const Case& c, const std::string& file) {
  Scene scene = loadScene(std::string(CUTAWAY_SOURCE_DIR) + "/" + file);
  scene.width = c.width, scene.height = c.height;
  for (const auto& [path, value] : c.setup) setOption(scene, path, value);
  return scene;
}

// A value of the option's type that differs from `now`, inside its range.
inline OptionValue changed(const OptionSpec& spec, const OptionValue& now) {
  using Type = OptionSpec::Type;
  switch (spec.type) {
    case Type::Bool:
      return !std::get<bool>(now);
    case Type::Int:
    case Type::Float: {
      // Half-way to the end of its range (of its slider, for unbounded ones), upwards first.
      const double v = std::get<double>(now);
      const double hi = std::min({spec.max, spec.sliderMax.value_or(spec.max), 4.0 * std::abs(v) + 1.0});
      const auto step = [&](double to) {
        const double x = 0.5 * (v + to);
        return spec.type == Type::Int ? std::round(x) : x;
      };
      if (spec.powerOfTwo) return v * 2 <= spec.max ? v * 2 : v / 2;
      const double up = step(hi);
      return up != v && up <= spec.max ? up : step(spec.min);
    }
    case Type::Choice: {
      const std::string& s = std::get<std::string>(now);
      for (const std::string& choice : spec.choices)
        if (choice != s) return choice;
      return s;
    }
    case Type::Color:
      return glm::vec3(0.9f, 0.1f, 0.6f) == std::get<glm::vec3>(now) ? glm::vec3(0.1f, 0.8f, 0.3f)
                                                                    : glm::vec3(0.9f, 0.1f, 0.6f);
    case Type::Direction:
      return glm::normalize(std::get<glm::vec3>(now) + glm::vec3(0.4f, -0.3f, 0.2f));
    case Type::Vec3:
      return std::get<glm::vec3>(now) * 1.15f + glm::vec3(0.05f);
    case Type::Text:
      break;
  }
  return now;
}

}  // namespace cutaway::test
