// Parameters bound to the members of one options struct of the scene (a cutter's options):
// how to read them (defaults when the cutter is off), how to write them (turning it on), and
// when they apply. Shared by the cutters' parameter tables.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "../parameters.hpp"

namespace cutaway::view {

template <typename Options>
struct OptionsBinding {
  std::string prefix;  // "cutout"
  const Options& (*read)(const Scene&);
  Options& (*write)(Scene&);
  bool (*active)(const Scene&);

  // A bool, number or colour member.
  template <typename T>
  Parameter member(std::string key, std::string label, Parameter::Type type, T Options::*field,
                   std::string help) const {
    Parameter p;
    p.key = prefix + "." + key;
    p.label = std::move(label);
    p.type = type;
    p.help = std::move(help);
    p.get = [read = read, field](const Scene& s) -> ParameterValue {
      const T& v = read(s).*field;
      if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, glm::vec3>)
        return v;
      else
        return double(v);
    };
    p.set = [write = write, field](Scene& s, const ParameterValue& v) {
      if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, glm::vec3>)
        write(s).*field = std::get<T>(v);
      else
        write(s).*field = T(std::get<double>(v));
    };
    p.applies = active;
    return p;
  }

  // An enum member shown as its scene-format name.
  template <typename E>
  Parameter choice(std::string key, std::string label, E Options::*field,
                   std::vector<std::pair<std::string, E>> names, std::string help) const {
    Parameter p;
    p.key = prefix + "." + key;
    p.label = std::move(label);
    p.type = Parameter::Type::Choice;
    p.help = std::move(help);
    p.choices = [names] {
      std::vector<std::string> out;
      for (const auto& [name, value] : names) out.push_back(name);
      return out;
    };
    p.get = [read = read, field, names](const Scene& s) -> ParameterValue {
      for (const auto& [name, value] : names)
        if (read(s).*field == value) return name;
      return names.front().first;
    };
    p.set = [write = write, field, names](Scene& s, const ParameterValue& v) {
      for (const auto& [name, value] : names)
        if (name == std::get<std::string>(v)) write(s).*field = value;
    };
    p.applies = active;
    return p;
  }

  // An optional colour member: the default shown until the user picks one.
  Parameter color(std::string key, std::string label, std::optional<glm::vec3> Options::*field,
                  glm::vec3 fallback, std::string help) const {
    Parameter p;
    p.key = prefix + "." + key;
    p.label = std::move(label);
    p.type = Parameter::Type::Color;
    p.help = std::move(help);
    p.get = [read = read, field, fallback](const Scene& s) -> ParameterValue {
      return (read(s).*field).value_or(fallback);
    };
    p.set = [write = write, field](Scene& s, const ParameterValue& v) {
      write(s).*field = std::get<glm::vec3>(v);
    };
    p.applies = active;
    return p;
  }

  // Whether the cutter is on: off removes it from the scene, on adds it with its defaults.
  Parameter enabled(std::string help, std::optional<Options> Scene::*field) const {
    Parameter p;
    p.key = prefix + ".enabled";
    p.label = "enabled";
    p.type = Parameter::Type::Bool;
    p.help = std::move(help);
    p.get = [field](const Scene& s) -> ParameterValue { return (s.*field).has_value(); };
    p.set = [field](Scene& s, const ParameterValue& v) {
      if (!std::get<bool>(v))
        (s.*field).reset();
      else if (!(s.*field))
        (s.*field).emplace();
    };
    return p;
  }
};

// The binding of the options a Scene holds in `Field`: their defaults while the cutter is
// off; writing any of them turns it on with the defaults first.
template <typename Options, std::optional<Options> Scene::*Field>
OptionsBinding<Options> sceneOptions(std::string prefix) {
  return {std::move(prefix),
          [](const Scene& s) -> const Options& {
            static const Options kDefaults;
            return s.*Field ? *(s.*Field) : kDefaults;
          },
          [](Scene& s) -> Options& {
            if (!(s.*Field)) (s.*Field).emplace();
            return *(s.*Field);
          },
          [](const Scene& s) { return (s.*Field).has_value(); }};
}

}  // namespace cutaway::view
