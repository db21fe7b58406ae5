#include "commands.hpp"

#include <unistd.h>

#include <cctype>
#include <charconv>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <tuple>
#include <utility>

#include "cutaway/core/error.hpp"
#include "cutaway/core/image.hpp"
#include "cutaway/core/unit_vector.hpp"
#include "cutaway/cutters/adaptive.hpp"
#include "cutaway/cutters/breakaway.hpp"
#include "cutaway/cutters/clip_surfaces.hpp"
#include "cutaway/cutters/cutout.hpp"
#include "cutaway/cutters/terrain_opening.hpp"
#include "cutaway/fields/cutaway_surface.hpp"
#include "cutaway/frame/aov.hpp"
#include "cutaway/gl/context.hpp"
#include "cutaway/io/gis_import.hpp"
#include "cutaway/io/raster_terrain.hpp"
#include "cutaway/render/renderer.hpp"
#include "cutaway/render/techniques.hpp"
#include "cutaway/scene/benchmark_city.hpp"
#include "cutaway/scene/scene.hpp"
#include "cutaway/scene/scene_writer.hpp"

namespace cutaway::cli {

namespace {

void applyOverrides(Scene& scene, const SceneOverrides& o) {
  if (!o.size.empty()) {
    static const std::regex sizeRe(R"((\d{1,9})x(\d{1,9}))");
    std::smatch m;
    if (!std::regex_match(o.size, m, sizeRe))
      throw CommandLineError("--size", "", "expected WxH, e.g. 800x600, got " + quote(o.size));
    const int w = std::stoi(m[1]), h = std::stoi(m[2]);
    if (w < 1 || h < 1 || w > 16384 || h > 16384)
      throw CommandLineError("--size", "", "width and height must be in [1, 16384]");
    scene.width = w;
    scene.height = h;
  }
  Camera& c = scene.camera;
  for (const auto& [option, p] : {std::pair{"--eye", o.eye}, std::pair{"--target", o.target}})
    if (p && !(sceneReach(*p) <= kMaxSceneReach))
      throw CommandLineError(
          option, "", "beyond 1e15 scene units from the origin (32-bit floats cannot render it)");
  if (o.eye) c.eye = *o.eye;
  if (o.target) c.target = *o.target;
  if ((o.eye || o.target) && !o.fit) c.fit = false;
  if (o.eye || o.target || o.fit) c.path.clear();  // an explicit camera replaces the path
  if (o.fit) c.fit = true;
  if (o.up) {  // any length, as in a scene file
    const std::optional<glm::vec3> unit = unitVector(glm::dvec3(*o.up));
    if (!unit) throw CommandLineError("--up", "", "up must not be the zero vector");
    c.up = *unit;
  }
  if (o.fov) c.fovY = *o.fov;
  if (!o.projection.empty()) {
    const Projection to =
        o.projection == "orthographic" ? Projection::Orthographic : Projection::Perspective;
    // The view keeps its height at the target (a path's first key), as the viewer's P does;
    // a fitted camera is framed again for the new projection.
    if (!c.fit && c.projection != to) {
      Camera at = c;
      if (!c.path.empty()) at.eye = c.path.front().eye, at.target = c.path.front().target;
      at.setProjection(to);
      c.height = at.height;
      if (c.path.empty()) c.eye = at.eye;
    }
    c.projection = to;
  }
  const glm::dvec3 along = glm::dvec3(c.eye) - glm::dvec3(c.target);
  // A fitted camera whose eye and target coincide takes a default direction
  // (Scene::resolvedCamera).
  const bool fitsDefault = c.fit && !(glm::length(along) > 0.0);
  if (!(glm::length(along) > 0.0) && !fitsDefault)
    throw CommandLineError("--eye", "", "eye and target coincide");
  if (!fitsDefault && glm::length(glm::cross(glm::normalize(along), glm::dvec3(c.up))) < 1e-6) {
    if (o.up) throw CommandLineError("--up", "", "up is parallel to the viewing direction");
    char up[96];
    std::snprintf(up, sizeof up, "%g,%g,%g", double(c.up.x), double(c.up.y), double(c.up.z));
    throw CommandLineError(
        o.eye ? "--eye" : "--target", "",
        std::string("the viewing direction is parallel to the scene's up vector (") + up +
            "); give --up too");
  }
  if (!o.style.empty()) scene.style.name = o.style;
  if (o.shadows) scene.style.shadows.enabled = true;
  if (o.samples) scene.samples = *o.samples;
  if (o.pixelError) scene.pixelError = *o.pixelError;
  if (o.simplify) {
    SimplifiedCache versions;
    addSimplifiedVersions(scene, versions);
  }
  if (o.noCutaway && o.cutawayAngle)
    throw CommandLineError("--no-cutaway", "", "cannot be combined with --cutaway-angle");
  if (o.noCutaway) scene.cutters.clear();  // the plain model: no cutter at all
  if (o.cutawayAngle) scene.cutters.enable<AdaptiveCutawayOptions>().angle = *o.cutawayAngle;
  // --importance PATTERN=V, in the order given (Burns11 §3.2).
  for (const std::string& assignment : o.importance) {
    const auto equals = assignment.rfind('=');
    double v = 0;
    const std::string value = equals == std::string::npos ? "" : assignment.substr(equals + 1);
    const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
    if (equals == std::string::npos || equals == 0 || ec != std::errc() || end != value.data() + value.size())
      throw CommandLineError("--importance", assignment,
                             "expected PATTERN=V with V a number, e.g. 'pistons=0.9'");
    try {
      scene.setImportance(assignment.substr(0, equals), float(v));
    } catch (const Error& e) {
      throw CommandLineError("--importance", e.file(), e.reason());
    }
  }
  // --set PATH=VALUE, in the order given: any technique's option by its scene-file path. A
  // path set twice to different values, or one an option of its own also sets, is at odds.
  std::map<std::string, std::string> given;
  for (const std::string& assignment : o.set) {
    const auto equals = assignment.find('=');
    if (equals == std::string::npos || equals == 0)
      throw CommandLineError("--set", assignment,
                             "expected PATH=VALUE, e.g. cutters.adaptive.angle=30");
    const std::string path = assignment.substr(0, equals), value = assignment.substr(equals + 1);
    if (const auto [at, fresh] = given.emplace(path, value); !fresh && at->second != value)
      throw CommandLineError("--set", path,
                             "given twice, as " + quote(at->second) + " and " + quote(value));
    const auto atOdds = [&](bool flag, const char* option, bool clash) {
      if (flag && clash)
        throw CommandLineError("--set", path, std::string("at odds with ") + option);
    };
    atOdds(!o.style.empty(), "--style", path == "style.name");
    atOdds(o.shadows, "--shadows", path == "style.shadows");
    atOdds(o.cutawayAngle.has_value(), "--cutaway-angle",
           path == "cutters.adaptive" || path == "cutters.adaptive.angle");
    atOdds(o.noCutaway, "--no-cutaway", path.rfind("cutters.", 0) == 0);
    try {
      setOption(scene, assignment.substr(0, equals), assignment.substr(equals + 1));
    } catch (const Error& e) {
      throw CommandLineError("--set", e.file(), e.reason());
    }
  }
  // What the options set now make of the scene, checked as a scene file would be; the place
  // named as --set names options (cutters.adaptive.contextual, not its JSON pointer).
  if (!o.set.empty() || o.cutawayAngle) {
    const char* given = o.set.empty()    ? "--cutaway-angle"
                        : o.cutawayAngle ? "--set and --cutaway-angle"
                                         : "--set";
    try {
      checkScene(scene, given);
    } catch (const Error& e) {
      std::string path = e.place();
      if (path.rfind('/', 0) == 0)
        path.erase(0, 1), std::replace(path.begin(), path.end(), '/', '.');
      throw CommandLineError(e.file(), path, e.reason());
    }
  }
}

// The renderer says a device limit at the scene's key (/samples, /resolution); where an option
// set that key, the error names the option (a value the command refuses: exit 2).
template <class Run>
auto blamingOverrides(const SceneOverrides& o, const Scene& scene, Run&& run) {
  try {
    return run();
  } catch (const Error& e) {
    const std::string size = std::to_string(scene.width) + "×" + std::to_string(scene.height);
    if (e.place() == "/samples" && o.samples) throw CommandLineError("--samples", "", e.reason());
    // The render targets' size: a matter of both; the option given is blamed.
    if (e.place() == "/resolution" && (!o.size.empty() || o.samples) &&
        e.reason().rfind(size, 0) == 0)
      throw CommandLineError(!o.size.empty() ? "--size" : "--samples", "", e.reason());
    throw;
  }
}

// Floats as the shortest decimals that read back as them.
nlohmann::json real(float f) {
  return shortestDecimal(f);
}
nlohmann::json vec(const glm::vec3& v) {
  return {real(v.x), real(v.y), real(v.z)};
}
nlohmann::json boundsJson(const Bounds& b) {
  return {{"min", vec(b.min)}, {"max", vec(b.max)}};
}

struct Stats {
  double median, min, max;
};
Stats stats(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  const double median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return {median, v.front(), v.back()};
}

// The scene file, or Konev18's generated benchmark city at `city` times its size.
Scene sceneOrCity(const std::string& file, int city, const char* command) {
  if (city == 0 && file.empty())
    throw CommandLineError(command, "", "give a scene file or --city SCALE");
  return city > 0 ? benchmarkCity({.scale = city}) : loadScene(file);
}

}  // namespace

// An animation's AOV folder for frame `index` (from 1): DIR/0001 …
std::string aovFrameFolder(const std::string& dir, int index) {
  char number[16];
  std::snprintf(number, sizeof number, "%04d", index);
  return (std::filesystem::path(dir) / number).string();
}

// The file name of frame `index` (1-based): a printf pattern in `output`, or the number
// appended to its stem ("out.png" → "out_0001.png").
std::string framePath(const std::string& output, int index) {
  if (output.find('%') != std::string::npos) {
    char buffer[4096];
    std::snprintf(buffer, sizeof buffer, output.c_str(), index);
    return buffer;
  }
  std::filesystem::path p(output);
  char number[16];
  std::snprintf(number, sizeof number, "_%04d", index);
  return (p.parent_path() / (p.stem().string() + number + p.extension().string())).string();
}

// Diepstraten03 rule 5 needs solids: a cut through an open exterior shows its inside, not a
// wall. Said once, so an illustrator knows why no wall appears and how to choose.
void warnAboutOpenExteriors(const Scene& scene) {
  if (!scene.cutters.find<CutoutOptions>() && !scene.cutters.find<BreakawayOptions>()) return;
  for (const auto& o : scene.objects)
    if (o.role == Role::Exterior && !o.proxy && !o.mesh->report.watertight &&
        !o.params.count("solid"))
      std::fprintf(stderr,
                   "warning: %s: exterior \"%s\" is not watertight; its cut shows the inside "
                   "instead of a cut wall (set its param \"solid\" to choose)\n",
                   scene.file.string().c_str(), o.name.c_str());
}

// Trapp13 §5: parity is undefined for open meshes, so their cuts get no caps; say which.
void warnAboutUncappedObjects(const Scene& scene) {
  const auto* clip = scene.cutters.find<ClipSurfaceOptions>();
  if (!clip || !clip->caps) return;
  std::vector<std::string> open;
  for (const auto& o : scene.objects)
    if (!o.proxy && o.role != Role::Interest && !o.mesh->report.watertight) open.push_back(o.name);
  if (open.empty()) return;
  std::string names;
  for (std::size_t i = 0; i < std::min<std::size_t>(open.size(), 3); ++i)
    names += (i ? ", \"" : "\"") + open[i] + "\"";
  if (open.size() > 3) names += " and " + std::to_string(open.size() - 3) + " more";
  std::fprintf(stderr,
               "warning: %s: %zu clipped object%s not watertight, so %s cut%s no cap (parity "
               "is undefined for open meshes): %s\n",
               scene.file.string().c_str(), open.size(), open.size() == 1 ? " is" : "s are",
               open.size() == 1 ? "its" : "their", open.size() == 1 ? " gets" : "s get",
               names.c_str());
}

// The GPU works in 32-bit floats: far from the origin they step by centimetres or more, and a
// camera placed near the origin sees nothing. GIS data in projected coordinates (British
// National Grid, UTM: 10⁵–10⁶ m) needs the geo frame's offset. Warned beyond 1e5, or where a
// step is over a thousandth of a thing's bounding radius (its shading and lines speckle);
// names the thing where it is worst.
void warnAboutFarCoordinates(const Scene& scene) {
  std::string name;
  Bounds farthest;
  float reach = 0.0f, worst = 0.0f;
  const auto consider = [&](const std::string& what, const Bounds& b) {
    if (b.empty()) return;
    const glm::vec3 c = glm::abs(b.center());
    const float at = std::max({c.x, c.y, c.z}), step = std::nextafter(at, 2 * at) - at;
    const float score = std::max(at / 1e5f, b.radius() > 0.0f ? step / (1e-3f * b.radius()) : 0.0f);
    if (score > 1.0f && score > worst) worst = score, reach = at, name = what, farthest = b;
  };
  for (const auto& n : scene.networks) consider(n.name, n.bounds());
  for (const auto& v : scene.volumes) consider(v.name, v.worldBounds());
  for (const auto& o : scene.objects)
    if (!o.proxy && o.networkPart == NetworkPart::None) consider(o.name, o.worldBounds());
  if (name.empty()) return;
  const glm::dvec3 at = glm::dvec3(GeoFrame::fromScene(farthest.center())) + scene.geo.offset;
  std::fprintf(stderr,
               "warning: %s: \"%s\" lies %.3g scene units from the origin, where floats step by "
               "%.2g (its bounding radius is %.3g); move it nearer (GIS data: a \"geo\" offset "
               "near its coordinates, about [%.0f, %.0f])\n",
               scene.file.string().c_str(), name.c_str(), double(reach),
               double(std::nextafter(reach, 2 * reach) - reach), double(farthest.radius()), at.x,
               at.y);
}

// A file to be written: its folder exists and may be written to.
void checkFolderOf(const std::string& file) {
  const std::filesystem::path folder = std::filesystem::path(file).has_parent_path()
                                           ? std::filesystem::path(file).parent_path()
                                           : ".";
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec))
    throw Error(file, "", (std::filesystem::exists(folder, ec) ? "not a folder: " : "no such folder: ") +
                              folder.string());
  if (::access(folder.c_str(), W_OK) != 0) throw Error(file, "", "the folder is not writable");
}

// The outputs checked before anything is rendered, so that a bad one leaves no file behind:
// a PNG name (no other format is written) and an SVG name in folders that take them, an AOV
// folder that is one or can be made (writeAovs makes it with a frame's AOVs, so that a run
// stopped before leaves no empty one).
void checkOutputs(const RenderOptions& options) {
  const std::filesystem::path out(options.output);
  if (options.output.empty()) throw CommandLineError("--output", "", "the file name is empty");
  std::error_code ec;
  if (std::filesystem::is_directory(out, ec))
    throw Error(options.output, "", "is a directory, not a file name");
  if (!isPngName(out))
    throw CommandLineError(options.output, "", "only PNG is written: give the output a .png name");
  // An animation's names are patterns, whose folders are checked frame by frame.
  if (options.frames == 0) checkFolderOf(options.output);
  // One path for two outputs: the later would take the earlier's place.
  const auto same = [](const std::string& a, const std::string& b) {
    const auto resolved = [](const std::string& p) {
      std::error_code ec;
      std::filesystem::path r = std::filesystem::weakly_canonical(std::filesystem::absolute(p), ec);
      return r.has_filename() ? r : r.parent_path();  // "out.png/" as "out.png"
    };
    return !a.empty() && !b.empty() && resolved(a) == resolved(b);
  };
  if (same(options.output, options.aovDir) || same(options.svg, options.aovDir))
    throw CommandLineError(options.aovDir, "", "--aov names the folder of a file written too");
  if (same(options.output, options.svg))
    throw CommandLineError(options.svg, "", "--svg and --output name the same file");
  if (!options.svg.empty()) {
    std::string svgExt = std::filesystem::path(options.svg).extension().string();
    for (char& c : svgExt) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (svgExt != ".svg")
      throw CommandLineError(options.svg, "", "--svg writes SVG: give it a .svg name");
    if (std::filesystem::is_directory(options.svg, ec))
      throw Error(options.svg, "", "is a directory, not a file name");
    if (options.frames == 0) checkFolderOf(options.svg);
  }
  if (options.aovDir.empty()) return;
  std::filesystem::path dir = std::filesystem::path(options.aovDir).lexically_normal();
  if (!dir.has_filename()) dir = dir.parent_path();  // "frames/aovs/"
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
    throw Error(options.aovDir, "", "--aov needs a directory; this is a file");
  std::filesystem::path existing = dir;  // the folder it is, or the nearest it would be made in
  while (!std::filesystem::exists(std::filesystem::status(existing, ec))) {
    if (ec && ec != std::errc::no_such_file_or_directory)
      throw Error(options.aovDir, "", "cannot create the AOV directory: " + ec.message());
    const std::filesystem::path parent =
        existing.has_parent_path() ? existing.parent_path() : std::filesystem::path(".");
    if (parent == existing) break;
    existing = parent;
  }
  if (!std::filesystem::is_directory(existing, ec))
    throw Error(options.aovDir, "",
                "cannot create the AOV directory: " + existing.string() + " is a file");
  if (::access(existing.c_str(), W_OK) != 0)
    throw Error(options.aovDir, "",
                existing == dir
                    ? "the AOV directory is not writable"
                    : "cannot create the AOV directory: " + existing.string() + " is not writable");
}

namespace {

// An animation written whole or not at all (render --frames): each frame's outputs that exist
// already are moved aside (NAME.old-PID) before the frame is written; if a frame fails, undo()
// takes back every output of the run and puts the moved ones back; commit() removes them,
// keeping in each AOV folder the files its index did not list (as writeAovs keeps them). An
// output reached through a symbolic link is the file or folder the link points to.
class SequenceOutputs {
 public:
  // The AOV folder and those above it that the frames' writers will make, innermost first.
  explicit SequenceOutputs(const std::string& aovDir) {
    std::error_code ec;
    if (!aovDir.empty())
      for (std::filesystem::path dir = std::filesystem::path(aovDir).lexically_normal();
           !dir.empty() && !std::filesystem::exists(std::filesystem::symlink_status(dir, ec));
           dir = dir.parent_path())
        if (dir.has_filename()) madeFolders_.push_back(dir);
  }

  void prepare(const std::string& given) {
    if (given.empty()) return;
    std::error_code ec;
    const bool link = std::filesystem::is_symlink(given, ec);
    const std::filesystem::path path =
        link ? std::filesystem::weakly_canonical(given, ec) : std::filesystem::path(given);
    if (std::filesystem::exists(std::filesystem::symlink_status(path, ec))) {
      const bool folder = std::filesystem::is_directory(path, ec);
      std::filesystem::rename(path, aside(path), ec);
      if (ec) throw Error(path.string(), "", "cannot move the earlier file aside: " + ec.message());
      moved_.push_back(path);
      if (link && folder) std::filesystem::create_directory(path, ec);  // the link leads on
    }
    written_.push_back(path);
  }

  void undo() const {
    std::error_code ignored;
    for (const auto& path : written_) std::filesystem::remove_all(path, ignored);
    for (const auto& path : moved_) std::filesystem::rename(aside(path), path, ignored);
    for (const auto& dir : madeFolders_) std::filesystem::remove(dir, ignored);  // where empty
  }

  void commit() const {
    std::error_code ec;
    for (const auto& path : moved_) {
      const std::filesystem::path old = aside(path);
      if (std::filesystem::is_directory(old, ec) && std::filesystem::is_directory(path, ec)) {
        const std::vector<std::filesystem::path> listed = indexedAovFiles(old);
        for (const auto& entry : std::filesystem::directory_iterator(old, ec)) {
          const std::filesystem::path name = entry.path().filename();
          if (name == "aovs.json" || std::filesystem::exists(path / name, ec) ||
              std::find(listed.begin(), listed.end(), old / name) != listed.end())
            continue;
          std::filesystem::rename(entry.path(), path / name, ec);
        }
      }
      std::filesystem::remove_all(old, ec);
    }
  }

 private:
  static std::filesystem::path aside(const std::filesystem::path& path) {
    return path.string() + ".old-" + std::to_string(::getpid());
  }
  std::vector<std::filesystem::path> written_, moved_, madeFolders_;
};

}  // namespace

int render(const RenderOptions& options) {
  checkOutputs(options);
  Scene scene = sceneOrCity(options.scene, options.city, "render");
  applyOverrides(scene, options.overrides);
  warnAboutFarCoordinates(scene);
  warnAboutOpenExteriors(scene);
  warnAboutUncappedObjects(scene);
  // A frame pattern is a printf format: nothing but one %d in it, and %% for a '%'.
  for (const auto& [option, path] :
       {std::pair{"--output", &options.output}, std::pair{"--svg", &options.svg}}) {
    static const std::regex patternRe(R"((?:[^%]|%%)*%0?\d{0,2}d(?:[^%]|%%)*)");
    if (options.frames > 0 && path->find('%') != std::string::npos &&
        !std::regex_match(*path, patternRe))
      throw CommandLineError(
          option, "",
          "with --frames, a name with a % is a frame pattern: it holds exactly one %d, of "
          "width at most 99 (e.g. frame_%04d.png), and %% for each percent sign");
  }
  // An animation's outputs that something else holds fail before the first frame is written.
  std::error_code ec;
  for (int i = 1; i <= options.frames; ++i) {
    for (const std::string* pattern : {&options.output, &options.svg}) {
      if (pattern->empty()) continue;
      if (std::filesystem::is_directory(framePath(*pattern, i), ec))
        throw Error(framePath(*pattern, i), "", "is a directory, not a file name");
      checkFolderOf(framePath(*pattern, i));
    }
    if (options.aovDir.empty()) continue;
    const std::string folder = aovFrameFolder(options.aovDir, i);
    if (std::filesystem::exists(folder, ec) && !std::filesystem::is_directory(folder, ec))
      throw Error(folder, "", "--aov needs a directory for each frame; this is a file");
  }
  // Every frame's camera before the first is written: an animation stops half-written else.
  const float aspect = float(scene.width) / float(scene.height);
  const float duration = scene.duration();
  const auto frameTime = [&](int i) {
    return options.frames > 1 ? duration * float(i) / float(options.frames - 1) : 0.0f;
  };
  for (int i = 0; i < std::max(options.frames, 1); ++i) {
    const float time = options.frames == 0 ? options.time : frameTime(i);
    if (const std::string why =
            scene.resolvedCamera(time).unresolvable(aspect, deepestDepthRange(scene));
        !why.empty()) {
      char at[32];
      std::snprintf(at, sizeof at, "%.4g s", double(time));
      const std::string reason =
          "at " + (options.frames > 0 ? "frame " + std::to_string(i + 1) + ", " : "") + at + ": " +
          why;
      // A camera the options placed: they are blamed (exit 2), not the scene file.
      const SceneOverrides& o = options.overrides;
      if (o.eye || o.target)
        throw CommandLineError(o.eye && o.target ? "--eye and --target"
                               : o.eye           ? "--eye"
                                                 : "--target",
                               "", reason);
      throw Error(scene.file.string(), "/camera", reason);
    }
  }
  if (!options.svg.empty() &&
      std::none_of(scene.volumes.begin(), scene.volumes.end(),
                   [](const SceneVolume& v) { return v.lines.has_value(); }))
    throw CommandLineError(
        "--svg", "",
        "writes the volumes' lines, and no volume of " + scene.file.string() + " has \"lines\"");
  const auto context = gl::HeadlessContext::create();
  Renderer renderer =
      blamingOverrides(options.overrides, scene, [&] { return Renderer(scene, context->info()); });
  auto renderOne = [&](float time, const std::string& out, const std::string& aovDir,
                       const std::string& svg) {
    const Camera camera = scene.resolvedCamera(time);
    renderer.render(camera, time);
    const Rgba8Image color = renderer.readColor();
    if (aovDir.empty())
      writePng(out, color);
    else  // the picture and its AOVs, all or none
      writeAovs(aovDir, renderer.readAovs(), camera, aspect,
                {{out, [&](std::ostream& os) { writePng(os, color, out); }}});
    if (!svg.empty()) writeVolumeLineSvg(svg, renderer.volumeLineDrawing());
  };
  if (options.frames == 0) {
    renderOne(options.time, options.output, options.aovDir, options.svg);
    std::printf("wrote %s (%dx%d, %s, %s)\n", options.output.c_str(), scene.width, scene.height,
                scene.style.name.c_str(), context->info().renderer.c_str());
    if (!options.svg.empty()) std::printf("wrote %s\n", options.svg.c_str());
    if (!options.aovDir.empty())
      std::printf("wrote AOVs to %s (see aovs.json)\n", options.aovDir.c_str());
    return 0;
  }
  SequenceOutputs outputs(options.aovDir);
  const bool progress = ::isatty(STDERR_FILENO);
  for (int i = 0; i < options.frames; ++i) {
    const float time = frameTime(i);
    const std::string aovDir = options.aovDir.empty() ? "" : aovFrameFolder(options.aovDir, i + 1);
    const std::string out = framePath(options.output, i + 1),
                      svg = options.svg.empty() ? "" : framePath(options.svg, i + 1);
    try {
      for (const std::string& path : {out, svg, aovDir}) outputs.prepare(path);
      renderOne(time, out, aovDir, svg);
    } catch (const Error& e) {
      outputs.undo();
      const std::string reason = "frame " + std::to_string(i + 1) + " of " +
                                 std::to_string(options.frames) +
                                 " (no frame written): " + e.reason();
      if (dynamic_cast<const CommandLineError*>(&e))
        throw CommandLineError(e.file(), e.place(), reason);
      throw Error(e.file(), e.place(), reason);
    } catch (...) {
      outputs.undo();
      throw;
    }
    if (progress) {
      const int width = 30, done = (i + 1) * width / options.frames;
      std::fprintf(
          stderr, "\r[%s%s] %d/%d  t = %.2f s", std::string(std::size_t(done), '#').c_str(),
          std::string(std::size_t(width - done), ' ').c_str(), i + 1, options.frames, time);
      std::fflush(stderr);
    }
  }
  outputs.commit();
  if (progress) std::fprintf(stderr, "\n");
  if (options.frames == 1)
    std::printf("wrote 1 frame %s (%dx%d)\n", framePath(options.output, 1).c_str(), scene.width,
                scene.height);
  else
    std::printf("wrote %d frames %s … %s (%dx%d, %.2f s of animation)\n", options.frames,
                framePath(options.output, 1).c_str(),
                framePath(options.output, options.frames).c_str(), scene.width, scene.height,
                duration);
  return 0;
}

namespace {

nlohmann::json crsJson(const GisCrs& crs) {
  if (!crs.known()) return nullptr;
  return {{"name", crs.name}, {"authority", crs.authority}};
}

int gisInfo(const std::string& path) {
  nlohmann::json out = {{"file", path}};
  if (isRaster(path)) {
    const RasterInfo r = describeRaster(path);
    out["raster"] = {{"driver", r.driver},
                     {"size", {r.width, r.height}},
                     {"bands", r.bands},
                     {"dataType", r.dataType},
                     {"crs", crsJson(r.crs)},
                     {"geoTransform", r.geoTransform ? nlohmann::json(*r.geoTransform) : nullptr},
                     {"nodata", r.nodata ? nlohmann::json(*r.nodata) : nullptr},
                     {"min", r.minimum ? nlohmann::json(*r.minimum) : nullptr},
                     {"max", r.maximum ? nlohmann::json(*r.maximum) : nullptr}};
    if (r.geoTransform) {
      const auto& g = *r.geoTransform;
      if (g[2] == 0.0 && g[4] == 0.0)
        out["raster"]["extent"] = {
            std::min(g[0], g[0] + r.width * g[1]), std::min(g[3], g[3] + r.height * g[5]),
            std::max(g[0], g[0] + r.width * g[1]), std::max(g[3], g[3] + r.height * g[5])};
    }
  } else {
    nlohmann::json layers = nlohmann::json::array();
    for (const GisLayerInfo& l : listGisLayers(path))
      layers.push_back({{"name", l.name},
                        {"geometryType", l.geometryType},
                        {"features", l.featureCount},
                        {"crs", crsJson(l.crs)},
                        {"extent", l.extent ? nlohmann::json({l.extent->min.x, l.extent->min.y,
                                                              l.extent->max.x, l.extent->max.y})
                                            : nlohmann::json(nullptr)},
                        {"fields", l.fields},
                        {"fieldTypes", l.fieldTypes}});
    out["layers"] = layers;
  }
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}

}  // namespace

int dem(const DemOptions& o) {
  if (o.extent.size() != 4)
    throw CommandLineError("--extent", "", "expected west south east north");
  for (const double v : o.extent)
    if (!std::isfinite(v))
      throw CommandLineError("--extent", "", "west, south, east and north must be finite numbers");
  std::string ext = std::filesystem::path(o.output).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".tif" && ext != ".tiff")
    throw CommandLineError(o.output, "", "dem writes a GeoTIFF: give the output a .tif name");
  // Float32 heights: base … base + relief must be floats, or the file holds infinities.
  const auto fits = [](double h) {
    return std::abs(h) <= double(std::numeric_limits<float>::max());
  };
  if (!fits(o.base))
    throw CommandLineError("--base", "", "the base height must fit in Float32 (|h| ≤ 3.4e38)");
  if (!fits(o.base + o.relief))
    throw CommandLineError(
        "--relief", "",
        "heights from --base to --base + --relief must fit in Float32 (|h| ≤ 3.4e38)");
  try {
    writeSyntheticDem(o.output, {.min = {o.extent[0], o.extent[1]},
                                 .max = {o.extent[2], o.extent[3]},
                                 .crs = o.crs,
                                 .cell = o.cell,
                                 .base = o.base,
                                 .relief = o.relief,
                                 .wavelength = o.wavelength,
                                 .octaves = o.octaves,
                                 .seed = o.seed});
  } catch (const Error& e) {
    // The CRS and the extent are command-line values: named by their options, exit 2.
    if (e.place() == "crs") throw CommandLineError("--crs", "", e.reason());
    if (e.place() == "extent") throw CommandLineError("--extent", "", e.reason());
    if (e.place() == "cell") throw CommandLineError("--cell", "", e.reason());
    throw;
  }
  const RasterInfo r = describeRaster(o.output);
  std::printf("wrote %s (%dx%d Float32, %s, heights %.2f to %.2f)\n", o.output.c_str(), r.width,
              r.height, r.crs.authority.empty() ? r.crs.name.c_str() : r.crs.authority.c_str(),
              r.minimum.value_or(0.0), r.maximum.value_or(0.0));
  return 0;
}

int info(const std::string& path) {
  if (path.empty())
    throw CommandLineError("info", "", "give a scene file, or a GIS file or raster");
  // Scenes are JSON; anything else is GIS data for GDAL to recognise (or reject clearly).
  if (std::filesystem::path(path).extension() != ".json") return gisInfo(path);
  const Scene scene = loadScene(path);
  nlohmann::json objects = nlohmann::json::array();
  std::size_t triangles = 0;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    const MeshReport& r = o.mesh->report;
    triangles += o.proxy ? 0 : o.mesh->triangleCount();
    nlohmann::json params = nlohmann::json::object();
    for (const auto& param : o.params)
      std::visit([&](auto value) { params[param.first] = value; }, param.second);
    objects.push_back({{"index", i},
                       {"name", o.name},
                       {"alias", o.alias},
                       {"source", o.source},
                       {"group", o.group},
                       {"role", roleName(o.role)},
                       {"importance", real(o.importance)},
                       {"proxy", o.proxy},
                       {"params", params},
                       {"triangles", o.mesh->triangleCount()},
                       {"vertices", o.mesh->positions.size()},
                       {"bounds", boundsJson(o.worldBounds())},
                       {"watertight", r.watertight},
                       {"boundaryEdges", r.boundaryEdges},
                       {"nonManifoldEdges", r.nonManifoldEdges},
                       {"misorientedEdges", r.misorientedEdges},
                       {"windingReversed", r.windingReversed},
                       {"droppedDegenerateTriangles", r.droppedDegenerate},
                       {"normalsComputed", r.normalsComputed}});
  }
  const Camera c = scene.resolvedCamera();
  // The style and the cutters with every option as the scene format writes them (their schemas:
  // a scene file reads them back), and under "resolved" what the cutters make of the scene.
  nlohmann::json out = {{"scene", path},
                        {"resolution", {scene.width, scene.height}},
                        {"style", nlohmann::json(styleJson(scene.style))},
                        {"triangles", triangles},
                        {"bounds", boundsJson(scene.bounds())},
                        {"camera",
                         {{"eye", vec(c.eye)},
                          {"target", vec(c.target)},
                          {"near", real(c.near)},
                          {"far", real(c.far)}}},
                        {"duration", real(scene.duration())},
                        {"objects", objects}};
  if (!scene.cutters.empty()) out["cutters"] = nlohmann::json(cuttersJson(scene));
  // Diepstraten03 §4.2: each exterior unit's main axis (hull-surface covariance).
  for (const auto& unit : exteriorUnits(scene)) {
    const PrincipalAxes& a = unit.axes;
    nlohmann::json members = nlohmann::json::array();
    for (const std::size_t i : unit.objects) members.push_back(scene.objects[i].name);
    nlohmann::json volumes = nlohmann::json::array();
    for (const std::size_t i : unit.volumes) volumes.push_back(scene.volumes[i].name);
    out["exteriors"].push_back(
        {{"name", unit.name},
         {"objects", members},
         {"volumes", volumes},
         {"centre", vec(a.center)},
         {"mainAxis", vec(a.axes[0])},
         {"axes", {vec(a.axes[0]), vec(a.axes[1]), vec(a.axes[2])}},
         {"eigenvalues", {real(a.eigenvalues[0]), real(a.eigenvalues[1]), real(a.eigenvalues[2])}},
         {"extentAlongMainAxis", {real(a.extentMin), real(a.extentMax)}}});
  }
  if (const auto* c = scene.cutters.find<CutoutOptions>())
    out["resolved"]["cutout"]["planes"] = c->axialRange ? 4 : 2;
  if (const auto* c = scene.cutters.find<ClipSurfaceOptions>()) {
    nlohmann::json& resolved = out["resolved"]["clipSurfaces"];
    for (const ClipSurface& cs : c->surfaces)
      resolved["surfaces"].push_back(
          {{"normal", vec(cs.normal())},
           {"offsetMapSize", {cs.offsetMap.width, cs.offsetMap.height}}});
    nlohmann::json capped = nlohmann::json::array(), uncapped = nlohmann::json::array();
    for (const auto& o : scene.objects)
      if (!o.proxy && o.role != Role::Interest)
        (o.mesh->report.watertight ? capped : uncapped).push_back(o.name);
    resolved["capped"] = c->caps ? capped : nlohmann::json::array();
    resolved["notCappedOpenMeshes"] = c->caps ? uncapped : nlohmann::json::array();
  }
  if (const auto* t = scene.cutters.find<TerrainOpeningOptions>()) {
    std::size_t nodes = 0;
    for (const auto& line : t->lines) nodes += line.size();
    out["resolved"]["terrainOpening"] = {{"polylines", t->lines.size()}, {"nodes", nodes}};
  }
  // Konev18 §§5–7: what each network holds after splitting at sharp bends and trimming
  // crossing cuts (§9).
  for (const PipeNetwork& net : scene.networks) {
    std::size_t nodes = 0, cut = 0;
    float length = 0.0f, cutLength = 0.0f;
    float rMin = std::numeric_limits<float>::max(), rMax = 0.0f;
    for (const Pipe& p : net.pipes) {
      nodes += p.nodes.size();
      length += p.length();
      rMin = std::min(rMin, p.radius), rMax = std::max(rMax, p.radius);
      if (p.cut) ++cut, cutLength += p.cut->y - p.cut->x;
    }
    out["networks"].push_back(
        {{"name", net.name},
         {"mode", net.mode == PipeNetwork::Mode::Billboards ? "billboards" : "mesh"},
         {"pipes", net.pipes.size()},
         {"nodes", nodes},
         {"length", real(length)},
         {"radius", {real(rMin), real(rMax)}},
         {"radiusScale", real(net.radiusScale)},
         {"cutPipes", cut},
         {"cutLength", real(cutLength)},
         {"shafts", net.shafts.size()},
         {"bounds", boundsJson(net.bounds())}});
  }
  for (const SceneVolume& v : scene.volumes) {
    const Volume& data = *v.volume;
    std::size_t transferPoints = 0;
    for (const TransferFunction::Row& row : v.transfer.rows) transferPoints += row.points.size();
    out["volumes"].push_back({{"name", v.name},
                              {"file", v.source},
                              {"dims", {data.dims.x, data.dims.y, data.dims.z}},
                              {"voxelType", data.voxelType},
                              {"spacing", vec(data.spacing())},
                              {"range", {real(data.minValue), real(data.maxValue)}},
                              {"role", roleName(v.role)},
                              {"mode", volumeModeName(v.mode)},
                              {"transferPoints", transferPoints},
                              {"transferRows", v.transfer.rows.size()},
                              {"bounds", boundsJson(v.worldBounds())}});
  }
  if (const auto* b = scene.cutters.find<BreakawayOptions>()) {
    const BreakawayExtent extent = breakawayExtent(scene, *b);
    nlohmann::json clusters = nlohmann::json::array();
    for (const auto& c : breakawayClusters(scene, *b))
      clusters.push_back({{"group", c.group},
                          {"objects", c.objects.size()},
                          {"hullTriangles", c.outerHull.triangles.size()}});
    // The offset and wall thickness resolved (the scene's, or from the scene's size).
    out["resolved"]["breakaway"] = {{"offset", real(extent.offset)},
                                    {"wallThickness", real(extent.wallThickness)},
                                    {"clusters", clusters}};
  }
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}

namespace {

struct PassStats {
  std::string name;
  Stats gpu, cpu;
};

struct Measurement {
  std::string label;
  const char* computePath = nullptr;  // adaptive cutter: "gpu" / "cpu"
  std::vector<PassStats> passes;
  Stats frame;
  // GPU (or CPU, for the CPU path) time of the cutaway-surface computation alone.
  double cutawaySurfaceMs = 0;
  std::size_t plain = 0;  // index of the run it is compared with
  std::size_t triangles = 0;  // of the scene's meshes, as drawn (at their selected detail)
  std::size_t culled = 0;     // objects the last frame found hidden and did not draw
  std::size_t peeled = 0;     // translucent-layer draws of objects already peeled, left out
};

// How every run of one bench invocation renders.
struct Timing {
  const gl::HeadlessContext& context;  // the run's
  int frames;
  bool occlusionCulling;
};

// A context of a row's own, current while it lives; the run's context is current again after.
// A row then starts as a `render` run does, and what the rasteriser keeps from a context's
// frames (its binned scenes, its buffers at the last size) neither carries into the next row's
// times nor piles up in the run's peak memory (bench/RESULTS.md, tenth session).
class RowContext {
 public:
  explicit RowContext(const gl::HeadlessContext& run) : run_(run) {}
  ~RowContext() {
    own_.reset();
    try {
      run_.makeCurrent();
    } catch (const Error& e) {  // a destructor must not throw; what follows then fails on GL
      std::fprintf(stderr, "cutaway bench: %s\n", e.what());
    }
  }
  RowContext(const RowContext&) = delete;
  RowContext& operator=(const RowContext&) = delete;
  const gl::ContextInfo& info() const { return own_->info(); }

 private:
  const gl::HeadlessContext& run_;
  std::unique_ptr<gl::HeadlessContext> own_ = gl::HeadlessContext::create();
};

// Renders `frames` frames (after a warm-up) and gathers per-pass and whole-frame times.
Measurement measure(const std::string& label, const Scene& scene, const Timing& timing) {
  const RowContext context(timing.context);
  Renderer renderer(scene, context.info());
  renderer.setOcclusionCulling(timing.occlusionCulling);
  const int frames = timing.frames;
  const Camera camera = scene.resolvedCamera();
  renderer.render(camera);  // warm-up: shader compilation, first allocation
  glFinish();
  (void)renderer.timings();
  std::vector<std::string> order;
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> times;
  std::vector<double> frameTimes;
  for (int i = 0; i < frames; ++i) {
    const auto start = std::chrono::steady_clock::now();
    renderer.render(camera);
    glFinish();
    frameTimes.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
    for (const auto& t : renderer.timings()) {
      if (!times.count(t.name)) order.push_back(t.name);
      times[t.name].first.push_back(t.gpuMs);
      times[t.name].second.push_back(t.cpuMs);
    }
  }
  Measurement m{label, renderer.cutawayComputePath(), {}, stats(frameTimes)};
  m.triangles = renderer.meshTriangles();
  m.culled = renderer.culledObjects();
  m.peeled = renderer.peeledLayerDraws();
  for (const auto& name : order) {
    PassStats p{name, stats(times[name].first), stats(times[name].second)};
    if (name == "cutawayCpu")
      m.cutawaySurfaceMs += p.cpu.median;
    else if (name == "cutawayAnchors" || name.rfind("jumpFlooding", 0) == 0 ||
             name == "cutawayDepth")
      m.cutawaySurfaceMs += p.gpu.median;
    m.passes.push_back(std::move(p));
  }
  return m;
}

// CPU reference algorithms (src/fields) on one seed image, median of `runs` (ms).
double timeMs(int runs, const std::function<void()>& f) {
  std::vector<double> t;
  for (int i = 0; i < runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count());
  }
  return stats(t).median;
}

// The scene's seed image at an n×n cutaway buffer, rendered by the real seed pass.
fields::SeedImage sceneSeedImage(const Scene& base, const gl::ContextInfo& info, int n) {
  Scene scene = base;
  AdaptiveCutawayOptions& adaptive = *scene.cutters.find<AdaptiveCutawayOptions>();
  adaptive.bufferSize = n;
  adaptive.compute = AdaptiveCutawayOptions::Compute::Cpu;
  Renderer renderer(scene, info);
  const Camera camera = scene.resolvedCamera();
  renderer.render(camera);
  return makeSeedImage(renderer.frame().read("seedDepth", 1), renderer.frame().read("seedAngle", 1),
                       n, adaptive,
                       cutawayProjection(camera, float(scene.width) / float(scene.height)));
}

nlohmann::json statsJson(const Stats& s) {
  return {{"median", s.median}, {"min", s.min}, {"max", s.max}};
}

}  // namespace

// Konev18 Table 1's rows for a scene with pipe networks: the empty scene, the (opened)
// terrain, the shafts, the billboard pipes and the same pipes meshed, each alone, then the
// whole scene with billboard pipes (the frame a user sees), at the paper's two resolutions.
void pipeTable(const Scene& scene, const Timing& timing, std::vector<Measurement>& runs) {
  const auto only = [&](bool terrain, bool shafts, std::optional<PipeNetwork::Mode> pipes) {
    Scene s = scene;
    s.objects.clear();
    for (const SceneObject& o : scene.objects) {
      const bool shaft =
          o.networkPart == NetworkPart::ShaftOuter || o.networkPart == NetworkPart::ShaftInner;
      if ((shaft && shafts) || (o.networkPart == NetworkPart::None && terrain))
        s.objects.push_back(o);
    }
    // Networks keep their indices (the shafts' colours); each keeps only the row's parts.
    for (PipeNetwork& net : s.networks) {
      if (!shafts) net.shafts.clear();
      if (!pipes) {
        net.pipes.clear();
        continue;
      }
      net.mode = *pipes;
      if (*pipes == PipeNetwork::Mode::Mesh)
        s.objects.push_back(networkObject(net, int(&net - s.networks.data()),
                                          NetworkPart::MeshedPipes, pipeMesh(net)));
    }
    if (!shafts && !pipes) s.networks.clear();
    if (!terrain) s.cutters.disable<TerrainOpeningOptions>();
    // The camera stays the whole scene's.
    s.camera = scene.resolvedCamera();
    s.camera.fit = false;
    return s;
  };
  const std::pair<const char*, Scene> rows[] = {
      {"Empty", only(false, false, std::nullopt)},
      {"Terrain", only(true, false, std::nullopt)},
      {"Shafts", only(false, true, std::nullopt)},
      {"Pipes (B)", only(false, false, PipeNetwork::Mode::Billboards)},
      {"Pipes (M)", only(false, false, PipeNetwork::Mode::Mesh)},
      {"City", only(true, true, PipeNetwork::Mode::Billboards)}};
  for (const auto& [w, h, size] : {std::tuple{1280, 960, "L"}, std::tuple{1920, 1200, "H"}})
    for (const auto& [label, row] : rows) {
      Scene s = row;
      s.width = w, s.height = h;
      runs.push_back(measure(std::string(label) + " " + size, s, timing));
      runs.back().plain = runs.size() - 1;
    }
}

namespace {

// `bench` on its scene, the options applied.
int benchScene(const BenchOptions& options, const Scene& scene) {
  const auto context = gl::HeadlessContext::create();
  const gl::ContextInfo& info = context->info();
  const Timing timing{*context, options.frames, !options.noOcclusionCulling};
  std::vector<Measurement> runs;
  nlohmann::json references = nlohmann::json::object(), accuracy = nlohmann::json::object();
  constexpr int kAccuracySize = 256;
  if (!scene.volumes.empty()) {
    // Volumes: plain ray casting, then each of the scene's cutters alone and all together,
    // at the two image sizes the volumes issue asks for.
    for (int n : {512, 1024}) {
      const std::string size = std::to_string(n) + "²";
      Scene plain = scene;
      plain.width = plain.height = n;
      plain.cutters.clear();
      const std::size_t base = runs.size();
      runs.push_back(measure("ray casting " + size, plain, timing));
      const std::vector<std::string> keys = scene.cutters.keys();
      for (const std::string& key : keys) {
        Scene one = plain;
        one.cutters.set(key, *scene.cutters.find(key));
        runs.push_back(measure(key + " " + size, one, timing));
      }
      if (keys.size() > 1) {
        Scene all = scene;
        all.width = all.height = n;
        runs.push_back(measure("all cutters " + size, all, timing));
      }
      for (std::size_t i = base; i < runs.size(); ++i) runs[i].plain = base;
    }
  } else if (!scene.networks.empty()) {
    pipeTable(scene, timing, runs);
  } else if (scene.cutters.find<CutoutOptions>() || scene.cutters.find<BreakawayOptions>()) {
    // Diepstraten03 §6's table: plain, cutout and breakaway for every style, in one run; a
    // cutter the scene does not configure runs with its defaults where the roles allow it.
    const bool interior =
        std::any_of(scene.objects.begin(), scene.objects.end(),
                    [](const SceneObject& o) { return o.role == Role::Interior; });
    for (const auto& style : styleNames()) {
      Scene plain = scene;
      plain.cutters.disable<CutoutOptions>();
      plain.cutters.disable<BreakawayOptions>();
      plain.style.name = style;
      const std::size_t base = runs.size();
      runs.push_back(measure("plain " + style, plain, timing));
      Scene cutout = plain;
      cutout.cutters.enable<CutoutOptions>() =
          scene.cutters.find<CutoutOptions>() ? *scene.cutters.find<CutoutOptions>() : CutoutOptions{};
      runs.push_back(measure("cutout " + style, cutout, timing));
      if (interior) {
        Scene breakaway = plain;
        breakaway.cutters.enable<BreakawayOptions>() = scene.cutters.find<BreakawayOptions>()
                                                           ? *scene.cutters.find<BreakawayOptions>()
                                                           : BreakawayOptions{};
        runs.push_back(measure("breakaway " + style, breakaway, timing));
      }
      for (std::size_t i = base; i < runs.size(); ++i) runs[i].plain = base;
    }
  } else if (scene.cutters.find<ClipSurfaceOptions>()) {
    // Trapp13 §6.2's comparison: the model alone, clipped, and clipped and capped.
    Scene plain = scene, clipped = scene;
    plain.cutters.disable<ClipSurfaceOptions>();
    clipped.cutters.find<ClipSurfaceOptions>()->caps = false;
    runs.push_back(measure("plain", plain, timing));
    runs.push_back(measure("clipped", clipped, timing));
    Scene capped = scene;
    capped.cutters.find<ClipSurfaceOptions>()->caps = true;
    runs.push_back(measure("clipped + capped", capped, timing));
  } else if (!scene.cutters.find<AdaptiveCutawayOptions>()) {
    runs.push_back(measure("frame", scene, timing));
  } else {
    // Burns08 Table 1's shape: the model alone, then with the cutaway, in one run; at the
    // two buffer sizes the issue asks for, on both compute paths.
    Scene plain = scene;
    plain.cutters.disable<AdaptiveCutawayOptions>();
    runs.push_back(measure("plain", plain, timing));
    for (int n : {512, 1024})
      for (auto compute :
           {AdaptiveCutawayOptions::Compute::Gpu, AdaptiveCutawayOptions::Compute::Cpu}) {
        Scene s = scene;
        s.cutters.find<AdaptiveCutawayOptions>()->bufferSize = n;
        s.cutters.find<AdaptiveCutawayOptions>()->compute = compute;
        const bool gpu = compute == AdaptiveCutawayOptions::Compute::Gpu;
        runs.push_back(
            measure("cutaway " + std::to_string(n) + (gpu ? " gpu" : " cpu"), s, timing));
      }
    // Burns11 Table 7.1's shape: the simple and the contextual structure, R applied each way
    // (its trimming, translucency, edge highlights), at the scene's own buffer size and
    // compute path; the scene's contextual options if any.
    Scene simple = scene;
    simple.cutters.find<AdaptiveCutawayOptions>()->contextual.reset();
    runs.push_back(measure("simple cutaway", simple, timing));
    using Application = ContextualCutawayOptions::Application;
    for (const auto& [name, apply] :
         {std::pair{"contextual cutaway", Application::Cut},
          std::pair{"contextual translucency", Application::Translucency},
          std::pair{"contextual edge highlights", Application::EdgeHighlights}}) {
      Scene contextual = scene;
      AdaptiveCutawayOptions& a = *contextual.cutters.find<AdaptiveCutawayOptions>();
      if (!a.contextual) a.contextual = ContextualCutawayOptions{};
      a.contextual->transitionAngle = std::max(a.contextual->transitionAngle, a.angle);
      a.contextual->apply = apply;
      runs.push_back(measure(name, contextual, timing));
    }
    const fields::JumpFloodingVariant variant = scene.cutters.find<AdaptiveCutawayOptions>()->variant;
    for (int n : {512, 1024}) {
      const fields::SeedImage seeds = sceneSeedImage(scene, info, n);
      const std::string size = std::to_string(n);
      references["jumpFlooding " + size + " (all threads)"] =
          timeMs(5, [&] { (void)fields::jumpFlooding(seeds, -1.0f, variant); });
      references["jumpFlooding " + size + " (1 thread)"] =
          timeMs(3, [&] { (void)fields::jumpFlooding(seeds, -1.0f, variant, 1); });
      references["chamfer 3x3 " + size] =
          timeMs(3, [&] { (void)fields::chamfer(seeds, -1.0f, fields::ChamferKernel::k3x3); });
      references["chamfer 5x5 " + size] =
          timeMs(3, [&] { (void)fields::chamfer(seeds, -1.0f, fields::ChamferKernel::k5x5); });
    }
    const fields::SeedImage small = sceneSeedImage(scene, info, 128);
    references["bruteForce 128"] = timeMs(1, [&] { (void)fields::bruteForce(small, -1.0f); });
    // Accuracy of each jump-flooding variant against brute force (exact) on this scene's
    // seed image: the share of pixels off by more than 1e-4 of the depth range.
    const fields::SeedImage seeds = sceneSeedImage(scene, info, kAccuracySize);
    const fields::CutawayField exact = fields::bruteForce(seeds, -1.0f);
    for (auto variant :
         {fields::JumpFloodingVariant::jfa, fields::JumpFloodingVariant::jfaPlus1,
          fields::JumpFloodingVariant::onePlusJfa, fields::JumpFloodingVariant::jfaPlus2}) {
      const fields::CutawayField f = fields::jumpFlooding(seeds, -1.0f, variant);
      std::size_t off = 0;
      for (std::size_t i = 0; i < f.depth.size(); ++i)
        off += std::abs(f.depth[i] - exact.depth[i]) > 2e-4f;  // NDC spans 2
      accuracy[fields::variantName(variant)] = double(off) / double(f.depth.size());
    }
  }
  const char* autoPath = nullptr;
  if (const auto* a = scene.cutters.find<AdaptiveCutawayOptions>())
    autoPath = cutawayOnCpu(*a, info.software) ? "cpu" : "gpu";

  if (options.json) {
    nlohmann::json out = {{"scene", options.scene},
                          {"renderer", info.renderer},
                          {"resolution", {scene.width, scene.height}},
                          {"samples", scene.samples},
                          {"frames", options.frames}};
    nlohmann::json list = nlohmann::json::array();
    for (const auto& m : runs) {
      nlohmann::json passes = nlohmann::json::array();
      for (const auto& p : m.passes)
        passes.push_back({{"pass", p.name},
                          {"gpuMs", statsJson(p.gpu)},
                          {"cpuMs", statsJson(p.cpu)},
                          {"gpuMedianMs", p.gpu.median},
                          {"gpuMinMs", p.gpu.min},
                          {"gpuMaxMs", p.gpu.max}});
      nlohmann::json entry = {{"label", m.label},
                              {"passes", passes},
                              {"frame", statsJson(m.frame)},
                              {"frameRatioToPlain", m.frame.median / runs[m.plain].frame.median},
                              {"meshTriangles", m.triangles},
                              {"culledObjects", m.culled},
                              {"peeledLayerDraws", m.peeled}};
      if (m.computePath)
        entry["cutawaySurfaceMs"] = m.cutawaySurfaceMs, entry["computePath"] = m.computePath;
      list.push_back(entry);
    }
    out["runs"] = list;
    // The first run's passes at top level, for a quick look.
    out["passes"] = list.front()["passes"];
    out["frame"] = {{"medianMs", runs.front().frame.median},
                    {"minMs", runs.front().frame.min},
                    {"maxMs", runs.front().frame.max}};
    if (autoPath) {
      out["autoComputePath"] = autoPath;
      out["cpuReferencesMs"] = references;
      out["jumpFloodingErrorFraction"] = accuracy;
      out["jumpFloodingErrorBuffer"] = kAccuracySize;
    }
    std::printf("%s\n", out.dump(2).c_str());
    return 0;
  }
  std::printf("%s, %dx%d, %d samples, %d frames on %s\n",
              options.city > 0 ? ("benchmark city x" + std::to_string(options.city)).c_str()
                               : options.scene.c_str(),
              scene.width, scene.height, scene.samples, options.frames, info.renderer.c_str());
  for (const auto& m : runs) {
    // CPU: wall time inside the pass's own code. On a software rasteriser a pass's commands
    // run when the next pass flushes, so a GPU pass's CPU time holds the previous pass's work.
    std::printf("\n[%s]", m.label.c_str());
    if (m.culled > 0) std::printf(" %zu hidden objects not drawn", m.culled);
    if (m.peeled > 0) std::printf(", %zu peeled objects not drawn into layers", m.peeled);
    std::printf("\n%-26s %10s %10s %10s %10s\n", "pass (ms)", "GPU median", "GPU min", "GPU max",
                "CPU wall");
    for (const auto& p : m.passes)
      std::printf("%-26s %10.3f %10.3f %10.3f %10.3f\n", p.name.c_str(), p.gpu.median, p.gpu.min,
                  p.gpu.max, p.cpu.median);
    std::printf("%-26s %10.3f %10.3f %10.3f\n", "frame (wall ms)", m.frame.median, m.frame.min,
                m.frame.max);
  }
  if (!scene.networks.empty()) {
    std::printf(
        "\nKonev18 Table 1 (frame ms, median; mesh triangles drawn):\n%-12s %12s %12s %12s %12s\n",
        "feature", "L 1280x960", "H 1920x1200", "L triangles", "H triangles");
    const std::size_t half = runs.size() / 2;
    for (std::size_t i = 0; i < half; ++i)
      std::printf("%-12s %12.3f %12.3f %12zu %12zu\n",
                  runs[i].label.substr(0, runs[i].label.size() - 2).c_str(), runs[i].frame.median,
                  runs[i + half].frame.median, runs[i].triangles, runs[i + half].triangles);
  } else if (runs.size() > 1) {
    // Each run against the plain run of its group (its style, its image size).
    std::printf("\n%-28s %12s %12s", "summary", "frame ms", "× plain");
    std::printf(autoPath ? " %18s\n" : "\n", "cutaway surface ms");
    for (const auto& m : runs) {
      std::printf("%-28s %12.3f %12.3f", m.label.c_str(), m.frame.median,
                  m.frame.median / runs[m.plain].frame.median);
      if (autoPath) std::printf(" %18.3f", m.cutawaySurfaceMs);
      std::printf("\n");
    }
  }
  if (autoPath) {
    std::printf("compute path of the cutaway surface here: %s\n", autoPath);
    if (!references.empty()) std::printf("\nCPU references (ms):\n");
    for (const auto& [name, ms] : references.items())
      std::printf("  %-32s %10.3f\n", name.c_str(), ms.get<double>());
    if (!accuracy.empty())
      std::printf(
          "\nJump flooding vs brute force at %d² (pixels off by > 1e-4 of the depth range):\n",
          kAccuracySize);
    for (const auto& [name, fraction] : accuracy.items())
      std::printf("  %-8s %9.4f%%\n", name.c_str(), 100.0 * fraction.get<double>());
  }
  return 0;
}

}  // namespace

int bench(const BenchOptions& options) {
  Scene scene = sceneOrCity(options.scene, options.city, "bench");
  applyOverrides(scene, options.overrides);
  return blamingOverrides(options.overrides, scene, [&] { return benchScene(options, scene); });
}

namespace {

const char* typeName(OptionSpec::Type type) {
  switch (type) {
    case OptionSpec::Type::Bool: return "bool";
    case OptionSpec::Type::Int: return "int";
    case OptionSpec::Type::Float: return "float";
    case OptionSpec::Type::Choice: return "choice";
    case OptionSpec::Type::Color: return "colour";
    case OptionSpec::Type::Direction: return "direction";
    case OptionSpec::Type::Vec3: return "vec3";
    case OptionSpec::Type::Text: return "text";
  }
  return "?";
}

std::string rangeText(const OptionSpec& s) {
  using T = OptionSpec::Type;
  if (s.type == T::Choice) {
    std::string list;
    for (const auto& c : s.choices) list += (list.empty() ? "" : "|") + c;
    return list;
  }
  if (s.type != T::Int && s.type != T::Float && s.type != T::Vec3) return "";
  return "[" + formatOptionValue(s.min) + ", " + formatOptionValue(s.max) + "]" +
         (s.powerOfTwo ? " 2^n" : "");
}

}  // namespace

int listOptions(bool json) {
  const Scene defaults;  // every technique off: each option reads as its default
  nlohmann::json list = nlohmann::json::array();
  for (const SceneOption& o : sceneOptions()) {
    const OptionSpec& s = o.spec;
    list.push_back({{"path", o.path},
                    {"type", typeName(s.type)},
                    {"range", rangeText(s)},
                    {"default", formatOptionValue(s.get(&defaults))},
                    {"live", s.live},
                    {"inFile", s.inFile},
                    {"doc", s.doc}});
  }
  if (json) {
    std::printf("%s\n", list.dump(2).c_str());
    return 0;
  }
  std::printf("%-44s %-9s %-22s %-16s %s\n", "path", "type", "range", "default", "live");
  for (const auto& o : list)
    std::printf("%-44s %-9s %-22s %-16s %s\n", o["path"].get<std::string>().c_str(),
                o["type"].get<std::string>().c_str(), o["range"].get<std::string>().c_str(),
                o["default"].get<std::string>().c_str(), o["live"].get<bool>() ? "live" : "rebuild");
  return 0;
}

}  // namespace cutaway::cli
