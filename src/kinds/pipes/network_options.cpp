// The pipe networks' run-time options (Konev18 §§5–7; cutaway::PipeNetwork) as scene options
// ("networks.<key>": --set, the viewer, the bindings). They apply to every network of the
// scene at once (the first one's value is read) and are read by the renderer every frame: a
// change redraws without a new renderer. The pipes, shafts and their attributes come from the
// scene file.
#include "kinds/member_options.hpp"

namespace cutaway {

namespace {

bool hasNetworks(const Scene& s) {
  return !s.networks.empty();
}

// A member of every network; `also` applies the value to what was copied from it at load
// (the shafts' and meshed pipes' object colours).
template <typename T>
OptionSpec networkMember(std::string key, std::string label, OptionSpec::Type type,
                         T PipeNetwork::*field, std::string help,
                         void (*also)(Scene&, int network, const T&) = nullptr) {
  OptionSpec p = liveMemberOption("networks." + key, std::move(label), type, std::move(help));
  p.get = [field](const void* scene) -> OptionValue {
    const Scene& s = *static_cast<const Scene*>(scene);
    const T& v = s.networks.empty() ? PipeNetwork{}.*field : s.networks.front().*field;
    if constexpr (std::is_same_v<T, glm::vec3>)
      return v;
    else
      return double(v);
  };
  p.set = [field, also](void* scene, const OptionValue& value) {
    Scene& s = *static_cast<Scene*>(scene);
    T v;
    if constexpr (std::is_same_v<T, glm::vec3>)
      v = std::get<glm::vec3>(value);
    else
      v = T(std::get<double>(value));
    for (std::size_t i = 0; i < s.networks.size(); ++i) {
      s.networks[i].*field = v;
      if (also) also(s, int(i), v);
    }
  };
  p.applies = [](const void* s) { return hasNetworks(*static_cast<const Scene*>(s)); };
  return p;
}

// Shafts, joints and meshed pipes are mesh objects given the network's outside colour at
// load; the shafts' inner cylinders carry the cut colour (their front faces are the wedge's
// cut surface).
void colorOutsides(Scene& s, int network, const glm::vec3& color) {
  for (SceneObject& o : s.objects)
    if (o.network == network && o.networkPart != NetworkPart::None &&
        o.networkPart != NetworkPart::ShaftInner)
      o.material.color = color;
}

void colorShaftInsides(Scene& s, int network, const glm::vec3& color) {
  for (SceneObject& o : s.objects)
    if (o.network == network && o.networkPart == NetworkPart::ShaftInner) o.material.color = color;
}

}  // namespace

std::vector<OptionSpec> networkOptions() {
  using Type = OptionSpec::Type;
  using N = PipeNetwork;
  std::vector<OptionSpec> out;
  OptionSpec radius = networkMember("radiusScale", "radius scale", Type::Float, &N::radiusScale,
                                    "§5: every pipe radius times this, at run time (the "
                                    "billboards, proxies and water follow).");
  radius.min = 1e-3, radius.max = 1e3, radius.sliderMax = 10;
  out.push_back(radius);
  OptionSpec opening = networkMember("shaftOpening", "shaft opening", Type::Float, &N::shaftOpening,
                                     "§7: shaft fragments are discarded where n·v (heights "
                                     "ignored) exceeds this; lower opens a wider wedge.");
  opening.min = -1, opening.max = 1;
  out.push_back(opening);
  out.push_back(networkMember("color", "outside", Type::Color, &N::color,
                              "Base colour of the pipes' and shafts' outside.", colorOutsides));
  out.push_back(networkMember("insideColor", "inside", Type::Color, &N::insideColor,
                              "§6: the other base colour inside opened pipes and shafts."));
  out.push_back(networkMember("cutColor", "cut surface", Type::Color, &N::cutColor,
                              "§6: the contrasting colour of the cut walls.", colorShaftInsides));
  out.push_back(networkMember("waterLow", "water, low", Type::Color, &N::waterLow,
                              "§6.4: water colour of an almost empty pipe or shaft."));
  out.push_back(networkMember("waterHigh", "water, full", Type::Color, &N::waterHigh,
                              "§6.4: water colour of a full pipe or shaft."));
  return out;
}

}  // namespace cutaway
