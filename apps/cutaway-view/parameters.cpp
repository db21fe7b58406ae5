#include "parameters.hpp"

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace cutaway::view {

const std::vector<ParameterGroup>& parameterGroups() {
  static const std::vector<ParameterGroup> groups{
      {"adaptive", "Adaptive cutaway (Burns08/11)", &adaptiveParameters()},
      {"cutout", "Cutout (Diepstraten03)", &cutoutParameters()},
      {"breakaway", "Breakaway (Diepstraten03)", &breakawayParameters()},
      {"clipSurfaces", "Clip surfaces (Trapp13)", &clipSurfaceParameters()},
      {"terrain", "Terrain opening (Konev18)", &terrainParameters()},
      {"networks", "Pipe networks (Konev18)", &networkParameters()},
      {"style", "Style", &styleParameters()},
  };
  return groups;
}

const Parameter* findParameter(const std::string& key) {
  for (const auto& group : parameterGroups())
    for (const auto& p : *group.parameters)
      if (p.key == key) return &p;
  return nullptr;
}

namespace {

bool parseNumber(const std::string& text, double& out) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, out);
  return ec == std::errc() && ptr == end && std::isfinite(out);
}

std::string rangeText(double lo, double hi) {
  std::ostringstream s;
  s << "[" << lo << ", " << hi << "]";
  return s.str();
}

}  // namespace

ParameterValue parseParameterValue(const Parameter& p, const std::string& text) {
  using Type = Parameter::Type;
  switch (p.type) {
    case Type::Bool:
      if (text == "true" || text == "on") return true;
      if (text == "false" || text == "off") return false;
      throw std::invalid_argument("expected true/false or on/off, got \"" + text + "\"");
    case Type::Int:
    case Type::Float: {
      double v = 0;
      if (!parseNumber(text, v))
        throw std::invalid_argument("expected a number, got \"" + text + "\"");
      if (p.type == Type::Int && v != std::floor(v))
        throw std::invalid_argument("expected an integer, got " + text);
      if (!(v >= p.min && v <= p.max))
        throw std::invalid_argument("value " + text + " is outside " + rangeText(p.min, p.max));
      return v;
    }
    case Type::Choice: {
      std::string list;
      for (const auto& c : p.choices()) {
        if (c == text) return text;
        list += (list.empty() ? "" : ", ") + c;
      }
      throw std::invalid_argument("unknown value \"" + text + "\" (expected one of: " + list + ")");
    }
    case Type::Color:
    case Type::Direction: {
      glm::vec3 v;
      std::size_t start = 0;
      for (int i = 0; i < 3; ++i) {
        const std::size_t comma = text.find(',', start);
        if ((i < 2) != (comma != std::string::npos))
          throw std::invalid_argument("expected three comma-separated numbers x,y,z, got \"" +
                                      text + "\"");
        double c = 0;
        if (!parseNumber(text.substr(start, comma - start), c))
          throw std::invalid_argument("expected three comma-separated numbers x,y,z, got \"" +
                                      text + "\"");
        if (p.type == Type::Color && !(c >= 0 && c <= 1))
          throw std::invalid_argument("colour channels must lie in [0, 1], got \"" + text + "\"");
        v[i] = float(c);
        start = comma + 1;
      }
      if (p.type == Type::Direction && glm::length(v) < 1e-9f)
        throw std::invalid_argument("a direction must not be the zero vector");
      return v;
    }
  }
  throw std::invalid_argument("unsupported parameter type");
}

std::string formatParameterValue(const ParameterValue& value) {
  std::ostringstream s;
  if (const bool* b = std::get_if<bool>(&value)) s << (*b ? "true" : "false");
  if (const double* d = std::get_if<double>(&value)) s << *d;
  if (const std::string* t = std::get_if<std::string>(&value)) s << *t;
  if (const glm::vec3* v = std::get_if<glm::vec3>(&value)) s << v->x << "," << v->y << "," << v->z;
  return s.str();
}

}  // namespace cutaway::view
