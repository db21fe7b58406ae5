// The subcommands of the `cutaway` program.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cutaway/core/error.hpp"

namespace cutaway::cli {

// A value on the command line that the parser took but the command refuses (out of its
// range, or at odds with another option): exit code 2, as a line that cannot be parsed.
struct CommandLineError : Error {
  using Error::Error;
};

// Scene overrides shared by render and bench.
struct SceneOverrides {
  std::string size;  // "WxH"
  std::optional<glm::vec3> eye, target, up;
  std::optional<float> fov;
  std::string projection;
  bool fit = false;
  std::string style;
  std::optional<int> samples;
  std::optional<float> pixelError;
  bool simplify = false;              // addSimplifiedVersions
  std::optional<float> cutawayAngle;  // adaptive cutter θ, degrees
  bool noCutaway = false;
  bool shadows = false;  // turn on style.shadows
  std::vector<std::string> set;  // "PATH=VALUE" (cutaway/render/techniques.hpp), in order
  std::vector<std::string> importance;  // "PATTERN=V" (Scene::setImportance), in order
};

struct RenderOptions {
  std::string scene, output, aovDir;
  std::string svg;    // the volumes' lines as SVG beside the PNG
  int city = 0;       // > 0: Konev18's generated benchmark city at this scale instead of a scene
  int frames = 0;     // > 0: an animation sequence of that many frames
  float time = 0.0f;  // the instant of a single frame, seconds
  SceneOverrides overrides;
};
int render(const RenderOptions& options);

// A scene file (.json), or any GDAL raster or OGR vector file (layers, CRS, extent, fields;
// raster size, geotransform, nodata, min/max), as JSON.
int info(const std::string& path);

struct DemOptions {
  std::vector<double> extent;  // west south east north
  std::string crs, output;
  double cell = 10.0, relief = 25.0, base = 0.0, wavelength = 1000.0;
  int octaves = 5;
  unsigned seed = 1;
};
// A synthetic DEM GeoTIFF from fractal value noise (io/raster_terrain.hpp).
int dem(const DemOptions& options);

struct BenchOptions {
  std::string scene;
  int city = 0;  // > 0: Konev18's generated benchmark city at this scale instead of a scene
  int frames = 60;
  bool json = false;
  bool noOcclusionCulling =
      false;  // every object drawn every frame (Renderer::setOcclusionCulling)
  SceneOverrides overrides;
};
int bench(const BenchOptions& options);

// Every registered technique's options (cutaway/render/techniques.hpp) with type, range,
// default, liveness and documentation, as a table or JSON.
int listOptions(bool json);

}  // namespace cutaway::cli
