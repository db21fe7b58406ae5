// The subcommands of the `cutaway` program.
#pragma once

#include <optional>
#include <string>

#include <glm/glm.hpp>

namespace cutaway::cli {

// Scene overrides shared by render and bench.
struct SceneOverrides {
  std::string size;  // "WxH"
  std::optional<glm::vec3> eye, target, up;
  std::optional<float> fov;
  std::string projection;
  bool fit = false;
  std::string style;
  std::optional<int> samples;
  std::optional<float> cutawayAngle;  // adaptive cutter θ, degrees
  bool noCutaway = false;
  bool shadows = false;  // turn on style.shadows
};

struct RenderOptions {
  std::string scene, output, aovDir;
  int frames = 0;     // > 0: an animation sequence of that many frames
  float time = 0.0f;  // the instant of a single frame, seconds
  SceneOverrides overrides;
};
int render(const RenderOptions& options);

int info(const std::string& scene);

struct BenchOptions {
  std::string scene;
  int frames = 60;
  bool json = false;
  SceneOverrides overrides;
};
int bench(const BenchOptions& options);

}  // namespace cutaway::cli
