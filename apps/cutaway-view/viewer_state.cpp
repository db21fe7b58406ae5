#include "viewer_state.hpp"

#include <algorithm>

#include "cutaway/core/error.hpp"

namespace cutaway::view {

std::vector<std::size_t> objectsNamed(const Scene& scene, const std::string& name) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < scene.objects.size(); ++i)
    if (scene.objects[i].name == name || (!name.empty() && scene.objects[i].alias == name))
      return {i};
  for (std::size_t i = 0; i < scene.objects.size(); ++i)
    if (!name.empty() && scene.objects[i].group == name) out.push_back(i);
  return out;
}

std::vector<std::string> groupsOf(const Scene& scene) {
  std::vector<std::string> groups;
  for (const auto& o : scene.objects)
    if (std::find(groups.begin(), groups.end(), o.group) == groups.end()) groups.push_back(o.group);
  return groups;
}

void setRole(ViewerState& state, Role role) {
  for (std::size_t i : state.selection) {
    SceneObject& o = state.scene.objects[i];
    if (o.role != role) o.role = role, state.sceneChanged = true;
  }
}

void setImportance(ViewerState& state, float importance) {
  importance = std::clamp(importance, 0.0f, 1.0f);
  for (std::size_t i : state.selection) {
    SceneObject& o = state.scene.objects[i];
    if (o.importance != importance) o.importance = importance, state.sceneChanged = true;
  }
}

void setLocalAngle(ViewerState& state, std::optional<float> degrees) {
  for (std::size_t i : state.selection) {
    ObjectParams& params = state.scene.objects[i].params;
    const auto it = params.find("cutawayAngle");
    if (!degrees) {
      if (it != params.end()) params.erase(it), state.sceneChanged = true;
      continue;
    }
    const double value = std::clamp(double(*degrees), 0.0, 90.0);
    if (it == params.end() || std::get<double>(it->second) != value)
      params["cutawayAngle"] = value, state.sceneChanged = true;
  }
}

void setParameter(ViewerState& state, const Parameter& p, const ParameterValue& value) {
  if (!p.live) {
    p.assign(state.scene, value);
    state.sceneChanged = true;
    return;
  }
  // Setting an option of a switchable group that is off switches it on (OptionSpec), which
  // the group's switch, not a uniform, says: a rebuild, as `cutaway render --set` draws it.
  const auto switches = [&] {
    std::vector<ParameterValue> values;
    for (const ParameterGroup& g : parameterGroups())
      for (const Parameter& q : g.parameters)
        if (!q.live && q.type == Parameter::Type::Bool && q.appliesTo(state.scene))
          values.push_back(q.value(state.scene));
    return values;
  };
  const std::vector<ParameterValue> before = switches();
  p.assign(state.scene, value);
  (switches() == before ? state.viewChanged : state.sceneChanged) = true;
}

Bounds selectionBounds(const ViewerState& state) {
  if (state.selection.empty()) return state.scene.bounds();
  Bounds b;
  for (std::size_t i : state.selection) b.extend(state.scene.objects[i].worldBounds());
  return b;
}

void addCameraKey(ViewerState& state, float time) {
  if (!state.cameraPath.empty() && !(time > state.cameraPath.back().time))
    throw Error("camera path", "",
                "key times must increase (last key at " +
                    std::to_string(state.cameraPath.back().time) + " s)");
  const Camera& c = state.scene.camera;
  state.cameraPath.push_back({time, c.eye, c.target});
}

Camera viewCamera(const ViewerState& state) {
  if (!state.previewPath || state.cameraPath.empty()) return state.scene.resolvedCamera(state.time);
  Scene probe = state.scene;  // resolvedCamera reads the path from the scene's camera
  probe.camera.path = state.cameraPath;
  return probe.resolvedCamera(state.time);
}

}  // namespace cutaway::view
