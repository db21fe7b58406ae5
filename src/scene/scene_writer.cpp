#include "cutaway/scene/scene_writer.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <sstream>

#include "core/json_reader.hpp"
#include "cutaway/core/atomic_file.hpp"
#include "cutaway/core/error.hpp"
#include "cutaway/cutters/adaptive.hpp"
#include "cutters/registry.hpp"
#include "styles/registry.hpp"

namespace cutaway {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

namespace {

using json_reader::exact;

json vec(const glm::vec3& v) {
  return {exact(v.x), exact(v.y), exact(v.z)};
}

json paramJson(const ParamValue& v) {
  return std::visit([](auto x) { return json(x); }, v);
}

// The value that has the effect of leaving `key` unset, for overrides, which can set a
// parameter but not remove one.
ParamValue unsetValue(const std::string& key, const Scene& scene) {
  if (key == "cutawayAngle") {
    const auto* adaptive = scene.cutters.find<AdaptiveCutawayOptions>();
    return double(exact(adaptive ? adaptive->angle : AdaptiveCutawayOptions{}.angle));
  }
  return true;  // "lines": drawn unless turned off
}

struct Changes {
  bool role = false, importance = false;
  ObjectParams setParams;                // changed or new
  std::vector<std::string> unsetParams;  // present when loaded, removed since
  bool any() const { return role || importance || !setParams.empty() || !unsetParams.empty(); }
};

Changes changes(const SceneObject& before, const SceneObject& after) {
  Changes c;
  c.role = before.role != after.role;
  c.importance = before.importance != after.importance;
  for (const auto& [k, v] : after.params) {
    const auto it = before.params.find(k);
    if (it == before.params.end() || it->second != v) c.setParams[k] = v;
  }
  for (const auto& [k, v] : before.params)
    if (!after.params.count(k)) c.unsetParams.push_back(k);
  return c;
}

// An object entry (not split), or a proxy: the keys are the object's own.
void patchEntry(json& entry, const SceneObject& before, const SceneObject& after) {
  const Changes c = changes(before, after);
  if (c.role) entry["role"] = roleName(after.role);
  if (c.importance) entry["importance"] = exact(after.importance);
  for (const auto& [k, v] : c.setParams) entry["params"][k] = paramJson(v);
  for (const auto& k : c.unsetParams)
    if (entry.contains("params")) entry["params"].erase(k);
  if (entry.contains("params") && entry["params"].empty()) entry.erase("params");
}

// One node of an entry split into nodes: an override matching exactly the node, last.
void patchNode(json& entry, const std::string& node, const SceneObject& before,
               const SceneObject& after, const Scene& scene) {
  const Changes c = changes(before, after);
  if (!c.any()) return;
  const std::string match = escapeRegex(node);
  json& overrides = entry["overrides"];
  json mine = {{"match", match}};
  // A previous save's exact override: its keys that we set again move to the new last one,
  // the rest (a colour, say) stays where it was so that its precedence does not change.
  for (std::size_t i = 0; i < overrides.size();) {
    json& o = overrides[i];
    if (o.value("match", "") != match) {
      ++i;
      continue;
    }
    for (const char* key : {"role", "importance"})
      if (o.contains(key)) mine[key] = o[key], o.erase(key);
    if (o.contains("params")) {
      for (auto& [k, v] : o["params"].items()) mine["params"][k] = v;
      o.erase("params");
    }
    if (o.size() == 1)
      overrides.erase(i);
    else
      ++i;
  }
  // Written in full (not only what changed) so that the node ends as the viewer shows it
  // whatever the overrides before this one say.
  mine["role"] = roleName(after.role);
  mine["importance"] = exact(after.importance);
  for (const auto& [k, v] : after.params) mine["params"][k] = paramJson(v);
  for (const auto& k : c.unsetParams) mine["params"][k] = paramJson(unsetValue(k, scene));
  overrides.push_back(mine);
}

void makePathsAbsolute(json& doc, const fs::path& baseDir) {
  if (!doc.contains("objects") || !doc["objects"].is_array()) return;
  for (auto& entry : doc["objects"])
    if (entry.contains("file") && entry["file"].is_string()) {
      const fs::path file = entry["file"].get<std::string>();
      if (file.is_relative())
        entry["file"] = fs::absolute(baseDir / file).lexically_normal().string();
    }
}

}  // namespace

std::string escapeRegex(const std::string& name) {
  std::string out;
  for (char c : name) {
    if (std::string_view("\\^$.|?*+()[]{}").find(c) != std::string_view::npos) out += '\\';
    out += c;
  }
  return out;
}

double shortestDecimal(float f) {
  return exact(f);
}

json cameraJson(const Camera& c) {
  json j = {
      {"projection", c.projection == Projection::Orthographic ? "orthographic" : "perspective"},
      {"eye", vec(c.eye)},
      {"target", vec(c.target)},
      {"up", vec(c.up)},
      {"fov", exact(c.fovY)},
      {"height", exact(c.height)}};
  if (c.near > 0) j["near"] = exact(c.near);
  if (c.far > 0) j["far"] = exact(c.far);
  if (!c.path.empty()) {
    json path = json::array();
    for (const auto& k : c.path)
      path.push_back({{"time", exact(k.time)}, {"eye", vec(k.eye)}, {"target", vec(k.target)}});
    j["path"] = path;
  }
  return j;
}

json cuttersJson(const Scene& scene) {
  json out = json::object();
  for (const CutterType& type : cutterTypes())
    if (const std::any* options = type.schema ? scene.cutters.find(type.key) : nullptr)
      out[type.key] = type.schema->write(type.schema->data(*options));
  return out;
}

json styleJson(const Style& style) {
  json out = styleSchema().write(&style);
  for (const StyleType& type : styleTypes()) {
    const std::any* options = style.shading.find(type.key);
    const std::any defaults = options ? std::any() : type.schema->makeDefault();
    out[type.key] = type.schema->write(type.schema->data(options ? *options : defaults));
  }
  return out;
}

// A network's keys --set and the viewer edit (kinds/pipes/network_options.cpp); its pipes,
// shafts and attributes stay as written.
json networkJson(const PipeNetwork& n) {
  return {{"radiusScale", exact(n.radiusScale)},
          {"shaftOpening", exact(n.shaftOpening)},
          {"color", vec(n.color)},
          {"insideColor", vec(n.insideColor)},
          {"cutColor", vec(n.cutColor)},
          {"waterColors", {vec(n.waterLow), vec(n.waterHigh)}}};
}

json transferPointsJson(const std::vector<TransferPoint>& points) {
  json out = json::array();
  for (const TransferPoint& p : points)
    out.push_back({{"value", exact(p.value)},
                   {"color", vec(p.color)},
                   {"opacity", exact(p.opacity)},
                   {"importance", exact(p.importance)}});
  return out;
}

// The volume options --set and the viewer edit (kinds/volumes/volume_options.cpp, the viewer's
// transfer-function editor), the transfer function under the key it was read from.
json volumeJson(const SceneVolume& v) {
  json out = {{"mode", volumeModeName(v.mode)},
              {"sampleDistance", exact(v.sampleDistance)},
              {"opacityDistance", exact(v.opacityDistance)},
              {"isoValue", exact(v.isoValue)},
              {"shading", v.shading},
              {"jitter", v.jitter},
              {"shadows", v.shadows}};
  if (v.transfer.twoDimensional())
    for (const TransferFunction::Row& row : v.transfer.rows)
      out["transferFunction2D"].push_back(
          {{"gradient", exact(row.gradient)}, {"points", transferPointsJson(row.points)}});
  else
    out["transferFunction"] = transferPointsJson(v.transfer.rows.front().points);
  if (v.lines) out["lines"] = volumeLineStyleSchema().write(&*v.lines);
  return out;
}

// `edited` merged into `into` key by key: objects recursively, arrays element by element,
// anything else replaced; keys only `into` has stay.
void merge(json& into, const json& edited) {
  if (edited.is_object() && into.is_object()) {
    for (const auto& [key, value] : edited.items())
      if (into.contains(key))
        merge(into[key], value);
      else
        into[key] = value;
  } else if (edited.is_array() && into.is_array() && edited.size() == into.size()) {
    for (std::size_t i = 0; i < edited.size(); ++i) merge(into[i], edited[i]);
  } else {
    into = edited;
  }
}

SceneDocument SceneDocument::load(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string(), "", "cannot open scene file");
  std::stringstream text;
  text << in.rdbuf();
  try {
    return SceneDocument(json::parse(text.str()), path);
  } catch (const json::exception& e) {
    throw Error(path.string(), "", std::string("invalid JSON: ") + e.what());
  }
}

SceneDocument::SceneDocument(json document, fs::path path)
    : document_(std::move(document)), path_(std::move(path)) {}

json SceneDocument::patched(const Scene& original, const Scene& current,
                            const fs::path& target) const {
  if (original.objects.size() != current.objects.size())
    throw Error(target.string(), "", "the viewer's objects no longer match the scene file");
  json doc = document_;
  doc["camera"] = cameraJson(current.camera);
  if (current.width != original.width || current.height != original.height)
    doc["resolution"] = {current.width, current.height};

  std::size_t k = 0;
  // The networks' shafts and meshed pipes come last and have no entry of their own.
  const std::size_t n = std::size_t(
      std::count_if(current.objects.begin(), current.objects.end(),
                    [](const SceneObject& o) { return o.networkPart == NetworkPart::None; }));
  // A scene of pipe networks or volumes alone may have no "objects" key (operator[] would
  // add one, as null).
  json noObjects = json::array();
  for (auto& entry : doc.contains("objects") ? doc["objects"] : noObjects) {
    if (k >= n) break;  // reported below
    const std::string name = entry.at("name").get<std::string>();
    if (entry.value("split", "file") != "nodes") {
      patchEntry(entry, original.objects[k], current.objects[k]);
      ++k;
      continue;
    }
    const std::string prefix = name + "/";
    for (; k < n && !current.objects[k].proxy && current.objects[k].name.starts_with(prefix); ++k)
      patchNode(entry, current.objects[k].name.substr(prefix.size()), original.objects[k],
                current.objects[k], current);
    if (entry.contains("overrides") && entry["overrides"].empty()) entry.erase("overrides");
  }
  if (doc.contains("proxies"))
    for (auto& entry : doc["proxies"]) {
      if (k >= n) break;  // reported below
      patchEntry(entry, original.objects[k], current.objects[k]);
      ++k;
    }
  if (k != n)
    throw Error(target.string(), "", "the viewer's objects no longer match the scene file");

  // The cutters: added, removed, or their changed keys merged in.
  const json before = cuttersJson(original), after = cuttersJson(current);
  for (const auto& [key, value] : after.items()) {
    if (before.contains(key) && before[key] == value) continue;
    if (doc.contains("cutters") && doc["cutters"].contains(key) && doc["cutters"][key].is_object())
      merge(doc["cutters"][key], value);
    else
      doc["cutters"][key] = value;
  }
  for (const auto& [key, value] : before.items())
    if (!after.contains(key) && doc.contains("cutters")) {
      doc["cutters"].erase(key);
      if (doc["cutters"].empty()) doc.erase("cutters");
    }
  const json style = styleJson(current.style);
  if (style != styleJson(original.style)) {
    json& s = doc["style"];
    if (s.is_string()) s = json{{"name", s}};
    if (!s.is_object()) s = json::object();
    merge(s, style);
  }
  for (std::size_t i = 0; i < current.networks.size() && i < original.networks.size(); ++i)
    if (const json edited = networkJson(current.networks[i]);
        edited != networkJson(original.networks[i]))
      for (auto& [key, value] : edited.items()) doc["networks"][i][key] = value;
  // Only the keys edited: a transfer function left alone stays as its author wrote it.
  for (std::size_t i = 0; i < current.volumes.size() && i < original.volumes.size(); ++i) {
    const json edited = volumeJson(current.volumes[i]), before = volumeJson(original.volumes[i]);
    for (auto& [key, value] : edited.items())
      if (!before.contains(key) || before.at(key) != value) doc["volumes"][i][key] = value;
    // A transfer function turned from one to two dimensions (or back) leaves its old key.
    for (const char* key : {"transferFunction", "transferFunction2D"})
      if (!edited.contains(key) && before.contains(key)) doc["volumes"][i].erase(key);
  }
  const fs::path from = fs::weakly_canonical(fs::absolute(path_)).parent_path();
  const fs::path to = fs::weakly_canonical(fs::absolute(target)).parent_path();
  if (from != to) makePathsAbsolute(doc, path_.parent_path());
  return doc;
}

void SceneDocument::save(const Scene& original, const Scene& current,
                         const fs::path& target) const {
  // Before the check below, which would read a folder's relative paths from its parent.
  std::error_code ec;
  if (fs::is_directory(target, ec)) throw Error(target.string(), "", "is a directory, not a file");
  const std::string text = patched(original, current, target).dump(2) + "\n";
  // The strict loader is the judge of the format; then what the viewer changed must read back.
  Scene saved;
  try {
    saved = parseScene(text, target, target.parent_path());
  } catch (const Error& e) {
    throw Error(target.string(), e.place(), "the saved scene would not load: " + e.reason());
  }
  const auto mismatch = [&](const std::string& what) {
    throw Error(target.string(), "", "the saved scene does not reproduce the viewer's " + what);
  };
  if (saved.objects.size() != current.objects.size()) mismatch("objects");
  for (std::size_t i = 0; i < saved.objects.size(); ++i) {
    const SceneObject &a = saved.objects[i], &b = current.objects[i];
    if (a.name != b.name || a.role != b.role || a.importance != b.importance)
      mismatch("object \"" + b.name + "\"");
    // Unset parameters may come back as their neutral value (unsetValue).
    for (const auto& [key, value] : b.params)
      if (!a.params.count(key) || a.params.at(key) != value)
        mismatch("parameters of \"" + b.name + "\"");
  }
  if (cameraJson(saved.camera) != cameraJson(current.camera)) mismatch("camera");
  const json savedCutters = cuttersJson(saved), currentCutters = cuttersJson(current);
  for (const CutterType& type : cutterTypes())
    if (savedCutters.value(type.key, json()) != currentCutters.value(type.key, json()))
      mismatch(type.title);
  if (styleJson(saved.style) != styleJson(current.style)) mismatch("style");
  if (saved.networks.size() != current.networks.size()) mismatch("pipe networks");
  for (std::size_t i = 0; i < saved.networks.size(); ++i)
    if (networkJson(saved.networks[i]) != networkJson(current.networks[i]))
      mismatch("pipe network \"" + current.networks[i].name + "\"");
  if (saved.volumes.size() != current.volumes.size()) mismatch("volumes");
  for (std::size_t i = 0; i < saved.volumes.size(); ++i)
    if (volumeJson(saved.volumes[i]) != volumeJson(current.volumes[i]))
      mismatch("volume \"" + current.volumes[i].name + "\"");
  if (saved.width != current.width || saved.height != current.height) mismatch("resolution");
  writeFileAtomically(target, [&](std::ostream& os) { os << text; });
}

}  // namespace cutaway
