// cutaway/core/options.hpp — one schema per option of a technique (a cutter's, a style's):
// its key, type, range, default, documentation, and whether a change is live (a uniform) or
// needs a new renderer. The same schema drives the scene file's reader and writer
// (src/core/options_json.cpp), the viewer's parameter tables and the CLI's --set overrides,
// so ranges and defaults are written once: the defaults are the options struct's own member
// initialisers.
//
// A schema is a tree over one options struct: values (members), groups (a member struct,
// written as a nested JSON object, optionally switched on and off by a bool member or an
// std::optional), arrays of element structs, and hooks for the keys a technique reads
// itself (file names, recipes, shorthand forms).
//
//   struct Options { float angle = 45.0f; bool outlines = true; };
//   const cutaway::OptionsSchema& schema() {
//     static const auto s = cutaway::OptionsBuilder<Options>()
//         .number("angle", &Options::angle, 0, 90, {.label = "angle (°)", .doc = "…", .live = true})
//         .value("outlines", &Options::outlines, {.doc = "…"})
//         .build();
//     return s;
//   }
//   for (const cutaway::OptionSpec& o : schema().flatten()) std::puts(o.key.c_str());
#pragma once

#include <any>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

namespace cutaway {

namespace json_reader {
struct Context;
class ObjectReader;
}  // namespace json_reader

// A value as the viewer, the CLI and the schemas pass it.
using OptionValue = std::variant<bool, double, std::string, glm::vec3>;

// What a builder call says about an option besides its key and type.
struct OptionInfo {
  std::string label;  // for panels; default: the key
  std::string doc;    // what it is and which paper: tooltips, --help, docs
  bool live = false;  // only a uniform: a change redraws without a new renderer
  bool required = false;          // must be given in the scene file (in its object)
  std::optional<double> sliderMax;  // sliders end here; larger values come from the script
  bool powerOfTwo = false;          // an integer that must be a power of two (a texture size)
  // Only in the scene file, whose reader checks it against other keys (a clip surface's
  // orthogonal sides): the viewer and the CLI edit it through derived values, if at all.
  bool fileOnly = false;
};

// One option, flattened for the viewer and the CLI: `get` and `set` work on the root options
// struct the schema describes. Setting an option of a switchable group switches it on.
struct OptionSpec {
  // Direction: a non-zero vec3, normalised when set. Choice: one of `choices`.
  enum class Type { Bool, Int, Float, Choice, Color, Direction, Vec3, Text };
  std::string key;    // path in the technique's options: "angle", "ghostLines.opacity",
                      // "surfaces.0.enabled"
  std::string label;
  Type type = Type::Float;
  double min = 0, max = 0;  // Int and Float, and each Vec3 component: the accepted range
  std::optional<double> sliderMax;
  bool powerOfTwo = false;  // Int: only powers of two are accepted
  std::vector<std::string> choices;
  std::string doc;
  bool live = false;
  bool required = false;
  bool inFile = true;  // read and written by the scene file (false: a viewer control only)
  bool fileOnly = false;  // the scene file's only: not among the flattened options
  std::function<OptionValue(const void*)> get;
  std::function<void(void*, const OptionValue&)> set;
  std::function<bool(const void*)> applies;  // null: always
  // What setting it by its path (CLI --set, the viewer, the bindings) sets beside it, as the
  // scene file's own check does where the key comes alone (a floor normal turns the
  // directional constraint on). Null: nothing.
  std::function<void(void*)> alsoSets;
  // Why a write would be lost (its struct does not exist: an array entry past the end), or
  // empty. Null: never.
  std::function<std::string(const void*)> absent;
};

// Parses text for `spec` ("true"/"false"/"on"/"off", a number, a choice, "x,y,z"); throws
// std::invalid_argument with the reason (range, type, unknown choice).
OptionValue parseOptionValue(const OptionSpec& spec, const std::string& text);
std::string formatOptionValue(const OptionValue& value);

class OptionsSchema {
 public:
  struct Node;
  using ReadHook = std::function<void(const json_reader::Context&, json_reader::ObjectReader&, void*)>;
  using WriteHook = std::function<void(const void*, nlohmann::ordered_json&)>;

  // A value of the type the schema describes, with its defaults.
  std::any makeDefault() const { return makeDefault_(); }
  void* data(std::any& a) const { return data_(a); }
  const void* data(const std::any& a) const { return data_(const_cast<std::any&>(a)); }

  // Every value of the tree with its path as key and accessors on the root; arrays expand to
  // their maximum count (the entries past an array's size do not apply).
  std::vector<OptionSpec> flatten() const;

  // The scene file: reads `r`'s object into `options` (the hooks first, then every value and
  // group not taken by them, then the checks); `r.finish()` is left to the caller.
  void read(const json_reader::Context& ctx, json_reader::ObjectReader& r, void* options) const;
  // Writes every value (unset optional ones left out) and the hooks' keys.
  nlohmann::ordered_json write(const void* options) const;
  // For options set in code, not read from a file: throws cutaway::Error(where, key, reason)
  // for the first number (or vector component) outside its range, a size that is not a
  // power of two, or a zero direction.
  void checkRanges(const void* options, const std::string& where) const;

  const std::vector<std::shared_ptr<const Node>>& nodes() const { return nodes_; }

 private:
  template <class O>
  friend class OptionsBuilder;
  std::function<std::any()> makeDefault_;
  std::function<void*(std::any&)> data_;
  std::vector<std::shared_ptr<const Node>> nodes_;
  std::vector<ReadHook> readHooks_, checks_;
  std::vector<WriteHook> writeHooks_;
};

// A node of a schema's tree; the builder makes them, the readers and writers walk them.
struct OptionsSchema::Node {
  enum class Kind { Value, Group, Array } kind = Kind::Value;
  OptionSpec spec;  // Value: the option (get/set on the node's struct); Group/Array: key, doc
  // Value: the JSON form; default: the spec's type.
  std::function<OptionValue(const json_reader::Context&, const nlohmann::json&, const std::string&)>
      readJson;
  std::function<nlohmann::ordered_json(const OptionValue&)> writeJson;
  // Optional values: whether one is set, and unsetting it.
  std::function<bool(const void*)> isSet;
  // Group and Array: the member inside the node's struct, and the element's schema.
  std::function<void*(void*)> member;
  std::shared_ptr<const OptionsSchema> inner;
  // Group: switched by a bool member or an std::optional (JSON true/false, or an object that
  // switches it on); `enabled` is its spec (key: the group's).
  bool switchable = false;
  bool switchInside = false;  // the switch is a member of the group's struct ("enabled" in JSON)
  OptionSpec enabled;
  // Array: the element count's bounds, and the vector's size and growth.
  std::size_t minCount = 0, maxCount = 0;
  std::function<std::size_t(const void*)> size;
  std::function<void*(void*, std::size_t)> element;
  std::function<void(void*, std::size_t)> resize;
};

// Builds the schema of options struct O from member pointers.
template <class O>
class OptionsBuilder {
  using Node = OptionsSchema::Node;

 public:
  OptionsBuilder() {
    schema_.makeDefault_ = [] { return std::any(O{}); };
    schema_.data_ = [](std::any& a) -> void* { return std::any_cast<O>(&a); };
  }

  // A bool, or a vec3 as a colour (components in [0, 1]) or a direction (non-zero).
  OptionsBuilder& value(std::string key, bool O::*m, OptionInfo info) {
    return add(std::move(key), OptionSpec::Type::Bool, 0, 0, m, std::move(info));
  }
  OptionsBuilder& color(std::string key, glm::vec3 O::*m, OptionInfo info) {
    return add(std::move(key), OptionSpec::Type::Color, 0, 1, m, std::move(info));
  }
  OptionsBuilder& direction(std::string key, glm::vec3 O::*m, OptionInfo info) {
    return add(std::move(key), OptionSpec::Type::Direction, 0, 0, m, std::move(info));
  }
  OptionsBuilder& vec3(std::string key, glm::vec3 O::*m, double min, double max, OptionInfo info) {
    return add(std::move(key), OptionSpec::Type::Vec3, min, max, m, std::move(info));
  }
  OptionsBuilder& text(std::string key, std::string O::*m, OptionInfo info) {
    return add(std::move(key), OptionSpec::Type::Text, 0, 0, m, std::move(info));
  }
  // An integer or floating-point member in [min, max].
  template <class T>
    requires std::is_arithmetic_v<T> && (!std::is_same_v<T, bool>)
  OptionsBuilder& number(std::string key, T O::*m, double min, double max, OptionInfo info) {
    return add(std::move(key), std::is_integral_v<T> ? OptionSpec::Type::Int : OptionSpec::Type::Float,
               min, max, m, std::move(info));
  }
  // An enum member, by the names of its values in the scene file.
  template <class E>
    requires std::is_enum_v<E>
  OptionsBuilder& choice(std::string key, E O::*m, std::vector<std::pair<std::string, E>> names,
                         OptionInfo info) {
    Node n = node(std::move(key), OptionSpec::Type::Choice, 0, 0, std::move(info));
    for (const auto& [name, e] : names) n.spec.choices.push_back(name);
    n.spec.get = [m, names](const void* o) -> OptionValue {
      for (const auto& [name, e] : names)
        if (static_cast<const O*>(o)->*m == e) return name;
      return names.front().first;
    };
    n.spec.set = [m, names](void* o, const OptionValue& v) {
      for (const auto& [name, e] : names)
        if (name == std::get<std::string>(v)) static_cast<O*>(o)->*m = e;
    };
    return push(std::move(n));
  }
  // A string member that is one of `names` (e.g. a name the registry lists).
  OptionsBuilder& choice(std::string key, std::string O::*m, std::vector<std::string> names,
                         OptionInfo info) {
    Node n = node(std::move(key), OptionSpec::Type::Choice, 0, 0, std::move(info));
    n.spec.choices = std::move(names);
    n.spec.get = [m](const void* o) -> OptionValue { return static_cast<const O*>(o)->*m; };
    n.spec.set = [m](void* o, const OptionValue& v) {
      static_cast<O*>(o)->*m = std::get<std::string>(v);
    };
    return push(std::move(n));
  }
  // An std::optional member: unset unless given; `fallback` is what the panels show while it is
  // unset (its doc says what unset means).
  template <class T>
  OptionsBuilder& optional(std::string key, std::optional<T> O::*m, OptionSpec::Type type,
                           double min, double max, T fallback, OptionInfo info) {
    Node n = node(std::move(key), type, min, max, std::move(info));
    n.spec.get = [m, fallback](const void* o) -> OptionValue {
      return toValue((static_cast<const O*>(o)->*m).value_or(fallback));
    };
    n.spec.set = [m](void* o, const OptionValue& v) {
      static_cast<O*>(o)->*m = fromValue<T>(v);
    };
    n.isSet = [m](const void* o) { return (static_cast<const O*>(o)->*m).has_value(); };
    return push(std::move(n));
  }
  // A value that is no member: a viewer control computed from others (never in the file).
  OptionsBuilder& derived(std::string key, OptionSpec::Type type, double min, double max,
                          std::function<OptionValue(const O&)> get,
                          std::function<void(O&, const OptionValue&)> set, OptionInfo info) {
    Node n = node(std::move(key), type, min, max, std::move(info));
    n.spec.inFile = false;
    n.spec.get = [get](const void* o) { return get(*static_cast<const O*>(o)); };
    n.spec.set = [set](void* o, const OptionValue& v) { set(*static_cast<O*>(o), v); };
    return push(std::move(n));
  }

  // A member struct as a nested object, described by `inner`.
  template <class S>
  OptionsBuilder& group(std::string key, S O::*m, const OptionsSchema& inner, OptionInfo info) {
    Node n = groupNode(std::move(key), inner, std::move(info));
    n.member = [m](void* o) -> void* { return &(static_cast<O*>(o)->*m); };
    return push(std::move(n));
  }
  // The same, switched on and off by the bool member `on`: JSON true, false, or an object
  // (which switches it on).
  template <class S>
  OptionsBuilder& group(std::string key, S O::*m, bool O::*on, const OptionsSchema& inner,
                        OptionInfo info) {
    Node n = groupNode(key, inner, info);
    n.member = [m](void* o) -> void* { return &(static_cast<O*>(o)->*m); };
    n.switchable = true;
    n.enabled = node(key, OptionSpec::Type::Bool, 0, 0, info).spec;
    n.enabled.get = [on](const void* o) -> OptionValue { return static_cast<const O*>(o)->*on; };
    n.enabled.set = [on](void* o, const OptionValue& v) {
      static_cast<O*>(o)->*on = std::get<bool>(v);
    };
    return push(std::move(n));
  }
  // The same, switched by the bool member `on` of the group's own struct, which its object may
  // also give as "enabled".
  template <class S>
  OptionsBuilder& group(std::string key, S O::*m, bool S::*on, const OptionsSchema& inner,
                        OptionInfo info) {
    Node n = groupNode(key, inner, info);
    n.member = [m](void* o) -> void* { return &(static_cast<O*>(o)->*m); };
    n.switchable = n.switchInside = true;
    n.enabled = node(key, OptionSpec::Type::Bool, 0, 0, info).spec;
    n.enabled.get = [m, on](const void* o) -> OptionValue {
      return (static_cast<const O*>(o)->*m).*on;
    };
    n.enabled.set = [m, on](void* o, const OptionValue& v) {
      (static_cast<O*>(o)->*m).*on = std::get<bool>(v);
    };
    return push(std::move(n));
  }
  // An std::optional member struct: unset is off; JSON true (its defaults), false, or an object.
  template <class S>
  OptionsBuilder& group(std::string key, std::optional<S> O::*m, const OptionsSchema& inner,
                        OptionInfo info) {
    Node n = groupNode(key, inner, info);
    n.member = [m](void* o) -> void* {
      auto& opt = static_cast<O*>(o)->*m;
      return opt ? &*opt : nullptr;
    };
    n.switchable = true;
    n.enabled = node(key, OptionSpec::Type::Bool, 0, 0, info).spec;
    n.enabled.get = [m](const void* o) -> OptionValue {
      return (static_cast<const O*>(o)->*m).has_value();
    };
    n.enabled.set = [m](void* o, const OptionValue& v) {
      auto& opt = static_cast<O*>(o)->*m;
      if (!std::get<bool>(v))
        opt.reset();
      else if (!opt)
        opt.emplace();
    };
    return push(std::move(n));
  }
  // A vector of element structs as a JSON array of objects, each described by `inner`.
  template <class E>
  OptionsBuilder& array(std::string key, std::vector<E> O::*m, std::size_t minCount,
                        std::size_t maxCount, const OptionsSchema& inner, OptionInfo info) {
    Node n = groupNode(std::move(key), inner, std::move(info));
    n.kind = Node::Kind::Array;
    n.minCount = minCount, n.maxCount = maxCount;
    n.size = [m](const void* o) { return (static_cast<const O*>(o)->*m).size(); };
    n.element = [m](void* o, std::size_t i) -> void* { return &(static_cast<O*>(o)->*m)[i]; };
    n.resize = [m](void* o, std::size_t count) { (static_cast<O*>(o)->*m).resize(count); };
    return push(std::move(n));
  }

  // Whether the last value added applies (the panels grey it out otherwise).
  OptionsBuilder& applies(std::function<bool(const O&)> when) {
    auto& n = const_cast<Node&>(*schema_.nodes_.back());
    n.spec.applies = [when](const void* o) { return when(*static_cast<const O*>(o)); };
    return *this;
  }
  // What setting the last value by its path sets beside it (OptionSpec::alsoSets).
  OptionsBuilder& alsoSets(std::function<void(O&)> what) {
    auto& n = const_cast<Node&>(*schema_.nodes_.back());
    n.spec.alsoSets = [what](void* o) { what(*static_cast<O*>(o)); };
    return *this;
  }
  // The scene file's JSON form of the last value, when not the type's own (e.g. a number that
  // also accepts true).
  OptionsBuilder& json(decltype(Node::readJson) read, decltype(Node::writeJson) write) {
    auto& n = const_cast<Node&>(*schema_.nodes_.back());
    n.readJson = std::move(read);
    n.writeJson = std::move(write);
    return *this;
  }
  // Keys the technique reads itself, before the schema's values (they take their keys).
  OptionsBuilder& readHook(std::function<void(const json_reader::Context&, json_reader::ObjectReader&, O&)> hook) {
    schema_.readHooks_.push_back([hook](const json_reader::Context& c, json_reader::ObjectReader& r, void* o) {
      hook(c, r, *static_cast<O*>(o));
    });
    return *this;
  }
  // Checks across values once everything is read (errors name the key).
  OptionsBuilder& check(std::function<void(const json_reader::Context&, json_reader::ObjectReader&, O&)> hook) {
    schema_.checks_.push_back([hook](const json_reader::Context& c, json_reader::ObjectReader& r, void* o) {
      hook(c, r, *static_cast<O*>(o));
    });
    return *this;
  }
  // The technique's own keys, written after the schema's values.
  OptionsBuilder& writeHook(std::function<void(const O&, nlohmann::ordered_json&)> hook) {
    schema_.writeHooks_.push_back([hook](const void* o, nlohmann::ordered_json& j) {
      hook(*static_cast<const O*>(o), j);
    });
    return *this;
  }

  OptionsSchema build() const { return schema_; }

 private:
  template <class T>
  static OptionValue toValue(const T& v) {
    if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, glm::vec3> ||
                  std::is_same_v<T, std::string>)
      return v;
    else
      return double(v);
  }
  template <class T>
  static T fromValue(const OptionValue& v) {
    if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, glm::vec3> ||
                  std::is_same_v<T, std::string>)
      return std::get<T>(v);
    else
      return T(std::get<double>(v));
  }

  static Node node(std::string key, OptionSpec::Type type, double min, double max, OptionInfo info) {
    Node n;
    n.spec.key = std::move(key);
    n.spec.label = info.label.empty() ? n.spec.key : std::move(info.label);
    n.spec.type = type;
    n.spec.min = min, n.spec.max = max;
    n.spec.sliderMax = info.sliderMax;
    n.spec.powerOfTwo = info.powerOfTwo;
    n.spec.doc = std::move(info.doc);
    n.spec.live = info.live;
    n.spec.required = info.required;
    n.spec.fileOnly = info.fileOnly;
    return n;
  }
  static Node groupNode(std::string key, const OptionsSchema& inner, OptionInfo info) {
    Node n = node(std::move(key), OptionSpec::Type::Bool, 0, 0, std::move(info));
    n.kind = Node::Kind::Group;
    n.inner = std::make_shared<const OptionsSchema>(inner);
    return n;
  }
  template <class T>
  OptionsBuilder& add(std::string key, OptionSpec::Type type, double min, double max, T O::*m,
                      OptionInfo info) {
    Node n = node(std::move(key), type, min, max, std::move(info));
    n.spec.get = [m](const void* o) { return toValue(static_cast<const O*>(o)->*m); };
    n.spec.set = [m](void* o, const OptionValue& v) { static_cast<O*>(o)->*m = fromValue<T>(v); };
    return push(std::move(n));
  }
  OptionsBuilder& push(Node n) {
    schema_.nodes_.push_back(std::make_shared<const Node>(std::move(n)));
    return *this;
  }

  OptionsSchema schema_;
};

}  // namespace cutaway
