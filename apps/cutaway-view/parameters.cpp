#include "parameters.hpp"

#include "cutaway/render/techniques.hpp"

namespace cutaway::view {

const std::vector<ParameterGroup>& parameterGroups() {
  static const std::vector<ParameterGroup> groups = [] {
    std::vector<ParameterGroup> out;
    for (const TechniqueInfo& t : techniques()) {
      ParameterGroup g{t.path, t.title, t.name, {}};
      for (const SceneOption& o : sceneOptions())
        if (o.technique == t.path) g.parameters.push_back(Parameter{o.spec});
      out.push_back(std::move(g));
    }
    return out;
  }();
  return groups;
}

const ParameterGroup* findGroup(const std::string& name) {
  for (const auto& group : parameterGroups())
    if (group.name == name) return &group;
  return nullptr;
}

const Parameter* findParameter(const std::string& key) {
  for (const auto& group : parameterGroups())
    for (const auto& p : group.parameters)
      if (p.key == key) return &p;
  return nullptr;
}

}  // namespace cutaway::view
