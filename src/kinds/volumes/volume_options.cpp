// The volumes' ray-casting options (cutaway::SceneVolume) and their lines'
// (src/styles/volume_lines) as scene options ("volumes.<key>": --set, the viewer, the bindings).
// They apply to every volume of the scene at once (the first one's value is read) and are read by
// the renderer every frame: a change redraws without a new renderer. The files come from the scene
// file; the transfer functions have the viewer's editor
// (apps/cutaway-view/panels/transfer_panel.cpp).
#include "kinds/member_options.hpp"

namespace cutaway {

namespace {

const char* const kModes[] = {"composite", "maximum", "isosurface"};

// A member of every volume, as a number, a bool or (the mode) a choice.
template <typename T>
OptionSpec volumeMember(std::string key, std::string label, OptionSpec::Type type,
                        T SceneVolume::*field, std::string help) {
  OptionSpec p = liveMemberOption("volumes." + key, std::move(label), type, std::move(help));
  if constexpr (std::is_same_v<T, VolumeMode>)
    p.choices.assign(std::begin(kModes), std::end(kModes));
  p.get = [field](const void* scene) -> OptionValue {
    const Scene& s = *static_cast<const Scene*>(scene);
    const T v = s.volumes.empty() ? SceneVolume{}.*field : s.volumes.front().*field;
    if constexpr (std::is_same_v<T, VolumeMode>)
      return std::string(kModes[int(v)]);
    else if constexpr (std::is_same_v<T, bool>)
      return v;
    else
      return double(v);
  };
  p.set = [field](void* scene, const OptionValue& value) {
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

std::vector<OptionSpec> volumeOptions() {
  using Type = OptionSpec::Type;
  using V = SceneVolume;
  std::vector<OptionSpec> out;
  out.push_back(volumeMember("mode", "mode", Type::Choice, &V::mode,
                             "Emission–absorption front to back, maximum intensity projection, "
                             "or the first crossing of the isovalue."));
  OptionSpec step = volumeMember("sampleDistance", "step (voxels)", Type::Float, &V::sampleDistance,
                                 "The ray's step in voxels; the opacities are corrected for it.");
  step.min = 0.05, step.max = 8, step.sliderMax = 2;
  out.push_back(step);
  OptionSpec opacity =
      volumeMember("opacityDistance", "opacity distance", Type::Float, &V::opacityDistance,
                   "The length in voxels the transfer function's opacities hold "
                   "for: larger makes the volume more transparent.");
  opacity.min = 0.05, opacity.max = 1000, opacity.sliderMax = 20;
  out.push_back(opacity);
  OptionSpec iso = volumeMember("isoValue", "isovalue", Type::Float, &V::isoValue,
                                "The isosurface mode's value, in the file's units.");
  iso.min = -1e6, iso.max = 1e6, iso.sliderMax = 4000;
  iso.applies = [](const void* scene) {
    const Scene& s = *static_cast<const Scene*>(scene);
    return !s.volumes.empty() && s.volumes.front().mode == VolumeMode::Isosurface;
  };
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
    OptionSpec p = spec;
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
    p.set = [spec](void* scene, const OptionValue& value) {
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

}  // namespace cutaway
