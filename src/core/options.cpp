#include "cutaway/core/options.hpp"

#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "core/json_reader.hpp"
#include "cutaway/core/unit_vector.hpp"

namespace cutaway {

namespace {

using json = nlohmann::json;
using ordered_json = nlohmann::ordered_json;
using Node = OptionsSchema::Node;

bool parseNumber(const std::string& text, double& out) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, out);
  return ec == std::errc() && ptr == end && std::isfinite(out);
}

bool isPowerOfTwo(double v) {
  const auto n = std::int64_t(v);
  return n > 0 && (n & (n - 1)) == 0;
}

std::string rangeText(double lo, double hi) {
  return "[" + json_reader::decimal(lo) + ", " + json_reader::decimal(hi) + "]";
}

// The shortest decimal that reads back as the same float, for values that are floats: 35 stays
// 35, not 35.000000000000001, and the loader's float of it is bit-identical.
ordered_json number(double d) {
  const float f = float(d);
  return double(f) == d ? json_reader::exact(f) : d;
}

ordered_json valueJson(const OptionSpec& spec, const OptionValue& v) {
  if (const bool* b = std::get_if<bool>(&v)) return *b;
  if (const std::string* s = std::get_if<std::string>(&v)) return *s;
  if (const glm::vec3* c = std::get_if<glm::vec3>(&v)) return {number(c->x), number(c->y), number(c->z)};
  const double d = std::get<double>(v);
  if (spec.type == OptionSpec::Type::Int) return std::int64_t(std::llround(d));
  return number(d);
}

OptionValue readValue(const json_reader::Context& ctx, const OptionSpec& spec, const json& j,
                      const std::string& ptr) {
  using T = OptionSpec::Type;
  switch (spec.type) {
    case T::Bool:
      return json_reader::boolean(ctx, j, ptr);
    case T::Int: {
      const double v = json_reader::integer(ctx, j, ptr, int(spec.min), int(spec.max));
      if (spec.powerOfTwo && !isPowerOfTwo(v)) ctx.fail(ptr, "must be a power of two");
      return v;
    }
    case T::Float:
      return json_reader::number(ctx, j, ptr, spec.min, spec.max);
    case T::Choice:
      return json_reader::oneOf(ctx, j, ptr, spec.choices);
    case T::Color:
      return json_reader::color(ctx, j, ptr);
    case T::Direction:
      return json_reader::direction(ctx, j, ptr);
    case T::Vec3:
      return json_reader::vec3(ctx, j, ptr, spec.min, spec.max);
    case T::Text:
      return json_reader::string(ctx, j, ptr);
  }
  ctx.fail(ptr, "unsupported option type");
}

// `spec` re-rooted: its struct is reached from the root through `member`, under `prefix`.
// `enable`, when given, switches the struct on before a write (a switchable group's child).
// `missing` says why a write is lost where `member` finds no struct (an array entry).
OptionSpec reroot(OptionSpec spec, const std::string& prefix, std::function<void*(void*)> member,
                  std::function<bool(const void*)> applies,
                  std::shared_ptr<const OptionsSchema> inner,
                  std::function<void(void*)> enable = {},
                  std::function<std::string(const void*)> missing = {}) {
  spec.key = prefix + spec.key;
  auto get = spec.get;
  auto set = spec.set;
  auto own = spec.applies;
  if (missing || spec.absent)
    spec.absent = [missing, member, inner = spec.absent](const void* o) -> std::string {
      if (const void* p = member(const_cast<void*>(o))) return inner ? inner(p) : "";
      return missing ? missing(o) : "";
    };
  // A missing struct (an unset optional group, an array entry past the end) shows defaults
  // and ignores writes.
  spec.get = [get, member, inner](const void* o) {
    if (const void* p = member(const_cast<void*>(o))) return get(p);
    std::any defaults = inner->makeDefault();
    return get(inner->data(defaults));
  };
  spec.set = [set, member, enable](void* o, const OptionValue& v) {
    if (enable) enable(o);
    if (void* p = member(o)) set(p, v);
  };
  spec.applies = [own, member, applies](const void* o) {
    if (applies && !applies(o)) return false;
    const void* p = member(const_cast<void*>(o));
    return p && (!own || own(p));
  };
  return spec;
}

}  // namespace

OptionValue parseOptionValue(const OptionSpec& p, const std::string& text) {
  using Type = OptionSpec::Type;
  switch (p.type) {
    case Type::Bool:
      if (text == "true" || text == "on") return true;
      if (text == "false" || text == "off") return false;
      throw std::invalid_argument("expected true/false or on/off, got " + quote(text));
    case Type::Int:
    case Type::Float: {
      double v = 0;
      if (!parseNumber(text, v))
        throw std::invalid_argument("expected a number, got " + quote(text));
      if (p.type == Type::Int && v != std::floor(v))
        throw std::invalid_argument("expected an integer, got " + text);
      if (!(v >= p.min && v <= p.max))
        throw std::invalid_argument("value " + text + " is outside " + rangeText(p.min, p.max));
      if (p.powerOfTwo && !isPowerOfTwo(v))
        throw std::invalid_argument("value " + text + " is not a power of two");
      return v;
    }
    case Type::Choice: {
      std::string list;
      for (const auto& c : p.choices) {
        if (c == text) return text;
        list += (list.empty() ? "" : ", ") + c;
      }
      throw std::invalid_argument("unknown value " + quote(text) + " (expected one of: " + list +
                                  ")");
    }
    case Type::Text:
      return text;
    case Type::Color:
    case Type::Direction:
    case Type::Vec3: {
      glm::dvec3 v;
      std::size_t start = 0;
      for (int i = 0; i < 3; ++i) {
        const std::size_t comma = text.find(',', start);
        double c = 0;
        if ((i < 2) != (comma != std::string::npos) ||
            !parseNumber(text.substr(start, comma - start), c))
          throw std::invalid_argument("expected three comma-separated numbers x,y,z, got " +
                                      quote(text));
        if (p.type == Type::Color && !(c >= 0 && c <= 1))
          throw std::invalid_argument("colour channels must lie in [0, 1], got " + quote(text));
        if (p.type == Type::Vec3 && !(c >= p.min && c <= p.max))
          throw std::invalid_argument("component " + std::to_string(i) + " of " + quote(text) +
                                      " is outside " + rangeText(p.min, p.max));
        v[i] = c;
        start = comma + 1;
      }
      if (p.type != Type::Direction) return glm::vec3(v);
      const std::optional<glm::vec3> unit = unitVector(v);  // any length, as in a scene file
      if (!unit) throw std::invalid_argument("a direction must not be the zero vector");
      return *unit;
    }
  }
  throw std::invalid_argument("unsupported option type");
}

std::string formatOptionValue(const OptionValue& value) {
  std::ostringstream s;
  if (const bool* b = std::get_if<bool>(&value)) s << (*b ? "true" : "false");
  if (const double* d = std::get_if<double>(&value)) s << json_reader::decimal(*d);
  if (const std::string* t = std::get_if<std::string>(&value)) s << *t;
  if (const glm::vec3* v = std::get_if<glm::vec3>(&value))
    s << json_reader::decimal(v->x) << "," << json_reader::decimal(v->y) << ","
      << json_reader::decimal(v->z);
  return s.str();
}

std::vector<OptionSpec> OptionsSchema::flatten() const {
  std::vector<OptionSpec> out;
  for (const auto& n : nodes_) {
    switch (n->kind) {
      case Node::Kind::Value:
        if (!n->spec.fileOnly) out.push_back(n->spec);
        break;
      case Node::Kind::Group: {
        std::function<bool(const void*)> on;
        std::function<void(void*)> enable;
        if (n->switchable) {
          out.push_back(n->enabled);
          on = [get = n->enabled.get](const void* o) { return std::get<bool>(get(o)); };
          enable = [set = n->enabled.set](void* o) { set(o, true); };
        }
        for (const OptionSpec& s : n->inner->flatten())
          out.push_back(reroot(s, n->spec.key + ".", n->member, on, n->inner, enable));
        break;
      }
      case Node::Kind::Array:
        for (std::size_t i = 0; i < n->maxCount; ++i) {
          const auto member = [n, i](void* o) -> void* {
            return i < n->size(o) ? n->element(o, i) : nullptr;
          };
          const auto missing = [n, i](const void* o) {
            const std::size_t size = n->size(o);
            return "no entry " + std::to_string(i) + ": " + quote(n->spec.key) + " has " +
                   std::to_string(size) + (size == 1 ? " entry" : " entries");
          };
          for (const OptionSpec& s : n->inner->flatten())
            out.push_back(reroot(s, n->spec.key + "." + std::to_string(i) + ".", member, {},
                                 n->inner, {}, missing));
        }
        break;
    }
  }
  return out;
}

void OptionsSchema::checkRanges(const void* options, const std::string& where) const {
  using Type = OptionSpec::Type;
  for (const OptionSpec& o : flatten()) {
    if (o.applies && !o.applies(options)) continue;
    std::vector<double> values;
    if (o.type == Type::Int || o.type == Type::Float) values = {std::get<double>(o.get(options))};
    if (o.type == Type::Vec3) {
      const glm::vec3 v = std::get<glm::vec3>(o.get(options));
      values = {v.x, v.y, v.z};
    }
    for (const double v : values)
      if (!(v >= o.min && v <= o.max))
        throw Error(where, o.key, formatOptionValue(o.get(options)) + " is outside [" +
                                      formatOptionValue(o.min) + ", " + formatOptionValue(o.max) + "]");
    if (o.powerOfTwo && !isPowerOfTwo(values.front()))
      throw Error(where, o.key, formatOptionValue(o.get(options)) + " is not a power of two");
    if (o.type == Type::Direction && glm::length(std::get<glm::vec3>(o.get(options))) == 0.0f)
      throw Error(where, o.key, "a direction must not be the zero vector");
  }
}

void OptionsSchema::read(const json_reader::Context& ctx, json_reader::ObjectReader& r,
                         void* options) const {
  for (const ReadHook& hook : readHooks_) hook(ctx, r, options);
  for (const auto& n : nodes_) {
    const std::string& key = n->spec.key;
    if (r.taken(key) || (n->kind == Node::Kind::Value && !n->spec.inFile)) continue;
    const json* v = r.take(key);
    if (!v) {
      if (n->spec.required) ctx.fail(r.pointer(), "missing required key " + quote(key));
      continue;
    }
    const std::string ptr = r.at(key);
    switch (n->kind) {
      case Node::Kind::Value:
        n->spec.set(options, n->readJson ? n->readJson(ctx, *v, ptr) : readValue(ctx, n->spec, *v, ptr));
        break;
      case Node::Kind::Group: {
        if (n->switchable && v->is_boolean()) {
          n->enabled.set(options, v->get<bool>());
          break;
        }
        if (n->switchable && !v->is_object())
          ctx.fail(ptr, "expected true, false or an object, got " + json_reader::typeName(*v));
        json_reader::ObjectReader g(ctx, *v, ptr);
        if (n->switchable) n->enabled.set(options, true);
        if (n->switchInside)
          if (const json* e = g.take("enabled"))
            n->enabled.set(options, json_reader::boolean(ctx, *e, g.at("enabled")));
        n->inner->read(ctx, g, n->member(options));
        g.finish();
        break;
      }
      case Node::Kind::Array: {
        if (!v->is_array())
          ctx.fail(ptr, "expected an array of " + std::to_string(n->minCount) + " to " +
                            std::to_string(n->maxCount) + " entries, got " +
                            json_reader::typeName(*v));
        if (v->size() < n->minCount || v->size() > n->maxCount)
          ctx.fail(ptr, "expected " + std::to_string(n->minCount) + " to " +
                            std::to_string(n->maxCount) + " entries, got " +
                            std::to_string(v->size()));
        n->resize(options, v->size());
        for (std::size_t i = 0; i < v->size(); ++i) {
          json_reader::ObjectReader e(ctx, (*v)[i], ptr + "/" + std::to_string(i));
          n->inner->read(ctx, e, n->element(options, i));
          e.finish();
        }
        break;
      }
    }
  }
  for (const ReadHook& check : checks_) check(ctx, r, options);
}

ordered_json OptionsSchema::write(const void* options) const {
  ordered_json out = ordered_json::object();
  void* o = const_cast<void*>(options);
  for (const auto& n : nodes_) {
    const std::string& key = n->spec.key;
    switch (n->kind) {
      case Node::Kind::Value:
        if (!n->spec.inFile || (n->isSet && !n->isSet(o))) break;
        out[key] = n->writeJson ? n->writeJson(n->spec.get(o)) : valueJson(n->spec, n->spec.get(o));
        break;
      case Node::Kind::Group:
        if (n->switchable && !std::get<bool>(n->enabled.get(o))) {
          out[key] = false;
          break;
        }
        out[key] = n->inner->write(n->member(o));
        if (n->switchInside) out[key]["enabled"] = true;
        break;
      case Node::Kind::Array: {
        ordered_json list = ordered_json::array();
        for (std::size_t i = 0; i < n->size(o); ++i) list.push_back(n->inner->write(n->element(o, i)));
        out[key] = list;
        break;
      }
    }
  }
  for (const WriteHook& hook : writeHooks_) hook(options, out);
  return out;
}

}  // namespace cutaway
