#include "cutaway/render/techniques.hpp"

#include <stdexcept>

#include "cutaway/core/error.hpp"
#include "cutters/registry.hpp"
#include "kinds/member_options.hpp"
#include "styles/registry.hpp"

namespace cutaway {

namespace {

// Where a technique's options live in a Scene: `any` is null while a cutter is off.
struct Holder {
  std::function<const std::any*(const Scene&)> find;
  std::function<std::any&(Scene&)> enable;  // with the defaults first
};

// `spec` (on the technique's options struct) re-rooted on the Scene.
OptionSpec onScene(OptionSpec spec, const OptionsSchema& schema, const Holder& holder) {
  const auto get = spec.get;
  const auto set = spec.set;
  const auto applies = spec.applies;
  spec.get = [get, &schema, holder](const void* s) {
    if (const std::any* a = holder.find(*static_cast<const Scene*>(s))) return get(schema.data(*a));
    std::any defaults = schema.makeDefault();
    return get(schema.data(defaults));
  };
  spec.set = [set, alsoSets = spec.alsoSets, &schema, holder](void* s, const OptionValue& v) {
    void* options = schema.data(holder.enable(*static_cast<Scene*>(s)));
    set(options, v);
    if (alsoSets) alsoSets(options);
  };
  spec.applies = [applies, &schema, holder](const void* s) {
    const std::any* a = holder.find(*static_cast<const Scene*>(s));
    return a && (!applies || applies(schema.data(*a)));
  };
  if (const auto absent = spec.absent)  // a technique switched off: its defaults
    spec.absent = [absent, &schema, holder](const void* s) {
      if (const std::any* a = holder.find(*static_cast<const Scene*>(s)))
        return absent(schema.data(*a));
      std::any defaults = schema.makeDefault();
      return absent(schema.data(defaults));
    };
  return spec;
}

std::vector<SceneOption> makeSceneOptions() {
  std::vector<SceneOption> out;
  const auto add = [&](const std::string& technique, const OptionsSchema& schema,
                       const Holder& holder) {
    for (const OptionSpec& s : schema.flatten()) {
      OptionSpec spec = onScene(s, schema, holder);
      spec.key = technique + "." + s.key;
      out.push_back({spec.key, technique, spec});
    }
  };
  for (const CutterType& type : cutterTypes()) {
    if (!type.schema) continue;
    const std::string path = "cutters." + type.key;
    const Holder holder{[key = type.key](const Scene& s) { return s.cutters.find(key); },
                        [key = type.key, schema = type.schema](Scene& s) -> std::any& {
                          if (!s.cutters.find(key)) s.cutters.set(key, schema->makeDefault());
                          return *s.cutters.find(key);
                        }};
    // The switch: off removes the cutter's options, on adds them with their defaults.
    OptionSpec on;
    on.key = path;
    on.label = "enabled";
    on.type = OptionSpec::Type::Bool;
    on.doc = type.title;
    on.get = [key = type.key](const void* s) -> OptionValue {
      return static_cast<const Scene*>(s)->cutters.find(key) != nullptr;
    };
    on.set = [key = type.key, holder](void* s, const OptionValue& v) {
      Scene& scene = *static_cast<Scene*>(s);
      if (!std::get<bool>(v))
        scene.cutters.erase(key);
      else
        (void)holder.enable(scene);
    };
    out.push_back({path, path, on});
    add(path, *type.schema, holder);
  }
  // The style's own keys, on the Style itself (always there).
  for (const OptionSpec& s : styleSchema().flatten()) {
    OptionSpec spec = s;
    spec.get = [get = s.get](const void* scene) { return get(&static_cast<const Scene*>(scene)->style); };
    spec.set = [set = s.set](void* scene, const OptionValue& v) { set(&static_cast<Scene*>(scene)->style, v); };
    if (s.applies)
      spec.applies = [applies = s.applies](const void* scene) {
        return applies(&static_cast<const Scene*>(scene)->style);
      };
    if (s.absent)
      spec.absent = [absent = s.absent](const void* scene) {
        return absent(&static_cast<const Scene*>(scene)->style);
      };
    spec.key = "style." + s.key;
    out.push_back({spec.key, "style", spec});
  }
  // Each shading style's, which apply while it is the style.
  for (const StyleType& type : styleTypes()) {
    const Holder holder{[key = type.key](const Scene& s) { return s.style.shading.find(key); },
                        [key = type.key, schema = type.schema](Scene& s) -> std::any& {
                          if (!s.style.shading.find(key)) s.style.shading.set(key, schema->makeDefault());
                          return *s.style.shading.find(key);
                        }};
    const std::string path = "style." + type.key;
    for (const OptionSpec& s : type.schema->flatten()) {
      OptionSpec spec = onScene(s, *type.schema, holder);
      // Unset options are the defaults: they apply whenever the style is the scene's.
      spec.applies = [name = type.name, applies = s.applies, schema = type.schema,
                      key = type.key](const void* p) {
        const Scene& scene = *static_cast<const Scene*>(p);
        if (scene.style.name != name) return false;
        if (!applies) return true;
        const std::any* a = scene.style.shading.find(key);
        std::any defaults = a ? std::any() : schema->makeDefault();
        return applies(schema->data(a ? *a : defaults));
      };
      spec.key = path + "." + s.key;
      out.push_back({spec.key, path, spec});
    }
  }
  for (OptionSpec& spec : networkOptions()) out.push_back({spec.key, "networks", std::move(spec)});
  for (OptionSpec& spec : volumeOptions()) out.push_back({spec.key, "volumes", std::move(spec)});
  return out;
}

}  // namespace

const std::vector<TechniqueInfo>& techniques() {
  static const std::vector<TechniqueInfo> list = [] {
    std::vector<TechniqueInfo> out;
    for (const CutterType& t : cutterTypes())
      if (t.schema) out.push_back({"cutters." + t.key, t.title, "", t.schema});
    out.push_back({"style", "Style", "", &styleSchema()});
    for (const StyleType& t : styleTypes()) out.push_back({"style." + t.key, t.title, t.name, t.schema});
    out.push_back({"networks", "Pipe networks (Konev18)", "", nullptr});
    out.push_back({"volumes", "Volumes", "", nullptr});
    return out;
  }();
  return list;
}

const std::vector<SceneOption>& sceneOptions() {
  static const std::vector<SceneOption> options = makeSceneOptions();
  return options;
}

const SceneOption* findSceneOption(const std::string& path) {
  for (const SceneOption& o : sceneOptions())
    if (o.path == path) return &o;
  return nullptr;
}

void setOption(Scene& scene, const std::string& path, const std::string& text) {
  const SceneOption* option = findSceneOption(path);
  if (!option) {
    // Name the options of the technique the path starts with (the longest: style.gooch, not
    // style), or the techniques.
    std::string technique;
    for (const TechniqueInfo& t : techniques())
      if ((path.rfind(t.path + ".", 0) == 0 || path == t.path) && t.path.size() > technique.size())
        technique = t.path;
    std::string known;
    for (const SceneOption& o : sceneOptions())
      if (!technique.empty() && o.technique == technique)
        known += (known.empty() ? "" : ", ") + o.path;
    if (known.empty())
      for (const TechniqueInfo& t : techniques()) known += (known.empty() ? "" : ", ") + t.path;
    throw Error(path, "", "no such option (known: " + known + ")");
  }
  if (option->spec.absent)
    if (const std::string why = option->spec.absent(&scene); !why.empty())
      throw Error(path, "", why);
  try {
    option->spec.set(&scene, parseOptionValue(option->spec, text));
  } catch (const std::invalid_argument& e) {
    throw Error(path, "", e.what());
  }
}

}  // namespace cutaway
