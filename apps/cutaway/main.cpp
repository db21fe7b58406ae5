// cutaway — renders cutaway illustrations of 3-D scenes headless.
//
//   cutaway render examples/engine.json -o engine.png [--size 800x600] [--aov out/aovs]
//   cutaway info examples/engine.json
//   cutaway bench examples/engine.json --frames 30 [--json]
//   cutaway info /usr/share/plplot5.15.0/ss/ss64ne_Building_Area.shp
//   cutaway dem --extent 265000 145000 270000 150000 --crs EPSG:27700 -o dem.tif
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <new>
#include <sstream>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "cutaway/core/atomic_file.hpp"
#include "cutaway/core/contained.hpp"
#include "cutaway/core/error.hpp"
#include "cutaway/render/techniques.hpp"
#include "cutaway/scene/scene.hpp"

namespace {

// "x,y,z" → vec3, for camera overrides.
std::string parseVec3(const std::string& text, glm::vec3& out) {
  std::istringstream in(text);
  char c1 = 0, c2 = 0;
  glm::dvec3 v;
  if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',' || !in.eof())
    return "expected three comma-separated numbers x,y,z";
  for (int i = 0; i < 3; ++i)
    if (!(std::abs(v[i]) <= double(std::numeric_limits<float>::max())))
      return cutaway::quote(text) + ": a coordinate lies beyond a 32-bit float's range";
  out = glm::vec3(v);
  return "";
}

// A finite number in [least, most] (above `least` where `aboveLeast`). CLI11's ranges let NaN
// through (every comparison with it is false), and their messages print DBL_MAX in full.
CLI::Validator finiteNumber(double least = -HUGE_VAL, double most = HUGE_VAL,
                            bool aboveLeast = false) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        // As CLI11 converts it afterwards (strtod: hexadecimal too), the whole text.
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        const bool low = aboveLeast ? !(v > least) : !(v >= least);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(v) || low || !(v <= most)) {
          std::ostringstream need;
          need << "a finite number";
          if (most != HUGE_VAL)
            need << " in " << (aboveLeast ? "(" : "[") << least << ", " << most << "]";
          else if (least != -HUGE_VAL)
            need << (aboveLeast ? " above " : " of at least ") << least;
          return "expected " + need.str() + ", got " + cutaway::quote(text);
        }
        return "";
      },
      "NUMBER");
}

void addSceneOverrides(CLI::App* command, cutaway::cli::SceneOverrides& o) {
  command->add_option("--size", o.size, "Image size WxH, e.g. 1024x768 (overrides the scene)");
  auto vecOption = [&](const char* name, std::optional<glm::vec3>& target, const char* help) {
    command->add_option_function<std::string>(
        name,
        [&target, name](const std::string& s) {
          glm::vec3 v;
          if (auto e = parseVec3(s, v); !e.empty()) throw CLI::ValidationError(name, e);
          target = v;
        },
        help);
  };
  vecOption("--eye", o.eye, "Camera position x,y,z");
  vecOption("--target", o.target, "Camera target x,y,z");
  vecOption("--up", o.up, "Camera up vector x,y,z");
  command
      ->add_option_function<float>(
          "--fov", [&o](float f) { o.fov = f; }, "Vertical field of view in degrees")
      ->check(finiteNumber(1.0, 170.0));
  command->add_option("--projection", o.projection, "Camera projection")
      ->check(CLI::IsMember({"perspective", "orthographic"}));
  command->add_flag("--fit", o.fit, "Fit the camera to the scene (keeps the viewing direction)");
  command->add_option("--style", o.style, "Shading style")
      ->check(CLI::IsMember(cutaway::styleNames()));
  command->add_flag("--shadows", o.shadows, "Shadows from the key light (style.shadows)");
  command
      ->add_option_function<int>(
          "--samples", [&o](int s) { o.samples = s; }, "MSAA samples (1, 2, 4, 8, 16)")
      ->check(CLI::IsMember({1, 2, 4, 8, 16}));
  command
      ->add_option_function<float>(
          "--pixel-error", [&o](float e) { o.pixelError = e; },
          "Screen-space error in pixels that terrain grids and shafts may show where drawn "
          "coarser (0: every triangle)")
      ->check(finiteNumber(0.0, 100.0));
  command->add_flag("--simplify", o.simplify,
                    "Draw every other mesh simplified too, within --pixel-error (as the viewer "
                    "does while its view moves)");
  command
      ->add_option_function<float>(
          "--cutaway-angle", [&o](float a) { o.cutawayAngle = a; },
          "Adaptive cutaway angle θ in degrees (adds the cutter if the scene has none)")
      ->check(finiteNumber(0.0, 90.0));
  command->add_flag("--no-cutaway", o.noCutaway,
                    "Render without any of the scene's cutters (the plain model)");
  command
      ->add_option("--set", o.set,
                   "PATH=VALUE: set any technique's option by its scene-file path, e.g. "
                   "cutters.adaptive.angle=30, style.lines.width=2, style.gooch.alpha=0.3, "
                   "cutters.cutout=true (repeatable; `cutaway options` lists them; a path "
                   "given twice to different values, or also set by --style, --shadows, "
                   "--cutaway-angle or --no-cutaway, is refused)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  command->add_option("--importance", o.importance,
                      "PATTERN=V: importance V in [0, 1] for the objects whose name or group the "
                      "regular expression matches whole (Burns11 §3; repeatable, in order)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

// The edits (insert, delete, replace a letter) that turn `a` into `b`.
std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      diagonal = std::exchange(row[j], std::min({row[j] + 1, row[j - 1] + 1,
                                                 diagonal + (a[i - 1] != b[j - 1] ? 1 : 0)}));
  }
  return row[b.size()];
}

// CLI11 reads a mistyped command as none at all ("A subcommand is required"): name it, and the
// command it is closest to.
std::string unknownCommand(CLI::App& app, const std::string& word) {
  std::string names, closest;
  std::size_t best = 3;  // at most two edits away
  for (const CLI::App* command : app.get_subcommands({})) {
    const std::string& name = command->get_name();
    if (name == word) return "";
    names += (names.empty() ? "" : ", ") + name;
    if (const std::size_t d = editDistance(word, name); d < best) best = d, closest = name;
  }
  return "unknown command " + cutaway::quote(word) +
         (closest.empty() ? "" : " (did you mean " + closest + "?)") + "; the commands are " +
         names;
}

constexpr const char* kCityHelp =
    "Konev18's generated benchmark city of Table 1 (1190 pipes, 1156 shafts, a 2.9M-triangle "
    "terrain) times this scale, instead of a scene file";

}  // namespace

int main(int argc, char** argv) {
  cutaway::startContainedHelper();  // while the process is small (cutaway/core/contained.hpp)
  cutaway::removeTemporariesOnSignals();  // a stopped run leaves no partial file behind
  CLI::App app{"cutaway: cutaway illustrations of 3-D scenes"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "cutaway 0.1.0");

  cutaway::cli::RenderOptions renderOptions;
  auto* render = app.add_subcommand("render", "Render a scene to a PNG image, headless");
  auto* renderScene = render->add_option("scene", renderOptions.scene, "Scene file (JSON)");
  render->add_option("--city", renderOptions.city, kCityHelp)
      ->check(CLI::Range(1, 100))
      ->excludes(renderScene);
  render->add_option("-o,--output", renderOptions.output, "Output PNG file")->required();
  // An empty value would read as the option not given.
  const CLI::Validator named(
      [](const std::string& s) {
        return s.empty() ? std::string("the name is empty") : std::string();
      },
      "", "named");
  render
      ->add_option("--aov", renderOptions.aovDir,
                   "Directory for the frame's intermediate buffers (PFM + aovs.json); with "
                   "--frames, one sub-directory per frame")
      ->check(named);
  render
      ->add_option("--svg", renderOptions.svg,
                   "The volumes' lines (a volume's \"lines\") as SVG, visible ones and, when "
                   "dimmed or shown, hidden ones, with their halos; with --frames, numbered "
                   "as the PNGs")
      ->check(named);
  auto* frames = render
                     ->add_option("--frames", renderOptions.frames,
                                  "Render an animation of N frames spanning the scene's duration; "
                                  "OUT may hold a printf pattern (frame_%04d.png), else the "
                                  "frame number is appended to its stem")
                     ->check(CLI::Range(1, 100000));
  render->add_option("--time", renderOptions.time, "Render the single instant T (seconds)")
      ->check(finiteNumber(0.0, 1e6))
      ->excludes(frames);
  addSceneOverrides(render, renderOptions.overrides);

  std::string infoScene;
  auto* info = app.add_subcommand("info",
                                  "Print the scene's objects, triangle counts, bounds "
                                  "and watertightness as JSON; or a GIS file's layers or a "
                                  "raster's size, CRS, geotransform, nodata and range");
  info->add_option("file", infoScene, "Scene file (.json), GIS vector file or raster")->required();

  cutaway::cli::DemOptions demOptions;
  auto* dem = app.add_subcommand("dem",
                                 "Write a synthetic DEM (Float32 GeoTIFF) from fractal value "
                                 "noise, for tiles without real heights");
  dem->add_option("--extent", demOptions.extent, "West south east north, in the CRS's units")
      ->expected(4)
      ->required();
  dem->add_option("--crs", demOptions.crs, "CRS (EPSG:27700, WKT, PROJ string)")->required();
  dem->add_option("--cell", demOptions.cell, "Cell size; the extent must hold whole cells")
      ->capture_default_str()
      ->check(finiteNumber(0.0, HUGE_VAL, true));
  dem->add_option("--relief", demOptions.relief, "Height range above the base")
      ->capture_default_str()
      ->check(finiteNumber(0.0));
  dem->add_option("--base", demOptions.base, "Lowest height")
      ->capture_default_str()
      ->check(finiteNumber());
  dem->add_option("--wavelength", demOptions.wavelength, "Size of the largest hills")
      ->capture_default_str()
      ->check(finiteNumber(0.0, HUGE_VAL, true));
  dem->add_option("--octaves", demOptions.octaves, "Noise octaves")
      ->capture_default_str()
      ->check(CLI::Range(1, 16));
  dem->add_option("--seed", demOptions.seed, "Noise seed")->capture_default_str();
  dem->add_option("-o,--output", demOptions.output, "Output GeoTIFF")->required();

  bool optionsJson = false;
  auto* options = app.add_subcommand("options",
                                     "List every technique's options: the paths --set and the "
                                     "viewer's script take, their types, ranges, defaults and "
                                     "whether a change is live");
  options->add_flag("--json", optionsJson, "Print JSON instead of a table");

  cutaway::cli::BenchOptions benchOptions;
  auto* bench = app.add_subcommand("bench",
                                   "Render frames and report per-pass GPU times and "
                                   "frame times");
  auto* benchScene = bench->add_option("scene", benchOptions.scene, "Scene file (JSON)");
  bench->add_option("--city", benchOptions.city, kCityHelp)
      ->check(CLI::Range(1, 100))
      ->excludes(benchScene);
  bench
      ->add_option("--frames", benchOptions.frames,
                   "Frames to time per run (after one warm-up frame). With a cutter, bench runs "
                   "the plain frame and the cutaway at 512² and 1024² on GPU and CPU paths, the "
                   "CPU reference kernels and the jump-flooding accuracy: minutes on llvmpipe")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  bench->add_flag("--json", benchOptions.json, "Print JSON instead of a table");
  bench->add_flag("--no-occlusion-culling", benchOptions.noOcclusionCulling,
                  "Draw every object every frame, also those the last frame found hidden (to "
                  "compare)");
  addSceneOverrides(bench, benchOptions.overrides);

  if (argc > 1 && argv[1][0] != '-')
    if (const std::string why = unknownCommand(app, argv[1]); !why.empty()) {
      std::fprintf(stderr, "cutaway: error: %s (see --help)\n", why.c_str());
      return 2;
    }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "cutaway: error: %s (see --help)\n", e.what());
    return 2;
  }
  try {
    if (*render) return cutaway::cli::render(renderOptions);
    if (*info) return cutaway::cli::info(infoScene);
    if (*bench) return cutaway::cli::bench(benchOptions);
    if (*dem) return cutaway::cli::dem(demOptions);
    if (*options) return cutaway::cli::listOptions(optionsJson);
  } catch (const cutaway::cli::CommandLineError& e) {
    std::fprintf(stderr, "cutaway: error: %s\n", e.what());
    return 2;
  } catch (const cutaway::Error& e) {
    std::fprintf(stderr, "cutaway: error: %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    // What an input claims (a count, a size) outgrew the memory; name what was being read.
    std::string input = *render  ? renderOptions.scene
                        : *info  ? infoScene
                        : *bench ? benchOptions.scene
                                 : demOptions.output;
    if (input.empty()) input = "the benchmark city";
    std::fprintf(stderr, "cutaway: error: %s: out of memory while loading or rendering it\n",
                 input.c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cutaway: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
