// The volumes' ray-casting options (src/kinds/volumes; cutaway::SceneVolume) and their lines'
// (src/styles/volume_lines) as viewer parameters. They apply to every volume of the scene at once
// (the first one's value is shown) and are read by the renderer every frame: a change redraws
// without a new renderer. The files come from the scene file; the transfer functions have their own
// editor (panels/transfer_panel.cpp).
#include "../parameters.hpp"

namespace cutaway::view {

namespace {

const char* const kModes[] = {"composite", "maximum", "isosurface"};

// A member of every volume, as a number, a bool or (the mode) a choice.
template <typename T>
Parameter volumeMember(std::string key, std::string label, Parameter::Type type,
                       T SceneVolume::*field, std::string help) {
  Parameter p;
  p.key = "volumes." + key;
  p.label = std::move(label);
  p.type = type;
  p.doc = std::move(help);
  p.live = true;
  if constexpr (std::is_same_v<T, VolumeMode>)
    p.choices.assign(std::begin(kModes), std::end(kModes));
  p.get = [field](const void* scene) -> ParameterValue {
    const Scene& s = *static_cast<const Scene*>(scene);
    const T v = s.volumes.empty() ? SceneVolume{}.*field : s.volumes.front().*field;
    if constexpr (std::is_same_v<T, VolumeMode>)
      return std::string(kModes[int(v)]);
    else if constexpr (std::is_same_v<T, bool>)
      return v;
    else
      return double(v);
  };
  p.set = [field](void* scene, const ParameterValue& value) {
    Scene& s = *static_cast<Scene*>(scene);
    T v{};
    if constexpr (std::is_same_v<T, VolumeMode>) {
      const std::string& name = std::get<std::string>(value);
      for (int i = 0; i < 3; ++i)
        if (name == kModes[i]) v = VolumeMode(i);
    } else if constexpr (std::is_same_v<T, bool>) {
      v = std::get<bool>(value);
    } else {
      v = T(std::get<double>(value));
    }
    for (SceneVolume& volume : s.volumes) volume.*field = v;
  };
  p.applies = [](const void* s) { return !static_cast<const Scene*>(s)->volumes.empty(); };
  return p;
}

}  // namespace

std::vector<Parameter> volumeParameters() {
  using Type = OptionSpec::Type;
  using V = SceneVolume;
  std::vector<Parameter> out;
  out.push_back(volumeMember("mode", "mode", Type::Choice, &V::mode,
                             "Emission–absorption front to back, maximum intensity projection, "
                             "or the first crossing of the isovalue."));
  Parameter step = volumeMember("sampleDistance", "step (voxels)", Type::Float, &V::sampleDistance,
                                "The ray's step in voxels; the opacities are corrected for it.");
  step.min = 0.05, step.max = 8, step.sliderMax = 2;
  out.push_back(step);
  Parameter opacity =
      volumeMember("opacityDistance", "opacity distance", Type::Float, &V::opacityDistance,
                   "The length in voxels the transfer function's opacities hold "
                   "for: larger makes the volume more transparent.");
  opacity.min = 0.05, opacity.max = 1000, opacity.sliderMax = 20;
  out.push_back(opacity);
  Parameter iso = volumeMember("isoValue", "isovalue", Type::Float, &V::isoValue,
                               "The isosurface mode's value, in the file's units.");
  iso.min = -1e6, iso.max = 1e6, iso.sliderMax = 4000;
  out.push_back(iso);
  out.push_back(volumeMember("shading", "shading", Type::Bool, &V::shading,
                             "Gradient normals shaded by the style; off: emission only."));
  out.push_back(volumeMember("jitter", "jitter", Type::Bool, &V::jitter,
                             "Ray starts offset per pixel against wood-grain bands."));
  out.push_back(volumeMember("shadows", "shadows", Type::Bool, &V::shadows,
                             "The material shadows the key light: a shadow ray per shaded "
                             "sample (slow on a software rasteriser)."));
  // The volumes' lines (Burns11 §2.4), by their schema: each option of every volume that has
  // lines (the first one's shown), live.
  for (const OptionSpec& spec : volumeLineStyleSchema().flatten()) {
    Parameter p;
    static_cast<OptionSpec&>(p) = spec;
    p.key = "volumes.lines." + spec.key;
    if (spec.key.ends_with(".value")) p.sliderMax = 4000;  // an isovalue, as the mode's
    const auto first = [](const Scene& s) -> const VolumeLineStyle* {
      for (const SceneVolume& v : s.volumes)
        if (v.lines) return &*v.lines;
      return nullptr;
    };
    p.get = [spec, first](const void* scene) {
      const VolumeLineStyle* lines = first(*static_cast<const Scene*>(scene));
      const VolumeLineStyle defaults;
      return spec.get(lines ? lines : &defaults);
    };
    p.set = [spec](void* scene, const ParameterValue& value) {
      for (SceneVolume& v : static_cast<Scene*>(scene)->volumes)
        if (v.lines) spec.set(&*v.lines, value);
    };
    p.applies = [spec, first](const void* scene) {
      const VolumeLineStyle* lines = first(*static_cast<const Scene*>(scene));
      return lines && (!spec.applies || spec.applies(lines));
    };
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace cutaway::view
