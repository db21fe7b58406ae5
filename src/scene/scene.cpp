#include "cutaway/scene/scene.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>
#include <regex>
#include <set>

#include "core/name_pattern.hpp"
#include "core/worker_threads.hpp"
#include "cutaway/core/error.hpp"
#include "cutaway/geometry/simplify.hpp"

namespace cutaway {

std::optional<Role> roleFromName(const std::string& name) {
  for (const Role r : kRoles)
    if (name == roleName(r)) return r;
  return std::nullopt;
}

const char* roleName(Role role) {
  switch (role) {
    case Role::Context:
      return "context";
    case Role::Interest:
      return "interest";
    case Role::Exterior:
      return "exterior";
    case Role::Interior:
      return "interior";
  }
  return "?";
}

const char* volumeModeName(VolumeMode mode) {
  switch (mode) {
    case VolumeMode::Composite:
      return "composite";
    case VolumeMode::Maximum:
      return "maximum";
    case VolumeMode::Isosurface:
      return "isosurface";
  }
  return "?";
}

TransferPoint SceneVolume::material(float value, float gradient) const {
  if (!labels) return transfer.at(value, gradient);
  const float label = std::round(value);
  for (const TransferPoint& p : transfer.rows.front().points)
    if (p.value == label) return p;
  return {label, glm::vec3(0.0f), 0.0f, 0.0f};
}

bool SceneVolume::mayBeVisible(float lo, float hi) const {
  if (!labels) return transfer.opaqueSomewhere(lo, hi);
  if (material(lo).opacity > 0.0f || material(hi).opacity > 0.0f) return true;
  for (const TransferPoint& p : transfer.rows.front().points)
    if (p.value >= lo && p.value <= hi && p.opacity > 0.0f) return true;
  return false;
}

namespace {
// The material a fraction t of the way from a to b, at `value`.
TransferPoint mixPoints(const TransferPoint& a, const TransferPoint& b, float t, float value) {
  return {value, glm::mix(a.color, b.color, t), a.opacity + (b.opacity - a.opacity) * t,
          a.importance + (b.importance - a.importance) * t};
}

TransferPoint rowAt(const std::vector<TransferPoint>& points, float value) {
  if (value <= points.front().value) return points.front();
  if (value >= points.back().value) return points.back();
  const auto hi = std::upper_bound(points.begin(), points.end(), value,
                                   [](float v, const TransferPoint& p) { return v < p.value; });
  const TransferPoint& a = *(hi - 1);
  return mixPoints(a, *hi, (value - a.value) / (hi->value - a.value), value);
}
}  // namespace

TransferPoint TransferFunction::at(float value, float gradient) const {
  if (gradient <= rows.front().gradient) return rowAt(rows.front().points, value);
  if (gradient >= rows.back().gradient) return rowAt(rows.back().points, value);
  const auto hi = std::upper_bound(rows.begin(), rows.end(), gradient,
                                   [](float g, const Row& r) { return g < r.gradient; });
  const float t = (gradient - (hi - 1)->gradient) / (hi->gradient - (hi - 1)->gradient);
  return mixPoints(rowAt((hi - 1)->points, value), rowAt(hi->points, value), t, value);
}

float TransferFunction::maxOpacity(float value) const {
  float most = 0.0f;
  for (const Row& r : rows) most = std::max(most, rowAt(r.points, value).opacity);
  return most;
}

bool TransferFunction::opaqueSomewhere(float lo, float hi) const {
  if (maxOpacity(lo) > 0.0f || maxOpacity(hi) > 0.0f) return true;
  for (const Row& r : rows)
    for (const TransferPoint& p : r.points)
      if (p.value >= lo && p.value <= hi && p.opacity > 0.0f) return true;
  return false;
}

const std::vector<ObjectParamSpec>& objectParameterSpecs() {
  static const std::vector<ObjectParamSpec> specs{
      {"lines", ObjectParamSpec::Type::Bool, 0, 0,
       "draw silhouette and crease lines on this object (styles/lines)"},
      {"cutawayAngle", ObjectParamSpec::Type::Number, 0, 90,
       "local cutaway angle θ in degrees of an object of interest (Burns11 §6.2.1)"},
      {"solid", ObjectParamSpec::Type::Bool, 0, 0,
       "whether a cut shows this object's inside as a solid cut wall (default: when the mesh "
       "is watertight); false for hollow shells such as rooms (Diepstraten03 rule 5)"},
      {"doubleSided", ObjectParamSpec::Type::Bool, 0, 0,
       "draw this object's back faces where no cutter cuts it (default); false culls them, "
       "as glTF's doubleSided: false asks (a cut always shows the back faces it opens)"},
      {"castsShadow", ObjectParamSpec::Type::Bool, 0, 0,
       "this object casts shadows (style.shadows); default: every visible object except those "
       "of role exterior"},
  };
  return specs;
}

glm::mat4 Trs::matrix() const {
  return glm::translate(glm::mat4(1.0f), translate) * glm::mat4_cast(rotate) *
         glm::scale(glm::mat4(1.0f), scale);
}

bool SceneObject::solid() const {
  const auto it = params.find("solid");
  return it != params.end() ? std::get<bool>(it->second) : mesh->report.watertight;
}

bool SceneObject::doubleSided() const {
  const auto it = params.find("doubleSided");
  return it == params.end() || std::get<bool>(it->second);
}

bool SceneObject::takesLines() const {
  const auto it = params.find("lines");
  return it == params.end() || std::get<bool>(it->second);
}

bool SceneObject::named(const std::regex& pattern) const {
  return std::regex_match(name, pattern) || (!alias.empty() && std::regex_match(alias, pattern));
}

glm::mat4 SceneObject::transformAt(float time) const {
  if (animation.empty()) return transform;
  if (time <= animation.front().time) return animation.front().trs.matrix() * transform;
  if (time >= animation.back().time) return animation.back().trs.matrix() * transform;
  std::size_t i = 1;
  while (animation[i].time < time) ++i;
  const Keyframe& a = animation[i - 1];
  const Keyframe& b = animation[i];
  const float u = (time - a.time) / (b.time - a.time);
  const Trs k{glm::mix(a.trs.translate, b.trs.translate, u),
              glm::slerp(a.trs.rotate, b.trs.rotate, u), glm::mix(a.trs.scale, b.trs.scale, u)};
  return k.matrix() * transform;
}

Bounds SceneObject::worldBounds() const {
  Bounds b;
  if (!mesh) return b;
  const Bounds local = mesh->bounds();
  if (animation.empty()) return local.transformed(transform);
  // Keyframes bound translation; rotations between them can only sweep so far, so sample.
  const float start = animation.front().time, end = animation.back().time;
  for (int i = 0; i <= 32; ++i)
    b.extend(local.transformed(transformAt(start + (end - start) * float(i) / 32.0f)));
  return b;
}

float Scene::duration() const {
  float d = camera.path.empty() ? 0.0f : camera.path.back().time;
  for (const auto& o : objects)
    if (!o.animation.empty()) d = std::max(d, o.animation.back().time);
  return d;
}

SceneObject networkObject(const PipeNetwork& net, int network, NetworkPart part, Mesh mesh) {
  SceneObject o;
  o.name = net.name + "/" +
           (part == NetworkPart::ShaftOuter   ? "shafts"
            : part == NetworkPart::ShaftInner ? "shaft-insides"
            : part == NetworkPart::Joints     ? "joints"
                                              : "pipes");
  o.source = "network " + net.name;
  o.role = Role::Interest;
  o.importance = 1.0f;
  o.networkPart = part;
  o.network = network;
  o.material.color = part == NetworkPart::ShaftInner ? net.cutColor : net.color;
  analyzeTopology(mesh);
  o.mesh = std::make_shared<Mesh>(std::move(mesh));
  return o;
}

SceneObject shaftObject(const PipeNetwork& net, int network, bool inner) {
  constexpr int kSides = 32;
  SceneObject o =
      networkObject(net, network, inner ? NetworkPart::ShaftInner : NetworkPart::ShaftOuter,
                    shaftMesh(net, inner, kSides));
  float radius = 0.0f;
  for (const Shaft& shaft : net.shafts) radius = std::max(radius, shaft.radius);
  for (int sides = kSides / 2; sides >= 4; sides /= 2) {
    Mesh coarser = shaftMesh(net, inner, sides);
    analyzeTopology(coarser);
    o.coarser.push_back({radius * (1.0f - std::cos(std::numbers::pi_v<float> / float(sides))),
                         std::make_shared<Mesh>(std::move(coarser))});
  }
  return o;
}

void addSimplifiedVersions(Scene& scene, SimplifiedCache& cache) {
  // Versions of meshes the scene no longer has (another scene opened) go.
  std::set<std::shared_ptr<const Mesh>> meshes;
  for (const SceneObject& o : scene.objects) meshes.insert(o.mesh);
  std::erase_if(cache, [&](const auto& entry) { return !meshes.count(entry.first); });
  std::vector<std::shared_ptr<const Mesh>> pending;
  for (const SceneObject& o : scene.objects)
    if (o.mesh && !o.mesh->grid && o.coarser.empty() && cache.try_emplace(o.mesh).second)
      pending.push_back(o.mesh);
  std::vector<std::vector<SimplifiedMesh>> versions(pending.size());
  std::atomic<std::size_t> next = 0;
  runOnThreads(hardwareThreads(int(pending.size())), [&] {
    for (std::size_t i; (i = next++) < pending.size();) versions[i] = simplifiedVersions(*pending[i]);
  });
  for (std::size_t i = 0; i < pending.size(); ++i)
    for (SimplifiedMesh& v : versions[i])
      cache[pending[i]].push_back({v.error, std::make_shared<Mesh>(std::move(v.mesh))});
  for (SceneObject& o : scene.objects)
    if (o.mesh && !o.mesh->grid && o.coarser.empty()) o.coarser = cache[o.mesh];
}

Bounds Scene::bounds() const {
  Bounds b;
  for (const auto& o : objects)
    if (!o.proxy) b.extend(o.worldBounds());
  for (const auto& n : networks) b.extend(n.bounds());
  for (const auto& v : volumes) b.extend(v.worldBounds());
  return b;
}

namespace {

std::regex namePattern(const std::string& pattern) {
  try {
    return compileNamePattern(pattern);
  } catch (const std::invalid_argument& e) {
    throw Error("", "", e.what());
  }
}

bool matches(const SceneObject& o, const std::regex& re) {
  return o.named(re) || (!o.group.empty() && std::regex_match(o.group, re));
}

}  // namespace

std::size_t Scene::setImportance(const std::string& pattern, float importance) {
  if (!(importance >= 0.0f && importance <= 1.0f))
    throw Error(shortNamePattern(pattern), "", "importance must lie in [0, 1]");
  const std::regex re = namePattern(pattern);
  std::size_t n = 0;
  for (SceneObject& o : objects)
    if (matches(o, re)) o.importance = importance, ++n;
  if (n == 0) throw Error(shortNamePattern(pattern), "", "matches no object's name or group");
  return n;
}

std::size_t Scene::setRole(const std::string& pattern, Role role) {
  const std::regex re = namePattern(pattern);
  std::size_t n = 0;
  for (SceneObject& o : objects)
    if (!o.proxy && matches(o, re)) o.role = role, ++n;
  for (SceneVolume& v : volumes)
    if (std::regex_match(v.name, re)) v.role = role, ++n;
  if (n == 0)
    throw Error(shortNamePattern(pattern), "", "matches no object's name or group, nor a volume");
  return n;
}

const SceneObject* Scene::find(const std::string& name) const {
  for (const auto& o : objects)
    if (o.name == name) return &o;
  return nullptr;
}

Camera Scene::resolvedCamera(float time) const {
  Camera c = camera;
  if (!c.path.empty()) {
    c.fit = false;
    const auto& p = c.path;
    if (time <= p.front().time || p.size() == 1) {
      c.eye = p.front().eye, c.target = p.front().target;
    } else if (time >= p.back().time) {
      c.eye = p.back().eye, c.target = p.back().target;
    } else {
      std::size_t i = 1;
      while (p[i].time < time) ++i;
      const float u = (time - p[i - 1].time) / (p[i].time - p[i - 1].time);
      c.eye = glm::mix(p[i - 1].eye, p[i].eye, u);
      c.target = glm::mix(p[i - 1].target, p[i].target, u);
    }
  }
  const Bounds b = bounds();
  glm::vec3 center = b.empty() ? glm::vec3(0.0f) : b.center();
  // A point (or nothing) still gets a view; a scene its own size, down to what floats resolve
  // at its distance from the origin (a 1e-3 floor framed a 1e-8 scene as a few pixels).
  float radius =
      !(b.radius() > 0.0f) ? 1e-3f : std::max(b.radius(), 1e-6f * glm::length(center));
  const float aspect = float(width) / float(height);
  if (c.fit) {
    // Keep the viewing direction (eye − target), aim at the bounds' centre and back off until
    // every corner of the bounding box lies inside the view, with a 5% margin.
    glm::vec3 direction = c.eye - c.target;
    if (glm::length(direction) < 1e-6f) direction = glm::vec3(1.0f, 0.8f, 1.4f);
    direction = glm::normalize(direction);
    c.target = center;
    glm::vec3 right = glm::cross(c.up, direction);
    if (glm::length(right) < 1e-6f) right = glm::cross(glm::vec3(0, 0, 1), direction);
    right = glm::normalize(right);
    const glm::vec3 up = glm::cross(direction, right);
    const float tanY = std::tan(glm::radians(c.fovY) * 0.5f), tanX = tanY * aspect;
    float distance = 0.0f, halfWidth = 0.0f, halfHeight = 0.0f;
    for (int i = 0; i < 8 && !b.empty(); ++i) {
      const glm::vec3 corner{(i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                             (i & 4) ? b.max.z : b.min.z};
      const glm::vec3 d = corner - center;
      const float x = std::abs(glm::dot(d, right)) * 1.05f, y = std::abs(glm::dot(d, up)) * 1.05f;
      const float towardsEye = glm::dot(d, direction);
      // A corner at lateral offset x and depth z (towards the eye) fits when x / (D − z) ≤ tan.
      distance = std::max({distance, x / tanX + towardsEye, y / tanY + towardsEye});
      halfWidth = std::max(halfWidth, x);
      halfHeight = std::max(halfHeight, y);
    }
    if (c.projection == Projection::Perspective) {
      c.eye = center + direction * std::max(distance, radius * 1e-2f);
    } else {
      c.height = 2.0f * std::max(halfHeight, halfWidth / aspect);
      c.eye = center + direction * (radius * 3.0f);
    }
  }
  // Depth range hugging the scene: better depth precision than a fixed range. It holds the
  // proxies of interest too: the adaptive cutter draws them (one past the far plane lost its
  // seed). The others have no effect (one far away once pushed the near plane past the scene).
  Bounds drawn = b;
  for (const SceneObject& o : objects)
    if (o.proxy && o.role == Role::Interest) drawn.extend(o.worldBounds());
  if (drawn.min != b.min || drawn.max != b.max) {
    center = drawn.center();
    radius = std::max(drawn.radius(), 1e-6f * glm::length(center));
  }
  const float distance = glm::length(center - c.eye);
  const bool perspective = c.projection == Projection::Perspective;
  const bool nearGiven = c.near > 0.0f, farGiven = c.far > 0.0f;
  if (!nearGiven) {
    const float n = distance - radius * 1.05f;
    c.near = perspective ? std::max(n, radius * 1e-3f) : n;
  }
  if (!farGiven) c.far = distance + radius * 1.05f;
  // Given values are kept (both given: far > near, checked where they are read); a derived
  // plane that lands on the wrong side of a given one yields to it.
  if (c.far <= c.near) {
    if (farGiven && !nearGiven)
      c.near = perspective ? c.far * 1e-3f : c.far - radius * 2.0f;
    else
      c.far = c.near + radius * 2.0f;
  }
  return c;
}

}  // namespace cutaway
