// The adaptive cutter's options (cutaway::AdaptiveCutawayOptions; Burns08, Burns11 ch. 4–6)
// as viewer parameters. Setting any of them on a scene without the cutter adds it with the
// defaults first, as `cutaway render --cutaway-angle` does.
#include "binding.hpp"

namespace cutaway::view {

namespace {

using Options = AdaptiveCutawayOptions;

const OptionsBinding<Options> kBinding = sceneOptions<Options, &Scene::adaptive>("adaptive");

template <typename T>
Parameter member(std::string key, std::string label, Parameter::Type type, T Options::*field,
                 std::string help) {
  return kBinding.member(std::move(key), std::move(label), type, field, std::move(help));
}

template <typename E>
Parameter choice(std::string key, std::string label, E Options::*field,
                 std::vector<std::pair<std::string, E>> names, std::string help) {
  return kBinding.choice(std::move(key), std::move(label), field, std::move(names),
                         std::move(help));
}

std::vector<Parameter> makeAdaptiveParameters() {
  using Type = Parameter::Type;
  std::vector<Parameter> out;
  out.push_back(
      kBinding.enabled("Cut away what hides the objects of interest (Burns08).", &Scene::adaptive));

  Parameter angle = member("angle", "angle θ (°)", Type::Float, &Options::angle,
                           "Angle between the cut's walls and the viewing ray (Burns08 §3); "
                           "objects may set their own (Scene panel).");
  angle.min = 0, angle.max = 90;
  out.push_back(angle);
  Parameter buffer = member("bufferSize", "buffer resolution", Type::Int, &Options::bufferSize,
                            "The cutaway buffer is n×n pixels whatever the view (Burns08 §6).");
  buffer.min = 16, buffer.max = 8192, buffer.sliderMax = 2048;
  out.push_back(buffer);
  out.push_back(member("perspectiveCompensation", "perspective compensation", Type::Bool,
                       &Options::perspectiveCompensation,
                       "Keep the walls at θ at any depth (Burns08 eq. 3, Burns11 eq. 5.7)."));
  out.push_back(member("edgeCompression", "edge compression", Type::Bool, &Options::edgeCompression,
                       "Shrink θ to 0 near the view's border (Burns11 eq. 5.8)."));
  Parameter region = member("edgeRegion", "edge region r", Type::Float, &Options::edgeRegion,
                            "Width r of the border region of eq. 5.8, in [−1, 1] units.");
  region.min = 1e-3, region.max = 1;
  region.applies = [](const Scene& s) { return s.adaptive && s.adaptive->edgeCompression; };
  out.push_back(region);
  out.push_back(member("directionalConstraint", "directional constraint", Type::Bool,
                       &Options::directionalConstraint,
                       "Keep the cut off the floor (Burns08 §5.5, Burns11 eqs. 6.1–6.4)."));
  Parameter floor = member("floorNormal", "floor normal", Type::Direction, &Options::floorNormal,
                           "World-space normal of the floor the constraint protects.");
  floor.applies = [](const Scene& s) { return s.adaptive && s.adaptive->directionalConstraint; };
  out.push_back(floor);
  out.push_back(choice("jumpFlooding", "jump flooding", &Options::variant,
                       {{"jfa", fields::JumpFloodingVariant::jfa},
                        {"jfa+1", fields::JumpFloodingVariant::jfaPlus1},
                        {"1+jfa", fields::JumpFloodingVariant::onePlusJfa},
                        {"jfa+2", fields::JumpFloodingVariant::jfaPlus2}},
                       "Step sequence of jump flooding (Burns08 §5.1)."));
  out.push_back(choice("compute", "compute", &Options::compute,
                       {{"auto", Options::Compute::Auto},
                        {"gpu", Options::Compute::Gpu},
                        {"cpu", Options::Compute::Cpu}},
                       "Where jump flooding runs; auto: the CPU on llvmpipe."));
  out.push_back(choice("cutSurfaces", "cut surfaces", &Options::cutSurfaces,
                       {{"all", Options::CutSurfaces::All},
                        {"watertight", Options::CutSurfaces::Watertight},
                        {"none", Options::CutSurfaces::None}},
                       "Shade back faces behind the cut as solid cut surfaces (Burns08 §4.1)."));
  out.push_back(member("outlines", "cut outlines", Type::Bool, &Options::outlines,
                       "Draw the boundary of the cut surfaces (Burns08 §4.2)."));
  Parameter outlineColor = member("outlineColor", "outline colour", Type::Color,
                                  &Options::outlineColor, "Colour of the cut outlines.");
  outlineColor.applies = [](const Scene& s) { return s.adaptive && s.adaptive->outlines; };
  out.push_back(outlineColor);
  out.push_back(member("ghostLines", "ghost lines", Type::Bool, &Options::ghostLines,
                       "Faded lines of the removed material (Burns08 §4.3)."));
  Parameter distance =
      member("ghostDistance", "ghost distance", Type::Float, &Options::ghostDistance,
             "World units in front of the cutaway surface over which ghost "
             "lines fade out; 0: 5% of the scene radius.");
  // No natural bound (world units): the panel drags it instead of a slider.
  distance.min = 0, distance.max = 1e30;
  distance.applies = [](const Scene& s) { return s.adaptive && s.adaptive->ghostLines; };
  out.push_back(distance);
  Parameter opacity = member("ghostOpacity", "ghost opacity", Type::Float, &Options::ghostOpacity,
                             "Opacity of the ghost lines over the image.");
  opacity.applies = distance.applies;
  out.push_back(opacity);
  return out;
}

}  // namespace

const std::vector<Parameter>& adaptiveParameters() {
  static const std::vector<Parameter> parameters = makeAdaptiveParameters();
  return parameters;
}

}  // namespace cutaway::view
