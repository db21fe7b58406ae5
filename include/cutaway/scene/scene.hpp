// cutaway/scene/scene.hpp — the scene model: objects with roles and importance, invisible
// proxies, camera, lights, background, resolution and style.
//
// Scenes are usually loaded from JSON (docs/scene-format.md) with `loadScene`, which also
// imports the meshes. Roles follow the papers' vocabulary: objects of `interest` are exposed
// (Burns08), `context` objects are cut away where they hide them; `exterior` and `interior`
// are Diepstraten03's outside and inside objects.
//
//   cutaway::Scene scene = cutaway::loadScene("examples/engine.json");   // throws cutaway::Error
//   for (const auto& object : scene.objects) std::puts(object.name.c_str());
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <regex>
#include <string>
#include <variant>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cutaway/core/geo_frame.hpp"
#include "cutaway/geometry/mesh.hpp"
#include "cutaway/geometry/pipe_network.hpp"
#include "cutaway/geometry/volume.hpp"
#include "cutaway/scene/camera.hpp"
#include "cutaway/scene/settings.hpp"
#include "cutaway/styles/emphasis.hpp"
#include "cutaway/styles/lines.hpp"
#include "cutaway/styles/shadows.hpp"
#include "cutaway/styles/volume_lines.hpp"

namespace cutaway {

enum class Role { Context, Interest, Exterior, Interior };
const char* roleName(Role role);
// Every role, in the order of the enum; and the role of a scene file's name (nullopt: none).
inline constexpr Role kRoles[] = {Role::Context, Role::Interest, Role::Exterior, Role::Interior};
std::optional<Role> roleFromName(const std::string& name);

struct Material {
  glm::vec3 color{0.75f};
  float specular = 0.25f;   // Blinn-Phong specular weight
  float shininess = 32.0f;  // Blinn-Phong exponent
};

// Per-object parameters: values by name; which names exist is declared by the cutters and
// styles in `objectParameterSpecs()` and validated at load time.
using ParamValue = std::variant<bool, double>;
using ObjectParams = std::map<std::string, ParamValue>;

struct ObjectParamSpec {
  std::string name;
  enum class Type { Bool, Number } type;
  double min = 0, max = 0;  // for numbers
  std::string meaning;
};
const std::vector<ObjectParamSpec>& objectParameterSpecs();

// Translation, rotation, scale; as a matrix T·R·S.
struct Trs {
  glm::vec3 translate{0.0f};
  glm::quat rotate{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 scale{1.0f};
  glm::mat4 matrix() const;
};

// A keyframe of an object's motion (Burns08 Fig. 10: objects moving through the scene).
struct Keyframe {
  float time;  // seconds
  Trs trs;
};

// Meshes a pipe network contributes to the object list (Konev18): the shafts' two cylinders,
// which the §7 wedge cuts and colours by layer, the joints at sharp bends, and the tessellated
// pipes of the meshed mode.
enum class NetworkPart { None, ShaftOuter, ShaftInner, Joints, MeshedPipes };

struct SceneObject {
  std::string name;
  // Another name that name patterns match: a file's own place for a node it leaves unnamed
  // ("engine/nodes[74]", ImportedNode::id), so that scenes written for it keep working; "".
  std::string alias;
  NetworkPart networkPart = NetworkPart::None;
  int network = -1;    // index in Scene::networks of the network it belongs to
  std::string group;   // optional group name ("" = none)
  std::string source;  // "file" or "file#node" it came from, or "proxy"
  Role role = Role::Context;
  float importance = 0.5f;  // in [0, 1]
  bool proxy = false;       // invisible: seen only by cutters (Burns11 §4.2.2)
  Material material;
  ObjectParams params;
  // The cutters (by their keys under "cutters") that may cut it, each by its own rule; unset:
  // every cutter. E.g. only "terrainOpening" for a terrain that an adaptive cutaway around the
  // pipes below must leave to Konev18's opening.
  std::optional<std::vector<std::string>> cutBy;
  std::shared_ptr<const Mesh> mesh;  // in object space
  // Coarser versions of `mesh` for far views (a network's shafts with fewer sides), finest
  // first, each with its geometric error: how far its surface may lie from the mesh's, in
  // object space. The renderer draws the coarsest whose error spans at most
  // Scene::pixelError pixels at the object's nearest point.
  struct Coarser {
    float error = 0.0f;
    std::shared_ptr<const Mesh> mesh;
  };
  std::vector<Coarser> coarser;
  glm::mat4 transform{1.0f};  // object → world
  // Motion, applied on top of `transform`: world = K(t)·transform, with K interpolated
  // between keyframes (translation and scale linearly, rotation by slerp), held at the ends.
  std::vector<Keyframe> animation;

  glm::mat4 transformAt(float time) const;
  bool mayBeCutBy(const std::string& cutter) const {
    return !cutBy || std::find(cutBy->begin(), cutBy->end(), cutter) != cutBy->end();
  }
  // Whether a cut shows the inside as solid material: param "solid", else watertightness.
  bool solid() const;
  // Whether its back faces are drawn where no cutter cuts it: param "doubleSided", else true.
  bool doubleSided() const;
  // Whether it takes feature lines, its ghost lines too: param "lines", else true.
  bool takesLines() const;
  // Whether `pattern` matches its name or its alias (the whole of either).
  bool named(const std::regex& pattern) const;
  // Bounds in world space over the whole animation (at every keyframe).
  Bounds worldBounds() const;
};

// A volume's transfer function: control points over its values (in the file's units),
// interpolated linearly and held at the ends. Each point carries an importance, so that the
// material a component stands for is emphasised and reduced like an object of that
// importance (Burns11 §3.2, §7.1: bone and vessels important, soft tissue not).
struct TransferPoint {
  float value = 0.0f;
  glm::vec3 color{1.0f};
  float opacity = 0.0f;     // per unit of `SceneVolume::opacityDistance`
  float importance = 0.5f;  // in [0, 1]
  bool operator==(const TransferPoint&) const = default;
};
// Two-dimensional over value × gradient magnitude (Kniss, Kindlmann, Hansen 2002): rows of
// control points at increasing gradient magnitudes (value units per world unit), interpolated
// linearly between the rows and held beyond the first and last, so that material boundaries
// (large gradients) and the inside of materials (small ones) of equal value are told apart.
// One row: a function of the value alone.
struct TransferFunction {
  struct Row {
    float gradient = 0.0f;
    std::vector<TransferPoint> points;  // increasing values, at least one
    bool operator==(const Row&) const = default;
  };
  std::vector<Row> rows;  // increasing gradients, at least one
  TransferPoint at(float value, float gradient = 0.0f) const;
  bool twoDimensional() const { return rows.size() > 1; }
  // The largest opacity of `value` at any gradient magnitude (at a row: the rows mix convexly).
  float maxOpacity(float value) const;
  // Whether some value in [lo, hi] has opacity at some gradient magnitude: the rows' opacities
  // are largest at the interval's ends or at a control point inside it.
  bool opaqueSomewhere(float lo, float hi) const;
  bool operator==(const TransferFunction&) const = default;
};

enum class VolumeMode {
  Composite,   // emission–absorption, front to back
  Maximum,     // maximum intensity projection
  Isosurface,  // the first crossing of `isoValue`, shaded as a surface
};
const char* volumeModeName(VolumeMode mode);

// A scalar volume drawn by ray casting (src/kinds/volumes): placed by its file's voxel-to-world
// matrix, then `transform`.
struct SceneVolume {
  std::string name;
  std::string source;  // the file it came from
  Role role = Role::Context;
  std::optional<std::vector<std::string>> cutBy;  // as SceneObject::cutBy
  std::shared_ptr<const Volume> volume;
  glm::mat4 transform{1.0f};
  TransferFunction transfer;
  VolumeMode mode = VolumeMode::Composite;
  float isoValue = 0.0f;
  // Ray step in voxels (of the smallest spacing); the opacities hold per `opacityDistance`
  // voxels and are corrected for the step (α' = 1 − (1 − α)^(step/opacityDistance)).
  float sampleDistance = 0.5f;
  float opacityDistance = 1.0f;
  bool shading = true;  // gradient normals shaded by the style; false: emission only
  bool jitter = true;   // ray starts offset per pixel (against wood-grain artefacts)
  // Its material shadows the key light for its own shaded samples (a shadow ray per sample).
  bool shadows = false;
  // A label volume (an atlas, a segmentation): integer values sampled at the nearest voxel,
  // each transfer-function point one label's material; labels it does not list are clear.
  bool labels = false;
  // Line drawings of its isosurfaces (Burns11 §2.4); nullopt: none.
  std::optional<VolumeLineStyle> lines;

  // The material of a value at a gradient magnitude: the transfer function's, or the label's.
  TransferPoint material(float value, float gradient = 0.0f) const;
  // Whether any sample of `value`, or of a value in [lo, hi], can have opacity (at any
  // gradient magnitude; a label volume: a listed label's).
  bool mayBeVisible(float value) const {
    return labels ? material(value).opacity > 0.0f : transfer.maxOpacity(value) > 0.0f;
  }
  bool mayBeVisible(float lo, float hi) const;

  glm::mat4 indexToWorld() const { return transform * volume->indexToWorld; }
  // Its inverse, worked out in doubles: in floats the determinant of voxels 1e-13 across
  // (1e-39) underflows.
  glm::mat4 worldToIndex() const { return glm::mat4(glm::inverse(glm::dmat4(indexToWorld()))); }
  Bounds worldBounds() const { return volume->indexBounds().transformed(indexToWorld()); }
  bool mayBeCutBy(const std::string& cutter) const {
    return !cutBy || std::find(cutBy->begin(), cutBy->end(), cutter) != cutBy->end();
  }
};

struct Light {
  enum class Type { Directional, Point } type = Type::Directional;
  glm::vec3 direction{-0.4f, -0.6f, -1.0f};  // direction the light travels (directional)
  glm::vec3 position{0.0f};                  // point lights
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  bool cameraSpace = true;  // direction/position given in eye space
};

// The style: the shading style by name (one of styleNames(): cutaway/styles/<name>.hpp holds
// its options), the feature lines, shadows and emphasis by importance applied with every
// style, and each shading style's options by its key (unset ones are their defaults).
struct Style {
  std::string name = "gooch";
  std::optional<LineStyle> lines = LineStyle{};  // nullopt: no lines
  ShadowStyle shadows;
  EmphasisStyle emphasis;
  TechniqueSettings shading;  // "style": {"gooch": {…}, "toon": {…}}
  template <class O>
  const O& get() const {
    static const O kDefaults{};
    const O* o = shading.find<O>();
    return o ? *o : kDefaults;
  }
  template <class O>
  O& edit() {
    return shading.enable<O>();
  }
};

struct Scene {
  std::filesystem::path file;  // where it was loaded from, for messages
  std::vector<SceneObject> objects;
  Camera camera;
  std::vector<Light> lights;
  glm::vec3 backgroundTop{1.0f}, backgroundBottom{1.0f};
  int width = 800, height = 600;
  int samples = 4;  // MSAA samples of the final image
  // Pixels of screen-space error a grid mesh (a terrain) may show where its chunks are drawn
  // coarser (cutaway/geometry/grid_lod.hpp), and an object with coarser versions
  // (SceneObject::coarser) where one is drawn instead; 0 draws every triangle.
  float pixelError = 0.5f;
  Style style;
  GeoFrame geo;                                         // "geo": {"crs": …, "offset": […]}
  // "cutters": {…}: each enabled cutter's options (cutaway/cutters/<name>.hpp) by its key.
  TechniqueSettings cutters;
  // Konev18 pipe networks drawn as billboards ("networks": […]). Their object ids in the
  // renderer's id buffer follow the objects': objects.size() + network index.
  std::vector<PipeNetwork> networks;
  std::vector<SceneVolume> volumes;  // "volumes": […]

  // Bounds of the visible (non-proxy) objects, networks and volumes in world space.
  Bounds bounds() const;
  // Resolves "fit" and derived near/far planes into concrete camera values.
  Camera resolvedCamera() const { return resolvedCamera(0.0f); }
  // The same at `time`: the camera path (if any) interpolated, then resolved.
  Camera resolvedCamera(float time) const;
  // Length of the animation: the last keyframe or camera key (0 for a still scene).
  float duration() const;
  const SceneObject* find(const std::string& name) const;
  // Burns11 §3.2: gives `importance` (in [0, 1]) to every object whose name or group the
  // regular expression `pattern` matches whole; returns how many. Throws cutaway::Error for a
  // bad pattern, a value outside [0, 1], or a pattern that matches nothing.
  std::size_t setImportance(const std::string& pattern, float importance);
  // Gives `role` to every object (not proxy) whose name or group, and every volume whose name,
  // `pattern` matches whole; returns how many. Throws as setImportance does.
  std::size_t setRole(const std::string& pattern, Role role);
};

// The object a network contributes for `part` ("NAME/shafts", "NAME/shaft-insides",
// "NAME/joints", "NAME/pipes"): an object of interest in the network's colours (the shaft
// insides in its cut colour, §7), its topology analysed; `network` is its index.
SceneObject networkObject(const PipeNetwork& net, int network, NetworkPart part, Mesh mesh);
// The shafts' outer or inner cylinders as networkObject gives them (32 sides), with coarser
// versions of 16, 8 and 4 sides for far views: an n-gon strays r (1 − cos(π/n)) from the
// circle through its corners.
SceneObject shaftObject(const PipeNetwork& net, int network, bool inner);

// Simplified versions (cutaway/geometry/simplify.hpp) as the coarser versions of every object
// otherwise drawn whole (its mesh no grid, no coarser versions of its own), so that renderers
// draw each at the coarsest whose measured error spans at most Scene::pixelError pixels: the
// viewer's frames while its view moves, `cutaway render --simplify`. `cache` keeps the
// versions by mesh between calls (of the scene's meshes only); meshes are simplified on the
// hardware's threads.
using SimplifiedCache = std::map<std::shared_ptr<const Mesh>, std::vector<SceneObject::Coarser>>;
void addSimplifiedVersions(Scene& scene, SimplifiedCache& cache);

// Loads and validates a scene file and imports its meshes; throws cutaway::Error naming the
// file, the JSON pointer and the reason.
Scene loadScene(const std::filesystem::path& path);
// Meshes and volumes held in memory rather than in files (the Python module's NumPy arrays):
// an object or volume entry names one by "arrays": KEY in place of its "file".
struct SceneArrays {
  std::map<std::string, std::shared_ptr<const Mesh>> meshes;
  std::map<std::string, std::shared_ptr<const Volume>> volumes;
};
// Same, from JSON text; relative mesh paths resolve against `baseDir`.
Scene parseScene(const std::string& text, const std::filesystem::path& displayName,
                 const std::filesystem::path& baseDir, const SceneArrays& arrays = {});
// Adds one "volumes" entry given as JSON text to `scene`, checked as in a scene file; on an
// error the scene is unchanged.
void appendVolume(Scene& scene, const std::string& text, const std::string& displayName,
                  const std::filesystem::path& baseDir, const SceneArrays& arrays = {});
// The checks a scene file gets after its parts are read, for a scene changed in memory (roles
// set, objects added, options set by path): each enabled cutter's options as its schema reads
// them (required keys, valid patterns, the checks across its keys), names unique, everything
// within float reach, each enabled cutter's needs (the roles it cuts or keeps), and what the
// cutters complete from the scene (a terrain opening's lines from its networks). Errors name
// `displayName`.
void checkScene(Scene& scene, const std::string& displayName);

}  // namespace cutaway
