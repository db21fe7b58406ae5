// The style's options (cutaway::Style: shading name, feature lines, Gooch and Blinn-Phong
// parameters) as viewer parameters. The style names come from cutaway::styleNames(), so a
// new style shows up here without a change.
#include "../parameters.hpp"

namespace cutaway::view {

namespace {

LineStyle& lines(Scene& s) {
  if (!s.style.lines) s.style.lines.emplace();
  return *s.style.lines;
}

const LineStyle& lines(const Scene& s) {
  static const LineStyle kDefaults;
  return s.style.lines ? *s.style.lines : kDefaults;
}

bool hasLines(const Scene& s) {
  return s.style.lines.has_value();
}

// A parameter reading and writing a float or bool through `field` of the scene.
template <typename T, typename Get, typename Ref>
Parameter field(std::string key, std::string label, Parameter::Type type, Get get, Ref ref,
                std::string help) {
  Parameter p;
  p.key = "style." + key;
  p.label = std::move(label);
  p.type = type;
  p.help = std::move(help);
  p.get = [get](const Scene& s) -> ParameterValue {
    const T v = get(s);
    if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, glm::vec3>)
      return v;
    else
      return double(v);
  };
  p.set = [ref](Scene& s, const ParameterValue& v) {
    if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, glm::vec3>)
      ref(s) = std::get<T>(v);
    else
      ref(s) = T(std::get<double>(v));
  };
  return p;
}

// A member of the line style (which is created with its defaults when first set).
template <typename T>
Parameter lineField(const std::string& key, std::string label, Parameter::Type type,
                    T LineStyle::*member, std::string help) {
  return field<T>(
      "lines." + key, std::move(label), type, [member](const Scene& s) { return lines(s).*member; },
      [member](Scene& s) -> T& { return lines(s).*member; }, std::move(help));
}

std::vector<Parameter> makeStyleParameters() {
  using Type = Parameter::Type;
  std::vector<Parameter> out;
  Parameter name;
  name.key = "style.name";
  name.label = "shading";
  name.type = Type::Choice;
  name.help = "How kept fragments are shaded.";
  name.choices = [] { return styleNames(); };
  name.get = [](const Scene& s) -> ParameterValue { return s.style.name; };
  name.set = [](Scene& s, const ParameterValue& v) { s.style.name = std::get<std::string>(v); };
  out.push_back(name);

  Parameter on;
  on.key = "style.lines";
  on.label = "lines";
  on.type = Type::Bool;
  on.help = "Image-space silhouette and crease lines.";
  on.get = [](const Scene& s) -> ParameterValue { return hasLines(s); };
  on.set = [](Scene& s, const ParameterValue& v) {
    if (!std::get<bool>(v))
      s.style.lines.reset();
    else if (!s.style.lines)
      s.style.lines.emplace();
  };
  out.push_back(on);
  std::vector<Parameter> lineParameters{
      lineField("silhouettes", "silhouettes", Type::Bool, &LineStyle::silhouettes,
                "Object-id changes and depth discontinuities."),
      lineField("creases", "creases", Type::Bool, &LineStyle::creases,
                "Normal discontinuities within an object."),
      lineField("creaseAngle", "crease angle (°)", Type::Float, &LineStyle::creaseAngle,
                "Normals meeting at more than this make a crease."),
      lineField("depthThreshold", "depth threshold", Type::Float, &LineStyle::depthThreshold,
                "Relative view-depth jump that counts as a silhouette."),
      lineField("width", "line width (px)", Type::Float, &LineStyle::width,
                "Drawn rounded to whole pixels."),
      lineField("color", "line colour", Type::Color, &LineStyle::color, "Colour of the lines."),
  };
  lineParameters[2].min = 0, lineParameters[2].max = 180;
  lineParameters[3].min = 0, lineParameters[3].max = 1, lineParameters[3].sliderMax = 0.1;
  lineParameters[4].min = 0.5, lineParameters[4].max = 8;
  for (auto& p : lineParameters) {
    p.applies = hasLines;
    out.push_back(std::move(p));
  }

  const auto isGooch = [](const Scene& s) { return s.style.name == "gooch"; };
  std::vector<Parameter> gooch{
      field<glm::vec3>(
          "gooch.cool", "cool", Type::Color, [](const Scene& s) { return s.style.gooch.cool; },
          [](Scene& s) -> glm::vec3& { return s.style.gooch.cool; },
          "Cool tone, for surfaces turned away from the key light (Gooch98)."),
      field<glm::vec3>(
          "gooch.warm", "warm", Type::Color, [](const Scene& s) { return s.style.gooch.warm; },
          [](Scene& s) -> glm::vec3& { return s.style.gooch.warm; },
          "Warm tone, for surfaces turned towards the key light."),
      field<float>(
          "gooch.alpha", "alpha", Type::Float, [](const Scene& s) { return s.style.gooch.alpha; },
          [](Scene& s) -> float& { return s.style.gooch.alpha; },
          "How much of the object colour enters the cool tone."),
      field<float>(
          "gooch.beta", "beta", Type::Float, [](const Scene& s) { return s.style.gooch.beta; },
          [](Scene& s) -> float& { return s.style.gooch.beta; },
          "How much of the object colour enters the warm tone."),
  };
  for (auto& p : gooch) {
    p.applies = isGooch;
    out.push_back(std::move(p));
  }
  Parameter ambient = field<float>(
      "blinnPhong.ambient", "ambient", Type::Float,
      [](const Scene& s) { return s.style.blinnPhong.ambient; },
      [](Scene& s) -> float& { return s.style.blinnPhong.ambient; },
      "Ambient term as a fraction of the object colour.");
  ambient.applies = [](const Scene& s) { return s.style.name == "blinn-phong"; };
  out.push_back(ambient);
  return out;
}

}  // namespace

const std::vector<Parameter>& styleParameters() {
  static const std::vector<Parameter> parameters = makeStyleParameters();
  return parameters;
}

}  // namespace cutaway::view
