// The clip-surface cutter's options (Trapp & Döllner 2013; cutaway::ClipSurfaceOptions) as
// viewer parameters: the combination rule, caps and their style, and each surface's
// placement along its normal, height and switch. Surfaces are defined in the scene file; the
// viewer moves and switches them.
#include "binding.hpp"

namespace cutaway::view {

namespace {

const ClipSurfaceOptions& readClip(const Scene& s) {
  static const ClipSurfaceOptions kDefaults;
  return s.clipSurfaces ? *s.clipSurfaces : kDefaults;
}
// Surfaces are defined in the scene file; a scene without any gets one flat surface.
ClipSurfaceOptions& writeClip(Scene& s) {
  if (!s.clipSurfaces) s.clipSurfaces = ClipSurfaceOptions{.surfaces = {ClipSurface{}}};
  return *s.clipSurfaces;
}
bool clipOn(const Scene& s) {
  return s.clipSurfaces.has_value();
}

// A parameter of surface `i`, applying while the scene has that many surfaces.
Parameter surface(int i, std::string name, std::string label, Parameter::Type type,
                  std::function<ParameterValue(const ClipSurface&)> get,
                  std::function<void(ClipSurface&, const ParameterValue&)> set, std::string help) {
  Parameter p;
  p.key = "clipSurfaces." + std::to_string(i) + "." + name;
  p.label = "surface " + std::to_string(i + 1) + ": " + label;
  p.type = type;
  p.help = std::move(help);
  p.get = [i, get](const Scene& s) -> ParameterValue {
    const auto& surfaces = readClip(s).surfaces;
    return std::size_t(i) < surfaces.size() ? get(surfaces[std::size_t(i)]) : get(ClipSurface{});
  };
  p.set = [i, set](Scene& s, const ParameterValue& v) {
    auto& surfaces = writeClip(s).surfaces;
    if (std::size_t(i) < surfaces.size()) set(surfaces[std::size_t(i)], v);
  };
  p.applies = [i](const Scene& s) {
    return s.clipSurfaces && std::size_t(i) < s.clipSurfaces->surfaces.size();
  };
  return p;
}

std::vector<Parameter> makeClipSurfaceParameters() {
  using Type = Parameter::Type;
  const OptionsBinding<ClipSurfaceOptions> b{"clipSurfaces", readClip, writeClip, clipOn};
  std::vector<Parameter> out;
  out.push_back(b.choice("combine", "combine", &ClipSurfaceOptions::combine,
                         {{"union", ClipSurfaceOptions::Combine::Union},
                          {"intersection", ClipSurfaceOptions::Combine::Intersection}},
                         "union: clipped where any enabled surface clips; intersection: where "
                         "all of them do (Trapp13 §4.5)."));
  out.push_back(b.member("caps", "caps", Type::Bool, &ClipSurfaceOptions::caps,
                         "Close the cuts of watertight objects with cap surfaces (§5)."));
  out.push_back(b.choice("parity", "parity", &ClipSurfaceOptions::parity,
                         {{"static", ClipSurfaceOptions::Parity::Static},
                          {"perFrame", ClipSurfaceOptions::Parity::PerFrame}},
                         "Depth sprites built once per mesh, or re-peeled every frame for "
                         "moving objects (§6.3)."));
  out.push_back(b.member("normalMap", "cap normal map", Type::Bool,
                         &ClipSurfaceOptions::capNormalMap,
                         "Shade the caps' relief from the offset map's gradients (§6.1)."));
  Parameter occlusion =
      b.member("occlusion", "cap occlusion", Type::Float, &ClipSurfaceOptions::capOcclusion,
               "Strength of the occlusion map derived from the offset map.");
  occlusion.min = 0, occlusion.max = 1;
  out.push_back(occlusion);
  out.push_back(b.member("solidTexture", "solid texture", Type::Bool,
                         &ClipSurfaceOptions::capSolidTexture,
                         "Marble-like procedural solid texture on the caps (Fig. 11)."));
  for (int i = 0; i < kMaxClipSurfaces; ++i) {
    out.push_back(surface(
        i, "enabled", "on", Type::Bool,
        [](const ClipSurface& cs) -> ParameterValue { return cs.enabled; },
        [](ClipSurface& cs, const ParameterValue& v) { cs.enabled = std::get<bool>(v); },
        "Whether this surface clips (§4.5: each surface can be switched)."));
    Parameter position = surface(
        i, "position", "position along N", Type::Float,
        [](const ClipSurface& cs) -> ParameterValue {
          return double(glm::dot(cs.origin, cs.normal()));
        },
        [](ClipSurface& cs, const ParameterValue& v) {
          const glm::vec3 n = cs.normal();
          cs.origin += (float(std::get<double>(v)) - glm::dot(cs.origin, n)) * n;
        },
        "Moves the surface along its normal N (scene units: N·O).");
    position.min = -1e30, position.max = 1e30;
    out.push_back(position);
    Parameter height = surface(
        i, "height", "height S_z", Type::Float,
        [](const ClipSurface& cs) -> ParameterValue { return double(cs.scale.z); },
        [](ClipSurface& cs, const ParameterValue& v) { cs.scale.z = float(std::get<double>(v)); },
        "Scale of the offset map along −N, scene units (eq. 1).");
    height.min = 0, height.max = 1e30;
    out.push_back(height);
  }
  return out;
}

}  // namespace

const std::vector<Parameter>& clipSurfaceParameters() {
  static const std::vector<Parameter> parameters = makeClipSurfaceParameters();
  return parameters;
}

}  // namespace cutaway::view
