// The JSON scene format (docs/scene-format.md): strict parsing, every error names the file,
// the JSON pointer and the reason; unknown keys are errors.
#include <algorithm>
#include <any>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <tuple>

#include "core/json_reader.hpp"
#include "cutaway/core/error.hpp"
#include "cutaway/core/image.hpp"
#include "cutaway/geometry/convex_hull.hpp"
#include "cutaway/geometry/extrude.hpp"
#include "cutaway/geometry/ground_height.hpp"
#include "cutaway/io/gis_import.hpp"
#include "cutaway/io/mesh_import.hpp"
#include "cutaway/io/raster_terrain.hpp"
#include "cutaway/io/volume_import.hpp"
#include "cutaway/scene/scene.hpp"
#include "cutters/registry.hpp"
#include "scene/network_json.hpp"
#include "styles/registry.hpp"

namespace cutaway {

namespace {

using namespace json_reader;
using json = nlohmann::json;

// The renderer's light array (kMaxLights in src/frame/frame_uniforms.glsl); more would be
// dropped without a word.
constexpr std::size_t kMaxLights = 8;

// translate / rotate / scale keys of a transform or keyframe, read from `r` in double, so that
// a placement millions of units from the origin (projected GIS coordinates) keeps its
// centimetres until the composed matrix is rounded once (placeObject).
struct ExactTrs {
  glm::dvec3 translate{0.0};
  glm::dquat rotate{1.0, 0.0, 0.0, 0.0};
  glm::dvec3 scale{1.0};
  glm::dmat4 matrix() const {
    return glm::translate(glm::dmat4(1.0), translate) * glm::mat4_cast(rotate) *
           glm::scale(glm::dmat4(1.0), scale);
  }
  Trs single() const { return {glm::vec3(translate), glm::quat(rotate), glm::vec3(scale)}; }
};

ExactTrs readTrs(const Context& ctx, ObjectReader& r) {
  ExactTrs out;
  if (const json* v = r.take("translate")) out.translate = dvec3(ctx, *v, r.at("translate"));
  if (const json* v = r.take("rotate")) {
    if (v->is_array()) {  // Euler angles in degrees, applied about x, then y, then z
      const glm::dvec3 e = glm::radians(dvec3(ctx, *v, r.at("rotate")));
      out.rotate = glm::angleAxis(e.z, glm::dvec3(0, 0, 1)) *
                   glm::angleAxis(e.y, glm::dvec3(0, 1, 0)) *
                   glm::angleAxis(e.x, glm::dvec3(1, 0, 0));
    } else {
      ObjectReader rr(ctx, *v, r.at("rotate"));
      const glm::dvec3 axis(direction(ctx, rr.require("axis"), rr.at("axis")));
      const double degrees = number(ctx, rr.require("degrees"), rr.at("degrees"), -1e6, 1e6);
      rr.finish();
      out.rotate = glm::angleAxis(glm::radians(degrees), glm::normalize(axis));
    }
  }
  if (const json* v = r.take("scale")) {
    const glm::dvec3 k = v->is_number() ? glm::dvec3(number(ctx, *v, r.at("scale"), -1e30, 1e30))
                                        : dvec3(ctx, *v, r.at("scale"));
    // Per component: the product would reject small uniform scales (0.0001³ < 1e-12).
    for (int i = 0; i < 3; ++i)
      if (!(std::abs(float(k[i])) >= std::numeric_limits<float>::min()))
        ctx.fail(r.at("scale"), "scale must not be zero");
    out.scale = k;
  }
  return out;
}

// The time of key `r`, in [0, 1e6], after the time of the key before it (`previous`, as read):
// both as the 32-bit floats they are kept in.
float keyTime(const Context& ctx, ObjectReader& r, std::optional<double>& previous,
              const std::string& keys) {
  const double time = number(ctx, r.require("time"), r.at("time"), 0, 1e6);
  if (previous && !(float(time) > float(*previous))) {
    std::string message = keys + " times must increase";
    // Each number as its shortest exact form, so that the two always read apart.
    const auto shortest = [](double v) {
      char text[32];
      return std::string(text, std::to_chars(text, text + sizeof text, v).ptr);
    };
    if (time > *previous)
      message +=
          ": " + shortest(time) + " and " + shortest(*previous) + " are one time in 32-bit floats";
    ctx.fail(r.at("time"), message);
  }
  previous = time;
  return float(time);
}

std::vector<Keyframe> animation(const Context& ctx, const json& j, const std::string& ptr) {
  if (!j.is_array() || j.empty()) ctx.fail(ptr, "expected a non-empty array of keyframes");
  std::vector<Keyframe> keys;
  std::optional<double> previous;
  for (std::size_t i = 0; i < j.size(); ++i) {
    ObjectReader r(ctx, j[i], ptr + "/" + std::to_string(i));
    const float time = keyTime(ctx, r, previous, "keyframe");
    keys.push_back({time, readTrs(ctx, r).single()});
    r.finish();
  }
  return keys;
}

// A camera's eye or target: within kMaxSceneReach of the origin, as the scene's parts.
glm::vec3 cameraPoint(const Context& ctx, const json& j, const std::string& ptr) {
  const glm::vec3 p = vec3(ctx, j, ptr);
  const float reach = sceneReach(p);
  if (!(reach <= kMaxSceneReach)) {
    std::ostringstream message;
    message << reach << " scene units from the origin; 32-bit floats cannot render beyond 1e15";
    ctx.fail(ptr, message.str());
  }
  return p;
}

// An eye and target nearer than a scene's least detail (kMinSceneDetail), in doubles: a float
// length underflows below 1e-19.
bool coincide(glm::vec3 eye, glm::vec3 target) {
  return glm::distance(glm::dvec3(eye), glm::dvec3(target)) < double(kMinSceneDetail);
}
constexpr const char* kCoincide = "eye and target coincide (nearer than 1e-15)";

std::vector<CameraKey> cameraPath(const Context& ctx, const json& j, const std::string& ptr) {
  if (!j.is_array() || j.empty()) ctx.fail(ptr, "expected a non-empty array of camera keys");
  std::vector<CameraKey> keys;
  std::optional<double> previous;
  for (std::size_t i = 0; i < j.size(); ++i) {
    ObjectReader r(ctx, j[i], ptr + "/" + std::to_string(i));
    CameraKey k;
    k.time = keyTime(ctx, r, previous, "camera key");
    k.eye = cameraPoint(ctx, r.require("eye"), r.at("eye"));
    k.target = cameraPoint(ctx, r.require("target"), r.at("target"));
    if (coincide(k.eye, k.target)) ctx.fail(r.at("eye"), kCoincide);
    r.finish();
    keys.push_back(k);
  }
  return keys;
}

glm::dmat4 transform(const Context& ctx, const json& j, const std::string& ptr) {
  ObjectReader r(ctx, j, ptr);
  if (const json* m = r.take("matrix")) {
    for (const char* k : {"translate", "rotate", "scale"})
      if (r.has(k)) ctx.fail(r.at(k), "\"matrix\" excludes translate/rotate/scale");
    if (!m->is_array() || m->size() != 16) ctx.fail(r.at("matrix"), "expected 16 numbers");
    glm::dmat4 out;
    for (int row = 0; row < 4; ++row)
      for (int col = 0; col < 4; ++col)  // written row-major, as one reads a matrix
        out[col][row] = number(ctx, (*m)[std::size_t(row * 4 + col)],
                               r.at("matrix") + "/" + std::to_string(row * 4 + col), -1e30, 1e30);
    // The renderer and the bounds use the matrix as an affine map (w stays 1).
    if (glm::dvec4(out[0][3], out[1][3], out[2][3], out[3][3]) != glm::dvec4(0, 0, 0, 1))
      ctx.fail(r.at("matrix"), "the last row must be 0, 0, 0, 1 (an affine transform)");
    // Singular relative to the columns' lengths (|det| ≤ their product), so that a uniformly
    // small scale such as 1e-4 is not mistaken for a singular matrix.
    const glm::dmat3 linear(out);
    if (!(std::abs(glm::determinant(linear)) >
          1e-6 * glm::length(linear[0]) * glm::length(linear[1]) * glm::length(linear[2])))
      ctx.fail(r.at("matrix"),
               "the matrix is singular or nearly so (|det| at most 1e-6 of the "
               "product of its columns' lengths)");
    r.finish();
    return out;
  }
  const ExactTrs trs = readTrs(ctx, r);
  r.finish();
  return trs.matrix();
}

// Beyond 2¹⁶ units from the origin a float's step exceeds 1/128 of a unit (0.5 at UTM's
// 4.8e6 m northings).
constexpr float kFarFromOrigin = 65536.0f;

// Gives `o` its mesh and its transform `m`, rounded to float once. A mesh whose centre c lies
// beyond kFarFromOrigin (projected GIS coordinates: UTM, the British National Grid) is moved
// by −c, each vertex rounded once, and c is folded into the matrix in double, m·T(c): neither
// the vertices nor the matrix then carry the large coordinates through float arithmetic, and
// a rotation about a far origin keeps the vertices' precision.
void placeObject(SceneObject& o, std::shared_ptr<const Mesh> mesh, const glm::dmat4& m) {
  const Bounds b = mesh->bounds();
  const glm::vec3 c = b.empty() ? glm::vec3(0.0f) : (b.min + b.max) * 0.5f;
  if (glm::all(glm::lessThanEqual(glm::abs(c), glm::vec3(kFarFromOrigin)))) {
    o.mesh = std::move(mesh), o.transform = glm::mat4(m);
    return;
  }
  auto moved = std::make_shared<Mesh>(*mesh);
  for (glm::vec3& p : moved->positions) p -= c;
  o.mesh = std::move(moved);
  o.transform = glm::mat4(m * glm::translate(glm::dmat4(1.0), glm::dvec3(c)));
}

Role role(const Context& ctx, const json& j, const std::string& ptr) {
  std::vector<std::string> names;
  for (const Role r : kRoles) names.push_back(roleName(r));
  return *roleFromName(oneOf(ctx, j, ptr, names));
}

ObjectParams params(const Context& ctx, const json& j, const std::string& ptr) {
  if (!j.is_object()) ctx.fail(ptr, "expected an object, got " + typeName(j));
  ObjectParams out;
  for (const auto& [key, value] : j.items()) {
    const std::string p = ptr + "/" + token(key);
    const ObjectParamSpec* spec = nullptr;
    for (const auto& s : objectParameterSpecs())
      if (s.name == key) spec = &s;
    if (!spec) {
      std::string known;
      for (const auto& s : objectParameterSpecs()) known += (known.empty() ? "" : ", ") + s.name;
      ctx.fail(p, "unknown object parameter " + quote(key) + " (known: " + known + ")");
    }
    if (spec->type == ObjectParamSpec::Type::Bool)
      out[key] = boolean(ctx, value, p);
    else
      out[key] = number(ctx, value, p, spec->min, spec->max);
  }
  return out;
}

// The keys every object, override and proxy may set about itself.
void appearance(const Context& ctx, ObjectReader& r, SceneObject& o, bool visible) {
  if (const json* v = r.take("role")) o.role = role(ctx, *v, r.at("role"));
  if (const json* v = r.take("importance"))
    o.importance = float(number(ctx, *v, r.at("importance"), 0, 1));
  if (const json* v = r.take("group")) o.group = name(ctx, *v, r.at("group"), "group", true);
  if (const json* v = r.take("cutBy")) {
    // The registered cutters' keys (the shaft wedge's too, which the file never switches).
    std::vector<std::string> keys;
    for (const CutterType& t : cutterTypes()) keys.push_back(t.key);
    if (!v->is_array()) ctx.fail(r.at("cutBy"), "expected an array of cutter names");
    o.cutBy.emplace();
    for (std::size_t i = 0; i < v->size(); ++i)
      o.cutBy->push_back(oneOf(ctx, (*v)[i], r.at("cutBy") + "/" + std::to_string(i), keys));
  }
  if (const json* v = r.take("params")) {
    for (auto& [k, value] : params(ctx, *v, r.at("params"))) o.params[k] = value;
  }
  if (!visible) return;
  if (const json* v = r.take("color")) o.material.color = color(ctx, *v, r.at("color"));
  if (const json* v = r.take("specular"))
    o.material.specular = float(number(ctx, *v, r.at("specular"), 0, 1));
  if (const json* v = r.take("shininess"))
    o.material.shininess = float(number(ctx, *v, r.at("shininess"), 1, 10000));
}

// A mesh file is imported once per scene, and not again while a scene still holds it (the
// viewer's last good scene while an edit reloads): files are known by path, size and
// modification time.
class MeshCache {
 public:
  // Shared so that the objects' meshes (aliasing pointers into it) outlive the cache.
  std::shared_ptr<const std::vector<ImportedNode>> get(const std::filesystem::path& file) {
    auto it = files_.find(file);
    if (it != files_.end()) return it->second;
    std::error_code sizeError, timeError;
    const Key key{file, std::filesystem::file_size(file, sizeError),
                  std::filesystem::last_write_time(file, timeError)};
    if (sizeError || timeError) return files_[file] = import(file);  // its error names why
    static std::mutex mutex;
    static std::map<Key, std::weak_ptr<const std::vector<ImportedNode>>> held;
    {
      const std::lock_guard lock(mutex);
      const auto entry = held.find(key);
      if (entry != held.end())
        if (auto nodes = entry->second.lock()) return files_[file] = nodes;
    }
    auto nodes = import(file);
    const std::lock_guard lock(mutex);
    std::erase_if(held, [](const auto& entry) { return entry.second.expired(); });
    held[key] = nodes;
    return files_[file] = nodes;
  }

 private:
  using Key = std::tuple<std::filesystem::path, std::uintmax_t, std::filesystem::file_time_type>;
  static std::shared_ptr<const std::vector<ImportedNode>> import(
      const std::filesystem::path& file) {
    return std::make_shared<const std::vector<ImportedNode>>(importMeshNodes(file));
  }
  std::map<std::filesystem::path, std::shared_ptr<const std::vector<ImportedNode>>> files_;
};

// A file reader's error as the reason for the scene's "file": where in the file it went
// wrong too ("vertex index 9 out of range (4 vertices) (part.ply: face 0)").
std::string fromFile(const Error& e, const std::filesystem::path& file) {
  return e.reason() + " (" + file.string() + (e.place().empty() ? "" : ": " + e.place()) + ")";
}

// "raster": a terrain grid from band 1 of a GDAL raster, placed through the scene's frame.
std::shared_ptr<Mesh> rasterMesh(const Context& ctx, const json& j, const std::string& ptr,
                                 std::string& source) {
  ObjectReader r(ctx, j, ptr);
  const std::string text = string(ctx, r.require("file"), r.at("file"));
  std::filesystem::path file = text;
  if (file.is_relative()) file = ctx.baseDir / file;
  RasterTerrainOptions options{.targetCrs = ctx.geo.crs, .offset = ctx.geo.offset};
  if (const json* v = r.take("step")) options.step = integer(ctx, *v, r.at("step"), 1, 1 << 20);
  if (const json* v = r.take("heightScale"))
    options.heightScale = number(ctx, *v, r.at("heightScale"), -1e6, 1e6);
  r.finish();
  if (options.heightScale == 0.0) ctx.fail(r.at("heightScale"), "heightScale must not be zero");
  source = file.string();
  try {
    auto mesh = std::make_shared<Mesh>(importRasterTerrain(file, options).mesh);
    analyzeTopology(*mesh);
    return mesh;
  } catch (const Error& e) {
    ctx.fail(r.at("file"), fromFile(e, file));
  }
}

// "footprints": polygons of a GIS layer extruded to blocks, all of them one mesh. `objects`
// are those read so far, for "on"; `transform` is this object's.
std::shared_ptr<Mesh> footprintMesh(const Context& ctx, const json& j, const std::string& ptr,
                                    const std::vector<SceneObject>& objects,
                                    const glm::mat4& transform, std::string& source) {
  ObjectReader r(ctx, j, ptr);
  const std::string text = string(ctx, r.require("file"), r.at("file"));
  std::filesystem::path file = text;
  if (file.is_relative()) file = ctx.baseDir / file;
  GisImportOptions options = gisImportOptions(ctx.geo);
  if (const json* v = r.take("layer")) options.layer = string(ctx, *v, r.at("layer"));
  // "height": a number, or {"field": NAME, "default": NUMBER} (a footprint with a null or
  // non-positive value takes the default).
  double height = 0.0;
  std::optional<double> fallback;
  const json& h = r.require("height");
  if (h.is_number()) {
    height = number(ctx, h, r.at("height"), 1e-3, 1e4);
  } else {
    ObjectReader hr(ctx, h, r.at("height"));
    options.attributes.push_back(string(ctx, hr.require("field"), hr.at("field")));
    if (const json* v = hr.take("default")) fallback = number(ctx, *v, hr.at("default"), 1e-3, 1e4);
    hr.finish();
  }
  const SceneObject* ground = nullptr;
  if (const json* v = r.take("on")) {
    const std::string name = string(ctx, *v, r.at("on"));
    for (const SceneObject& o : objects)
      if (o.name == name) ground = &o;
    if (!ground)
      ctx.fail(r.at("on"),
               "no object named " + quote(name) + " before this one (list the terrain first)");
  }
  r.finish();
  source = file.string();
  GisPolygons polygons;
  try {
    polygons = importGisPolygons(file, options);
  } catch (const Error& e) {
    ctx.fail(r.at("file"), fromFile(e, file));
  }
  // The terrain at rest, in this object's space: the highest surface over a point is the
  // ground there (an overhang's underside is not).
  std::optional<GroundHeight> terrain;
  if (ground)
    terrain.emplace(std::vector<const Mesh*>{ground->mesh.get()},
                    std::vector<glm::mat4>{glm::inverse(transform) * ground->transform});
  auto mesh = std::make_shared<Mesh>();
  for (const GisPolygon& polygon : polygons.polygons) {
    Footprint footprint;
    // GeoFrame: scene x = E − E0, z = −(N − N0).
    for (const glm::vec3& p : polygon.outer) footprint.outer.emplace_back(p.x, -p.y);
    for (const auto& hole : polygon.holes) {
      footprint.holes.emplace_back();
      for (const glm::vec3& p : hole) footprint.holes.back().emplace_back(p.x, -p.y);
    }
    const std::string feature = "feature " + std::to_string(polygon.featureId);
    double blockHeight = height;
    if (!polygon.attributes.empty()) {
      const double value = polygon.attributes[0];
      if (std::isfinite(value) && value > 0.0)
        blockHeight = value;
      else if (fallback)
        blockHeight = *fallback;
      else
        ctx.fail(r.at("height") + "/field", feature + " of " + file.string() +
                                                " has no positive \"" + options.attributes[0] +
                                                "\" value, and no \"default\" is given");
    }
    float base = 0.0f;
    if (terrain) {
      // The lowest ground under the footprint's outline.
      std::optional<float> lowest;
      for (const glm::vec2& p : footprint.outer)
        if (const std::optional<float> y = terrain->at(p))
          lowest = std::min(lowest.value_or(*y), *y);
      if (!lowest)
        ctx.fail(r.at("on"), feature + " of " + file.string() + " lies outside object \"" +
                                 ground->name + "\"");
      base = *lowest;
    }
    mesh->append(extrudeFootprint(footprint, base, base + float(blockHeight)), glm::mat4(1.0f));
  }
  analyzeTopology(*mesh);
  return mesh;
}

// The mesh or volume an entry's "arrays" key names among the ones given in memory.
template <class T>
std::shared_ptr<const T> arraysEntry(const Context& ctx, const json& j, const std::string& ptr,
                                     const std::map<std::string, std::shared_ptr<const T>>& given) {
  const std::string key = string(ctx, j, ptr);
  const auto it = given.find(key);
  if (it == given.end())
    ctx.fail(ptr, "no arrays named \"" + key +
                      "\" were given (arrays come from NumPy through the Python module)");
  return it->second;
}

void readObject(const Context& ctx, const json& j, const std::string& ptr, MeshCache& cache,
                const SceneArrays& arrays, std::vector<SceneObject>& out) {
  ObjectReader r(ctx, j, ptr);
  const std::string name = cutaway::name(ctx, r.require("name"), r.at("name"), "object");
  const json* fileKey = r.take("file");
  const json* rasterKey = r.take("raster");
  const json* footprintsKey = r.take("footprints");
  const json* arraysKey = r.take("arrays");
  if (int(!!fileKey) + int(!!rasterKey) + int(!!footprintsKey) + int(!!arraysKey) != 1)
    ctx.fail(ptr,
             "an object needs exactly one of \"file\", \"raster\", \"footprints\" or "
             "\"arrays\"");
  if (!fileKey)
    for (const char* k : {"split", "nodes", "overrides"})
      if (r.has(k)) ctx.fail(r.at(k), std::string("\"") + k + "\" needs a mesh \"file\"");
  const std::string fileText = fileKey ? string(ctx, *fileKey, r.at("file")) : "";
  std::filesystem::path file = fileText;
  if (file.is_relative()) file = ctx.baseDir / file;
  const bool split =
      r.has("split") && oneOf(ctx, *r.take("split"), r.at("split"), {"file", "nodes"}) == "nodes";
  r.take("split");
  std::optional<std::regex> nodeFilter;
  if (const json* v = r.take("nodes")) nodeFilter = regex(ctx, *v, r.at("nodes"));
  glm::dmat4 m(1.0);
  if (const json* v = r.take("transform")) m = transform(ctx, *v, r.at("transform"));

  SceneObject base;
  base.name = name;
  base.transform = glm::mat4(m);
  if (const json* v = r.take("animation")) base.animation = animation(ctx, *v, r.at("animation"));
  const bool colorGiven = r.has("color");
  appearance(ctx, r, base, true);

  struct Override {
    std::regex match;
    json body;
    std::string pointer;
  };
  std::vector<Override> overrides;
  if (const json* v = r.take("overrides")) {
    if (!v->is_array()) ctx.fail(r.at("overrides"), "expected an array, got " + typeName(*v));
    for (std::size_t i = 0; i < v->size(); ++i) {
      const std::string p = r.at("overrides") + "/" + std::to_string(i);
      ObjectReader orr(ctx, (*v)[i], p);
      Override o{regex(ctx, orr.require("match"), orr.at("match")), (*v)[i], p};
      SceneObject probe;
      appearance(ctx, orr, probe, true);  // validates the keys now, applied per node below
      orr.finish();
      overrides.push_back(std::move(o));
    }
    if (!split) ctx.fail(r.at("overrides"), "overrides need \"split\": \"nodes\"");
  }
  r.finish();

  if (!fileKey) {
    SceneObject o = base;
    if (arraysKey) {
      placeObject(o, arraysEntry(ctx, *arraysKey, r.at("arrays"), arrays.meshes), m);
      o.source = "arrays " + arraysKey->get<std::string>();
    } else {
      placeObject(o,
                  rasterKey ? rasterMesh(ctx, *rasterKey, r.at("raster"), o.source)
                            : footprintMesh(ctx, *footprintsKey, r.at("footprints"), out,
                                            base.transform, o.source),
                  m);
    }
    out.push_back(std::move(o));
    return;
  }

  std::shared_ptr<const std::vector<ImportedNode>> nodes;
  try {
    nodes = cache.get(file);
  } catch (const Error& e) {
    ctx.fail(r.at("file"), fromFile(e, file));
  }
  std::vector<const ImportedNode*> selected;
  for (const auto& node : *nodes)
    if (!nodeFilter || std::regex_match(node.name, *nodeFilter) ||
        (!node.id.empty() && std::regex_match(node.id, *nodeFilter)))
      selected.push_back(&node);
  if (selected.empty()) ctx.fail(r.at("nodes"), "no mesh node of " + file.string() + " matches");

  if (!split) {
    auto mesh = std::make_shared<Mesh>();
    for (const auto* node : selected) {
      mesh->append(node->mesh, glm::mat4(1.0f));
      mesh->report.droppedDegenerate += node->mesh.report.droppedDegenerate;
      mesh->report.normalsComputed |= node->mesh.report.normalsComputed;
      mesh->report.windingReversed |= node->mesh.report.windingReversed;
    }
    analyzeTopology(*mesh);
    orientOutward(*mesh);  // the nodes may close only together
    SceneObject o = base;
    o.source = file.string();
    if (!colorGiven && selected.front()->color) o.material.color = *selected.front()->color;
    placeObject(o, std::move(mesh), m);
    out.push_back(std::move(o));
    return;
  }
  for (const auto* node : selected) {
    SceneObject o = base;
    o.name = name + "/" + node->name;
    if (!node->id.empty()) o.alias = name + "/" + node->id;
    o.source = file.string() + "#" + node->name;
    if (!colorGiven && node->color) o.material.color = *node->color;
    // Aliasing: shares the file's nodes (unless far from the origin: a moved copy).
    placeObject(o, std::shared_ptr<const Mesh>(nodes, &node->mesh), m);
    for (const auto& ov : overrides) {
      if (!std::regex_match(node->name, ov.match) &&
          (node->id.empty() || !std::regex_match(node->id, ov.match)))
        continue;
      ObjectReader orr(ctx, ov.body, ov.pointer);
      orr.take("match");
      appearance(ctx, orr, o, true);
    }
    out.push_back(std::move(o));
  }
}

void readProxy(const Context& ctx, const json& j, const std::string& ptr,
               std::vector<SceneObject>& objects) {
  ObjectReader r(ctx, j, ptr);
  SceneObject o;
  o.proxy = true;
  o.role = Role::Interest;
  o.importance = 1.0f;
  o.source = "proxy";
  o.name = name(ctx, r.require("name"), r.at("name"), "proxy");
  const json* box = r.take("box");
  const json* hullOf = r.take("hullOf");
  if (!!box == !!hullOf) ctx.fail(ptr, "a proxy needs exactly one of \"box\" or \"hullOf\"");
  if (const json* v = r.take("transform"))
    o.transform = glm::mat4(transform(ctx, *v, r.at("transform")));
  if (const json* v = r.take("animation")) o.animation = animation(ctx, *v, r.at("animation"));
  appearance(ctx, r, o, false);
  r.finish();
  if (box) {
    ObjectReader br(ctx, *box, r.at("box"));
    const glm::vec3 lo = vec3(ctx, br.require("min"), br.at("min"));
    const glm::vec3 hi = vec3(ctx, br.require("max"), br.at("max"));
    br.finish();
    if (!glm::all(glm::lessThan(lo, hi)))
      ctx.fail(r.at("box"), "box min must be below max on every axis");
    o.mesh = std::make_shared<Mesh>(makeBox(lo, hi));
  } else {
    const std::regex pattern = regex(ctx, *hullOf, r.at("hullOf"));
    std::vector<glm::vec3> points;
    int matched = 0;
    for (const auto& other : objects) {
      if (other.proxy || !other.named(pattern)) continue;
      ++matched;
      for (const auto& p : other.mesh->positions)
        points.push_back(glm::vec3(other.transform * glm::vec4(p, 1.0f)));
    }
    if (matched == 0) ctx.fail(r.at("hullOf"), "no object name matches");
    try {
      // Points are in world space already; the proxy's own transform applies on top.
      o.mesh = std::make_shared<Mesh>(convexHull(points));
    } catch (const Error& e) {
      ctx.fail(r.at("hullOf"), e.reason());
    }
  }
  objects.push_back(std::move(o));
}

// A transfer function's control points, in increasing value.
std::vector<TransferPoint> transferPoints(const Context& ctx, const json& j,
                                          const std::string& ptr) {
  if (!j.is_array() || j.empty()) ctx.fail(ptr, "expected an array of control points");
  std::vector<TransferPoint> points;
  for (std::size_t i = 0; i < j.size(); ++i) {
    ObjectReader r(ctx, j[i], ptr + "/" + std::to_string(i));
    TransferPoint p;
    const double value = number(ctx, r.require("value"), r.at("value"), -1e30, 1e30);
    p.value = float(value);
    if (const json* v = r.take("color")) p.color = color(ctx, *v, r.at("color"));
    p.opacity = float(number(ctx, r.require("opacity"), r.at("opacity"), 0, 1));
    if (const json* v = r.take("importance"))
      p.importance = float(number(ctx, *v, r.at("importance"), 0, 1));
    r.finish();
    if (!points.empty() && !(p.value > points.back().value))
      ctx.fail(r.at("value"), value > double(points.back().value)
                                  ? "control points must have increasing values as 32-bit floats"
                                  : "control points must have increasing values");
    points.push_back(p);
  }
  return points;
}

// A two-dimensional transfer function: rows {gradient, points} in increasing gradient magnitude.
TransferFunction transferFunction2D(const Context& ctx, const json& j, const std::string& ptr) {
  if (!j.is_array() || j.empty())
    ctx.fail(ptr, "expected an array of rows {\"gradient\", \"points\"}");
  TransferFunction tf;
  for (std::size_t i = 0; i < j.size(); ++i) {
    ObjectReader r(ctx, j[i], ptr + "/" + std::to_string(i));
    TransferFunction::Row row;
    row.gradient = float(number(ctx, r.require("gradient"), r.at("gradient"), 0, 1e30));
    row.points = transferPoints(ctx, r.require("points"), r.at("points"));
    r.finish();
    if (!tf.rows.empty() && !(row.gradient > tf.rows.back().gradient))
      ctx.fail(r.at("gradient"), "rows must have increasing gradient magnitudes");
    tf.rows.push_back(std::move(row));
  }
  return tf;
}

std::any techniqueOptions(const Context& ctx, const OptionsSchema& schema, const json& j,
                          const std::string& ptr, bool trueMeansDefaults);

void readVolume(const Context& ctx, const json& j, const std::string& ptr,
                const SceneArrays& arrays, Scene& scene) {
  ObjectReader r(ctx, j, ptr);
  SceneVolume v;
  v.name = name(ctx, r.require("name"), r.at("name"), "volume");
  std::filesystem::path file;
  if (const json* a = r.take("arrays")) {
    if (r.has("file")) ctx.fail(ptr, "a volume needs one of \"file\" or \"arrays\", not both");
    v.volume = arraysEntry(ctx, *a, r.at("arrays"), arrays.volumes);
    v.source = "arrays " + a->get<std::string>();
  } else {
    file = string(ctx, r.require("file"), r.at("file"));
    if (file.is_relative()) file = ctx.baseDir / file;
    v.source = file.string();
  }
  if (const json* t = r.take("transform"))
    v.transform = glm::mat4(transform(ctx, *t, r.at("transform")));
  if (const json* t = r.take("role")) v.role = role(ctx, *t, r.at("role"));
  if (const json* t = r.take("cutBy")) {
    std::vector<std::string> keys;
    for (const CutterType& type : cutterTypes()) keys.push_back(type.key);
    if (!t->is_array()) ctx.fail(r.at("cutBy"), "expected an array of cutter names");
    v.cutBy.emplace();
    for (std::size_t i = 0; i < t->size(); ++i)
      v.cutBy->push_back(oneOf(ctx, (*t)[i], r.at("cutBy") + "/" + std::to_string(i), keys));
  }
  const json* oneD = r.take("transferFunction");
  const json* twoD = r.take("transferFunction2D");
  if (oneD && twoD)
    ctx.fail(r.at("transferFunction2D"),
             "give \"transferFunction\" or \"transferFunction2D\", not both");
  if (twoD)
    v.transfer = transferFunction2D(ctx, *twoD, r.at("transferFunction2D"));
  else
    v.transfer.rows = {{0.0f, transferPoints(ctx, oneD ? *oneD : r.require("transferFunction"),
                                             r.at("transferFunction"))}};
  if (const json* t = r.take("mode")) {
    const std::string mode = oneOf(ctx, *t, r.at("mode"), {"composite", "maximum", "isosurface"});
    v.mode = mode == "maximum"      ? VolumeMode::Maximum
             : mode == "isosurface" ? VolumeMode::Isosurface
                                    : VolumeMode::Composite;
  }
  if (const json* t = r.take("isoValue"))
    v.isoValue = float(number(ctx, *t, r.at("isoValue"), -1e30, 1e30));
  else if (v.mode == VolumeMode::Isosurface)
    ctx.fail(ptr, "the isosurface mode needs an \"isoValue\"");
  if (const json* t = r.take("sampleDistance"))
    v.sampleDistance = float(number(ctx, *t, r.at("sampleDistance"), 0.05, 8));
  if (const json* t = r.take("opacityDistance"))
    v.opacityDistance = float(number(ctx, *t, r.at("opacityDistance"), 0.05, 1000));
  if (const json* t = r.take("shading")) v.shading = boolean(ctx, *t, r.at("shading"));
  if (const json* t = r.take("jitter")) v.jitter = boolean(ctx, *t, r.at("jitter"));
  if (const json* t = r.take("shadows")) v.shadows = boolean(ctx, *t, r.at("shadows"));
  if (const json* t = r.take("labels")) v.labels = boolean(ctx, *t, r.at("labels"));
  if (const json* t = r.take("lines"))
    v.lines = std::any_cast<VolumeLineStyle>(
        techniqueOptions(ctx, volumeLineStyleSchema(), *t, r.at("lines"), false));
  r.finish();
  if (v.labels) {
    if (twoD)
      ctx.fail(r.at("transferFunction2D"),
               "a label volume's materials are per label (use \"transferFunction\")");
    // One texel per label between the first and the last (kinds/volumes' table).
    const std::vector<TransferPoint>& points = v.transfer.rows.front().points;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (points[i].value != std::round(points[i].value))
        ctx.fail(r.at("transferFunction") + "/" + std::to_string(i) + "/value",
                 "a label volume's points are whole label values");
    if (const double span = double(points.back().value) - double(points.front().value);
        span >= 65536) {
      char labels[32];  // the labels from the first to the last, as kinds/volumes counts them
      std::snprintf(labels, sizeof labels, "%.0f", span + 1.0);
      ctx.fail(r.at("transferFunction"),
               std::string("its labels span ") + labels +
                   " values, more than a GPU's 2-D texture holds (its size less 2: 16382 on "
                   "llvmpipe)");
    }
    if (v.mode == VolumeMode::Isosurface)
      ctx.fail(r.at("labels"), "a label volume is drawn in the composite or maximum mode");
    if (v.lines) ctx.fail(r.at("lines"), "a label volume has no isosurfaces to draw lines of");
  }
  if (!v.volume) {
    try {
      v.volume = std::make_shared<const Volume>(importVolume(file));
    } catch (const Error& e) {
      ctx.fail(r.at("file"), e.what());
    }
  }
  scene.volumes.push_back(std::move(v));
}

Camera camera(const Context& ctx, const json& j, const std::string& ptr) {
  ObjectReader r(ctx, j, ptr);
  Camera c;
  if (const json* v = r.take("projection"))
    c.projection =
        oneOf(ctx, *v, r.at("projection"), {"perspective", "orthographic"}) == "perspective"
            ? Projection::Perspective
            : Projection::Orthographic;
  if (const json* v = r.take("fit")) c.fit = boolean(ctx, *v, r.at("fit"));
  if (const json* v = r.take("path")) c.path = cameraPath(ctx, *v, r.at("path"));
  const json* eye = r.take("eye");
  const json* target = r.take("target");
  if (!c.fit && c.path.empty() && (!eye || !target))
    ctx.fail(ptr, "a camera needs \"eye\" and \"target\", a \"path\", or \"fit\": true");
  if (!c.path.empty() && !eye && !target)
    c.eye = c.path.front().eye, c.target = c.path.front().target;
  if (eye) c.eye = cameraPoint(ctx, *eye, r.at("eye"));
  if (target) c.target = cameraPoint(ctx, *target, r.at("target"));
  // A fitted camera whose eye and target coincide takes a default direction
  // (Scene::resolvedCamera).
  if (eye && target && !c.fit && coincide(c.eye, c.target)) ctx.fail(r.at("eye"), kCoincide);
  if (const json* v = r.take("up")) c.up = direction(ctx, *v, r.at("up"));
  for (std::size_t i = 0; i < c.path.size(); ++i)
    if (glm::length(glm::cross(glm::normalize(c.path[i].eye - c.path[i].target), c.up)) < 1e-6f)
      ctx.fail(r.at("path") + "/" + std::to_string(i), "up is parallel to the viewing direction");
  // Checked on the defaults too: "fit" keeps the direction eye − target, whichever gave it.
  if (!coincide(c.eye, c.target) &&
      glm::length(glm::cross(glm::normalize(c.eye - c.target), c.up)) < 1e-6f)
    ctx.fail(r.at("up"), "up is parallel to the viewing direction");
  if (const json* v = r.take("fov")) c.fovY = float(number(ctx, *v, r.at("fov"), 1, 170));
  if (const json* v = r.take("height"))
    c.height = float(number(ctx, *v, r.at("height"), kMinSceneDetail, 1e30));
  if (const json* v = r.take("near"))
    c.near = float(number(ctx, *v, r.at("near"), kMinSceneDetail, 1e30));
  if (const json* v = r.take("far"))
    c.far = float(number(ctx, *v, r.at("far"), kMinSceneDetail, 1e30));
  if (c.near > 0 && c.far > 0 && c.far <= c.near)
    ctx.fail(r.at("far"), "far must be greater than near");
  r.finish();
  return c;
}

Light light(const Context& ctx, const json& j, const std::string& ptr) {
  ObjectReader r(ctx, j, ptr);
  Light l;
  l.type = oneOf(ctx, r.require("type"), r.at("type"), {"directional", "point"}) == "point"
               ? Light::Type::Point
               : Light::Type::Directional;
  if (l.type == Light::Type::Directional)
    l.direction = direction(ctx, r.require("direction"), r.at("direction"));
  else
    l.position = vec3(ctx, r.require("position"), r.at("position"));
  if (const json* v = r.take("color")) l.color = color(ctx, *v, r.at("color"));
  if (const json* v = r.take("intensity"))
    l.intensity = float(number(ctx, *v, r.at("intensity"), 0, 1e6));
  if (const json* v = r.take("space"))
    l.cameraSpace = oneOf(ctx, *v, r.at("space"), {"camera", "world"}) == "camera";
  r.finish();
  return l;
}

GeoFrame geoFrame(const Context& ctx, const json& j, const std::string& ptr) {
  GeoFrame g;
  ObjectReader r(ctx, j, ptr);
  if (const json* v = r.take("crs")) {
    g.crs = string(ctx, *v, r.at("crs"));
    if (!gisCrsKnown(g.crs)) ctx.fail(r.at("crs"), "unknown CRS " + quote(g.crs));
  }
  if (const json* v = r.take("offset")) {
    if (!v->is_array() || (v->size() != 2 && v->size() != 3))
      ctx.fail(r.at("offset"), "expected [easting, northing] or [easting, northing, height]");
    for (std::size_t i = 0; i < v->size(); ++i)
      g.offset[int(i)] =
          number(ctx, (*v)[i], r.at("offset") + "/" + std::to_string(i), -1e12, 1e12);
  }
  r.finish();
  return g;
}

// One technique's options from `j` (true: its defaults; an object: its keys), by its schema.
std::any techniqueOptions(const Context& ctx, const OptionsSchema& schema, const json& j,
                          const std::string& ptr, bool trueMeansDefaults) {
  std::any options = schema.makeDefault();
  if (trueMeansDefaults && j.is_boolean()) {
    if (!j.get<bool>()) ctx.fail(ptr, "use true or an object (leave the key out to disable)");
    const json empty = json::object();
    ObjectReader r(ctx, empty, ptr);  // the required keys still must be given
    schema.read(ctx, r, schema.data(options));
    return options;
  }
  ObjectReader r(ctx, j, ptr);
  schema.read(ctx, r, schema.data(options));
  r.finish();
  return options;
}

// "cutters": each registered cutter's options under its key.
void readCutters(const Context& ctx, const json& j, Scene& scene) {
  ObjectReader r(ctx, j, "/cutters");
  for (const CutterType& type : cutterTypes()) {
    if (!type.schema) continue;
    if (const json* v = r.take(type.key))
      scene.cutters.set(type.key,
                        techniqueOptions(ctx, *type.schema, *v, r.at(type.key), true));
  }
  r.finish();
}

// "style": a style's name, or its name, lines, shadows and each shading style's options.
Style style(const Context& ctx, const json& j, const std::string& ptr) {
  Style s;
  if (j.is_string()) {
    s.name = oneOf(ctx, j, ptr, styleNames());
    return s;
  }
  if (!j.is_object()) ctx.fail(ptr, "expected a style's name or an object, got " + typeName(j));
  ObjectReader r(ctx, j, ptr);
  for (const StyleType& type : styleTypes())
    if (const json* v = r.take(type.key))
      s.shading.set(type.key, techniqueOptions(ctx, *type.schema, *v, r.at(type.key), false));
  styleSchema().read(ctx, r, &s);
  r.finish();
  return s;
}

// Names unique across objects and volumes, and everything within float reach. Also what the
// file's reader checks where it reads a name or a colour, for objects made otherwise (a
// split file's nodes, the Python module's arrays).
void checkNamesAndReach(const Context& ctx, const Scene& scene) {
  std::set<std::string> names;
  std::size_t proxies = 0;  // the proxies follow the objects, in the file's order
  for (const auto& o : scene.objects) {
    if (o.name.empty() || o.name.size() > kMaxNameLength)
      ctx.fail("/objects", "an object name of " + std::to_string(o.name.size()) +
                               " characters (1 to " + std::to_string(kMaxNameLength) + ")");
    if (const std::size_t at = o.name.find('\0'); at != std::string::npos)
      ctx.fail("/objects", "an object name holds a NUL character (at " + std::to_string(at) + ")");
    const glm::vec3 c = o.material.color;
    if (!(glm::all(glm::greaterThanEqual(c, glm::vec3(0.0f))) &&
          glm::all(glm::lessThanEqual(c, glm::vec3(1.0f)))))
      ctx.fail("/objects", quote(o.name) + " has the colour [" + std::to_string(c.r) + ", " +
                               std::to_string(c.g) + ", " + std::to_string(c.b) +
                               "], outside [0, 1]");
    const bool fresh = names.insert(o.name).second;
    if (o.proxy && !fresh)
      ctx.fail("/proxies/" + std::to_string(proxies) + "/name",
               "the name " + quote(o.name) + " is taken");
    if (!fresh) ctx.fail("/objects", "two objects are named " + quote(o.name));
    proxies += o.proxy;
  }
  for (std::size_t i = 0; i < scene.volumes.size(); ++i)
    if (!names.insert(scene.volumes[i].name).second)
      ctx.fail("/volumes/" + std::to_string(i) + "/name",
               "the name " + quote(scene.volumes[i].name) + " is taken");
  // Within kMaxSceneReach; nearer, far coordinates render with a warning (the CLI names the
  // farthest part). At least kMinSceneDetail across.
  const auto checkReach = [&](const std::string& ptr, const std::string& name, const Bounds& b) {
    if (b.empty()) return;
    const float reach = sceneReach(glm::max(glm::abs(b.min), glm::abs(b.max)));
    const float across = sceneReach(b.max - b.min);
    std::ostringstream message;
    if (!(reach <= kMaxSceneReach))  // NaN and infinity fail too
      message << "\"" << name << "\" reaches " << reach
              << " scene units from the origin; 32-bit floats cannot render beyond 1e15 (scale "
                 "it down or move it nearer)";
    else if (across < kMinSceneDetail)
      message << "\"" << name << "\" measures " << across
              << " scene units across; 32-bit floats cannot shade a part smaller than 1e-15 "
                 "(scale it up)";
    else
      return;
    ctx.fail(ptr, message.str());
  };
  std::size_t proxy = 0;  // proxies keep the order of their entries; objects, split, do not
  for (const auto& o : scene.objects)
    checkReach(o.proxy ? "/proxies/" + std::to_string(proxy++) : "/objects", o.name,
               o.worldBounds());
  for (std::size_t i = 0; i < scene.volumes.size(); ++i) {
    const SceneVolume& v = scene.volumes[i];
    const std::string ptr = "/volumes/" + std::to_string(i);
    checkReach(ptr, v.name, v.worldBounds());
    const glm::dmat3 m(glm::dmat4(v.indexToWorld()));
    const double voxel = std::min({glm::length(m[0]), glm::length(m[1]), glm::length(m[2])});
    if (voxel < kMinSceneDetail) {
      std::ostringstream message;
      message << "\"" << v.name << "\" has voxels " << voxel
              << " scene units apart; 32-bit floats cannot shade voxels nearer than 1e-15 (scale "
                 "it up)";
      ctx.fail(ptr, message.str());
    }
  }
  for (const auto& n : scene.networks) checkReach("/networks", n.name, n.bounds());
}

// What a scene file gets once its parts are read: names, reach, and the cutters' checks
// across the scene (the roles they need, the network to open above).
void checkAcross(const Context& ctx, Scene& scene) {
  checkNamesAndReach(ctx, scene);
  for (const CutterType& type : cutterTypes())
    if (type.complete && scene.cutters.find(type.key))
      type.complete(ctx, "/cutters/" + type.key, scene);
}

}  // namespace

Scene parseScene(const std::string& text, const std::filesystem::path& displayName,
                 const std::filesystem::path& baseDir, const SceneArrays& arrays) {
  Context ctx{displayName.string(), baseDir, {}};
  const json root = parse(ctx, text);
  Scene scene;
  scene.file = displayName;
  ObjectReader r(ctx, root, "");
  if (const json* v = r.take("version"))
    if (integer(ctx, *v, "/version", 1, 1) != 1) ctx.fail("/version", "unsupported version");
  if (const json* v = r.take("geo")) ctx.geo = scene.geo = geoFrame(ctx, *v, "/geo");
  if (const json* v = r.take("resolution")) {
    if (!v->is_array() || v->size() != 2) ctx.fail("/resolution", "expected [width, height]");
    scene.width = integer(ctx, (*v)[0], "/resolution/0", 1, 16384);
    scene.height = integer(ctx, (*v)[1], "/resolution/1", 1, 16384);
  }
  if (const json* v = r.take("samples")) {
    scene.samples = integer(ctx, *v, "/samples", 1, 16);
    if (scene.samples & (scene.samples - 1))
      ctx.fail("/samples", "samples must be 1, 2, 4, 8 or 16");
  }
  if (const json* v = r.take("pixelError"))
    scene.pixelError = float(number(ctx, *v, "/pixelError", 0.0, 100.0));
  if (const json* v = r.take("background")) {
    if (v->is_array()) {
      scene.backgroundTop = scene.backgroundBottom = color(ctx, *v, "/background");
    } else {
      ObjectReader br(ctx, *v, "/background");
      scene.backgroundTop = color(ctx, br.require("top"), "/background/top");
      scene.backgroundBottom = color(ctx, br.require("bottom"), "/background/bottom");
      br.finish();
    }
  }
  if (const json* v = r.take("style")) scene.style = style(ctx, *v, "/style");
  if (const json* v = r.take("cutters")) readCutters(ctx, *v, scene);
  if (const json* v = r.take("lights")) {
    if (!v->is_array()) ctx.fail("/lights", "expected an array, got " + typeName(*v));
    if (v->size() > kMaxLights)
      ctx.fail("/lights", "at most " + std::to_string(kMaxLights) + " lights, got " +
                              std::to_string(v->size()));
    for (std::size_t i = 0; i < v->size(); ++i)
      scene.lights.push_back(light(ctx, (*v)[i], "/lights/" + std::to_string(i)));
  } else {
    scene.lights.push_back(Light{});  // a key light over the viewer's right shoulder
  }

  MeshCache cache;
  // Pipe networks or volumes alone make a scene (Konev18's pipes without terrain, a CT);
  // otherwise objects.
  const bool networks = r.has("networks"), volumes = r.has("volumes");
  const json noObjects = json::array();
  const json& objects =
      (networks || volumes) && !r.has("objects") ? noObjects : r.require("objects");
  if (!objects.is_array()) ctx.fail("/objects", "expected an array, got " + typeName(objects));
  if (objects.empty() && !networks && !volumes)
    ctx.fail("/objects", "a scene needs at least one object, pipe network or volume");
  for (std::size_t i = 0; i < objects.size(); ++i)
    readObject(ctx, objects[i], "/objects/" + std::to_string(i), cache, arrays, scene.objects);
  if (const json* v = r.take("proxies")) {
    if (!v->is_array()) ctx.fail("/proxies", "expected an array, got " + typeName(*v));
    for (std::size_t i = 0; i < v->size(); ++i)
      readProxy(ctx, (*v)[i], "/proxies/" + std::to_string(i), scene.objects);
  }
  if (const json* v = r.take("networks")) readNetworks(ctx, *v, "/networks", scene);
  if (const json* v = r.take("volumes")) {
    if (!v->is_array() || v->empty()) ctx.fail("/volumes", "expected an array of volumes");
    for (std::size_t i = 0; i < v->size(); ++i)
      readVolume(ctx, (*v)[i], "/volumes/" + std::to_string(i), arrays, scene);
  }
  checkAcross(ctx, scene);
  // The camera may "fit" to the objects, so it is read after them.
  if (const json* v = r.take("camera"))
    scene.camera = camera(ctx, *v, "/camera");
  else
    scene.camera.fit = true;
  r.finish();
  return scene;
}

void appendVolume(Scene& scene, const std::string& text, const std::string& displayName,
                  const std::filesystem::path& baseDir, const SceneArrays& arrays) {
  const Context ctx{displayName, baseDir, scene.geo};
  Scene grown = scene;  // the scene is left as it was when the entry fails
  readVolume(ctx, parse(ctx, text), "", arrays, grown);
  checkAcross(ctx, grown);
  scene = std::move(grown);
}

void checkScene(Scene& scene, const std::string& displayName) {
  const Context ctx{displayName, {}, scene.geo};
  // Options set in memory (`--set`, the Python module) skipped their schema's checks: each
  // enabled cutter's options are written and read back through it (required keys, patterns,
  // the checks across its keys).
  for (const CutterType& type : cutterTypes()) {
    const std::any* options = type.schema ? scene.cutters.find(type.key) : nullptr;
    if (!options) continue;
    const json written = json::parse(type.schema->write(type.schema->data(*options)).dump());
    std::any read = type.schema->makeDefault();
    ObjectReader r(ctx, written, "/cutters/" + type.key);
    type.schema->read(ctx, r, type.schema->data(read));
    r.finish();
  }
  checkAcross(ctx, scene);
}

Scene loadScene(const std::filesystem::path& path) {
  // A device or FIFO given as the scene (/dev/zero) would be read without end.
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw Error(path.string(), "", "not a regular file");
  constexpr std::uintmax_t kMaxSceneBytes = std::uintmax_t(1) << 30;
  if (const std::uintmax_t size = std::filesystem::file_size(path, ec);
      !ec && size > kMaxSceneBytes)
    throw Error(path.string(), "",
                "scene file of " + std::to_string(size >> 20) + " MiB (the limit is 1 GiB)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string(), "", "cannot open scene file");
  std::stringstream text;
  text << in.rdbuf();
  return parseScene(text.str(), path, path.parent_path());
}

}  // namespace cutaway
