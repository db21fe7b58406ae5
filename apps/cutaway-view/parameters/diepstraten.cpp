// The cutout and breakaway cutters' options (Diepstraten, Weiskopf, Ertl 2003;
// cutaway::CutoutOptions, cutaway::BreakawayOptions) as viewer parameters.
#include "binding.hpp"

namespace cutaway::view {

namespace {

const OptionsBinding<CutoutOptions> kCutout = sceneOptions<CutoutOptions, &Scene::cutout>("cutout");
const OptionsBinding<BreakawayOptions> kBreakaway =
    sceneOptions<BreakawayOptions, &Scene::breakaway>("breakaway");

bool textureCutout(const Scene& s) {
  return s.cutout && s.cutout->method == CutoutOptions::Method::Texture;
}

const CutoutJitter& readJitter(const Scene& s) {
  return kCutout.read(s).jitter;
}
CutoutJitter& writeJitter(Scene& s) {
  return kCutout.write(s).jitter;
}
bool jittered(const Scene& s) {
  return textureCutout(s) && s.cutout->jitter.pattern != CutoutJitter::Pattern::None;
}

std::vector<Parameter> makeCutoutParameters() {
  using Type = Parameter::Type;
  const OptionsBinding<CutoutOptions>& b = kCutout;
  std::vector<Parameter> out;
  out.push_back(
      b.enabled("Cut a wedge out of every exterior object along its main axis "
                "(Diepstraten03 §4).",
                &Scene::cutout));
  out.push_back(b.choice("method", "method", &CutoutOptions::method,
                         {{"texture", CutoutOptions::Method::Texture},
                          {"clipPlanes", CutoutOptions::Method::ClipPlanes}},
                         "texture: per-fragment signed distances with jitter and walls (§4.5); "
                         "clipPlanes: hardware clip planes, one pass per plane (§4.3)."));
  Parameter angle = b.member("angle", "wedge angle (°)", Type::Float, &CutoutOptions::angle,
                             "Relative angle between the two planes (rule 2; default 90°).");
  angle.min = 1, angle.max = 180;
  out.push_back(angle);
  Parameter facing;
  facing.key = "cutout.facingCamera";
  facing.label = "faces the camera";
  facing.type = Type::Bool;
  facing.help =
      "Turn the wedge about the main axis towards the viewer (rule 3), or hold it at "
      "the rotation below.";
  facing.get = [](const Scene& s) -> ParameterValue { return !kCutout.read(s).rotation; };
  facing.set = [](Scene& s, const ParameterValue& v) {
    if (std::get<bool>(v))
      kCutout.write(s).rotation.reset();
    else if (!kCutout.write(s).rotation)
      kCutout.write(s).rotation = 0.0f;
  };
  facing.applies = kCutout.active;
  out.push_back(facing);
  Parameter rotation;
  rotation.key = "cutout.rotation";
  rotation.label = "rotation (°)";
  rotation.type = Type::Float;
  rotation.min = -360, rotation.max = 360, rotation.sliderMax = 180;
  rotation.help = "The wedge's rotation about the main axis, from the second principal axis.";
  rotation.get = [](const Scene& s) -> ParameterValue {
    return double(kCutout.read(s).rotation.value_or(0.0f));
  };
  rotation.set = [](Scene& s, const ParameterValue& v) {
    kCutout.write(s).rotation = float(std::get<double>(v));
  };
  rotation.applies = [](const Scene& s) { return s.cutout && s.cutout->rotation.has_value(); };
  out.push_back(rotation);

  const OptionsBinding<CutoutJitter> j{"cutout", readJitter, writeJitter, jittered};
  Parameter pattern = j.choice("jitter", "jitter", &CutoutJitter::pattern,
                               {{"none", CutoutJitter::Pattern::None},
                                {"sawtooth", CutoutJitter::Pattern::Sawtooth},
                                {"noise", CutoutJitter::Pattern::Noise}},
                               "Rough cut boundaries (rule 4, §4.5): a sawtooth or fractal noise "
                               "displaces the signed distance.");
  pattern.applies = textureCutout;
  out.push_back(pattern);
  Parameter amplitude =
      j.member("jitterAmplitude", "jitter amplitude", Type::Float, &CutoutJitter::amplitude,
               "Displacement, as a fraction of the main axis' extent.");
  amplitude.min = 0, amplitude.max = 1, amplitude.sliderMax = 0.2;
  out.push_back(amplitude);
  Parameter frequency =
      j.member("jitterFrequency", "jitter frequency", Type::Float, &CutoutJitter::frequency,
               "Pattern repeats per extent along the main axis.");
  frequency.min = 1e-3, frequency.max = 1e4, frequency.sliderMax = 60;
  out.push_back(frequency);
  out.push_back(b.color("wallColor", "wall colour", &CutoutOptions::wallColor, kDefaultWallColor,
                        "Colour of the cut walls of solid exteriors (rule 5)."));
  return out;
}

// An optional length shown as its resolved default (breakawayExtent) until the user sets it.
Parameter extent(std::string key, std::string label, std::optional<float> BreakawayOptions::*field,
                 float BreakawayExtent::*resolved, std::string help) {
  Parameter p;
  p.key = "breakaway." + key;
  p.label = std::move(label);
  p.type = Parameter::Type::Float;
  p.min = 0, p.max = 1e30;  // scene units: dragged, not a slider
  p.help = std::move(help);
  p.get = [field, resolved](const Scene& s) -> ParameterValue {
    const BreakawayOptions& o = kBreakaway.read(s);
    if (o.*field) return double(*(o.*field));
    return double(breakawayExtent(s, o).*resolved);
  };
  p.set = [field](Scene& s, const ParameterValue& v) {
    kBreakaway.write(s).*field = float(std::get<double>(v));
  };
  p.applies = kBreakaway.active;
  return p;
}

std::vector<Parameter> makeBreakawayParameters() {
  const OptionsBinding<BreakawayOptions>& b = kBreakaway;
  std::vector<Parameter> out;
  out.push_back(
      b.enabled("Open one hole in the exterior objects where the interior objects "
                "would be hidden (Diepstraten03 §5).",
                &Scene::breakaway));
  out.push_back(extent("offset", "hull offset", &BreakawayOptions::offset, &BreakawayExtent::offset,
                       "Scene units the interior objects' convex hulls grow by."));
  out.push_back(extent("wallThickness", "wall thickness", &BreakawayOptions::wallThickness,
                       &BreakawayExtent::wallThickness,
                       "The back-face hull is smaller by this: the hole's wall (at most the "
                       "offset)."));
  out.push_back(b.color("wallColor", "wall colour", &BreakawayOptions::wallColor, kDefaultWallColor,
                        "Colour of the cut walls of solid exteriors."));
  return out;
}

}  // namespace

const std::vector<Parameter>& cutoutParameters() {
  static const std::vector<Parameter> parameters = makeCutoutParameters();
  return parameters;
}

const std::vector<Parameter>& breakawayParameters() {
  static const std::vector<Parameter> parameters = makeBreakawayParameters();
  return parameters;
}

}  // namespace cutaway::view
