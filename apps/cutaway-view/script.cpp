#include "script.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "colormap.hpp"
#include "cutaway/core/error.hpp"
#include "cutaway/core/image.hpp"

namespace cutaway::view {

namespace {

using Kind = ScriptCommand::Kind;

// How a command's arguments are read.
enum class Args {
  None,     // no arguments
  Numbers,  // `count` numbers
  Rest,     // the rest of the line, not empty (names and paths may hold spaces)
  Special,  // parsed by the command's own code below
};

struct CommandSpec {
  Kind kind;
  Args args;
  int count = 0;
};

const std::map<std::string, CommandSpec>& commands() {
  static const std::map<std::string, CommandSpec> table{
      {"wait", {Kind::Wait, Args::Numbers, 1}},
      {"orbit", {Kind::Orbit, Args::Numbers, 2}},
      {"look", {Kind::Look, Args::Numbers, 2}},
      {"pan", {Kind::Pan, Args::Numbers, 2}},
      {"zoom", {Kind::Zoom, Args::Numbers, 1}},
      {"fly", {Kind::Fly, Args::Numbers, 3}},
      {"projection", {Kind::Projection, Args::Special}},
      {"frame", {Kind::Frame, Args::None}},
      {"select", {Kind::Select, Args::Rest}},
      {"deselect", {Kind::Deselect, Args::None}},
      {"pick", {Kind::Pick, Args::Numbers, 2}},
      {"role", {Kind::Role, Args::Special}},
      {"importance", {Kind::Importance, Args::Numbers, 1}},
      {"angle", {Kind::Angle, Args::Special}},
      {"set", {Kind::Set, Args::Special}},
      {"aov", {Kind::Aov, Args::Special}},
      {"probe", {Kind::Probe, Args::Numbers, 2}},
      {"time", {Kind::Time, Args::Numbers, 1}},
      {"key", {Kind::Key, Args::Numbers, 1}},
      {"clear-path", {Kind::ClearPath, Args::None}},
      {"screenshot", {Kind::Screenshot, Args::Rest}},
      {"screenshot-window", {Kind::ScreenshotWindow, Args::Rest}},
      {"save", {Kind::Save, Args::Rest}},
      {"reload", {Kind::Reload, Args::None}},
      {"open", {Kind::Open, Args::Rest}},
      {"save-aovs", {Kind::SaveAovs, Args::Rest}},
      {"panels", {Kind::Panels, Args::Special}},
      {"moving", {Kind::Moving, Args::Special}},
      {"timings", {Kind::Timings, Args::None}},
      {"quit", {Kind::Quit, Args::None}},
  };
  return table;
}

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

std::vector<std::string> words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

float number(const std::string& text) {
  double v = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc() || ptr != end || !std::isfinite(v))
    throw std::invalid_argument("expected a number, got " + quote(text));
  // Moves and values are 32-bit floats: 1e300 would become infinite, 1e-300 zero.
  if (std::abs(v) > double(std::numeric_limits<float>::max()) || (v != 0.0 && float(v) == 0.0f))
    throw std::invalid_argument(quote(text) + " lies beyond a 32-bit float's range");
  return float(v);
}

void expectCount(const std::string& name, const std::vector<std::string>& args, std::size_t n,
                 const std::string& usage) {
  if (args.size() != n)
    throw std::invalid_argument(
        quote(name) + " takes " + (n == 0 ? std::string("no arguments") : usage) + ", got " +
        std::to_string(args.size()) + " argument" + (args.size() == 1 ? "" : "s"));
}

// Range checks of the numeric commands, with the reason a person needs.
void checkNumbers(const ScriptCommand& c) {
  const auto& n = c.numbers;
  switch (c.kind) {
    case Kind::Wait:
      if (n[0] < 0 || n[0] != std::floor(n[0]) || n[0] > 100000)
        throw std::invalid_argument("wait takes a whole number of frames in [0, 100000]");
      break;
    case Kind::Zoom:
      if (!(n[0] > 0)) throw std::invalid_argument("zoom factor must be greater than 0");
      break;
    case Kind::Importance:
      if (!(n[0] >= 0 && n[0] <= 1)) throw std::invalid_argument("importance must lie in [0, 1]");
      break;
    case Kind::Pick:
    case Kind::Probe:
      if (n[0] < 0 || n[1] < 0) throw std::invalid_argument("pixel coordinates must be ≥ 0");
      break;
    case Kind::Time:
    case Kind::Key:
      if (!(n[0] >= 0 && n[0] <= 1e6)) throw std::invalid_argument("time must lie in [0, 1e6] s");
      break;
    default:
      break;
  }
}

ScriptCommand parseLine(const std::string& line) {
  const std::string text = trim(line);
  const auto space = text.find_first_of(" \t");
  const std::string name = text.substr(0, space);
  const std::string rest = space == std::string::npos ? "" : trim(text.substr(space));
  const auto it = commands().find(name);
  if (it == commands().end()) throw std::invalid_argument("unknown command " + quote(name));
  const CommandSpec& spec = it->second;
  ScriptCommand c{spec.kind};
  const std::vector<std::string> args = words(rest);
  switch (spec.args) {
    case Args::None:
      expectCount(name, args, 0, "");
      break;
    case Args::Numbers:
      expectCount(name, args, std::size_t(spec.count),
                  std::to_string(spec.count) + (spec.count == 1 ? " number" : " numbers"));
      for (const auto& a : args) c.numbers.push_back(number(a));
      checkNumbers(c);
      break;
    case Args::Rest:
      if (rest.empty()) throw std::invalid_argument(quote(name) + " needs an argument");
      c.text = rest;
      break;
    case Args::Special:
      break;
  }
  switch (spec.kind) {
    case Kind::Projection:
      expectCount(name, args, 1, "perspective or orthographic");
      if (args[0] != "perspective" && args[0] != "orthographic")
        throw std::invalid_argument("projection must be perspective or orthographic, got " +
                                    quote(args[0]));
      c.text = args[0];
      break;
    case Kind::Role: {
      expectCount(name, args, 1, "a role");
      Role role;
      if (!parseRole(args[0], role))
        throw std::invalid_argument("unknown role " + quote(args[0]) +
                                    " (expected one of: context, interest, exterior, interior)");
      c.text = args[0];
      break;
    }
    case Kind::Angle:
      expectCount(name, args, 1, "an angle in degrees or \"off\"");
      c.text = args[0];
      if (args[0] != "off") {
        c.text.clear();
        c.numbers.push_back(number(args[0]));
        if (!(c.numbers[0] >= 0 && c.numbers[0] <= 90))
          throw std::invalid_argument("cutaway angle must lie in [0, 90] degrees");
      }
      break;
    case Kind::Set: {
      expectCount(name, args, 2, "a parameter key and a value");
      c.parameter = findParameter(args[0]);
      if (!c.parameter) {
        std::string known;
        for (const auto& group : parameterGroups())
          for (const auto& p : group.parameters) known += (known.empty() ? "" : ", ") + p.key;
        throw std::invalid_argument("unknown parameter " + quote(args[0]) + " (known: " + known +
                                    ")");
      }
      try {
        c.value = parseOptionValue(*c.parameter, args[1]);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(args[0] + ": " + e.what());
      }
      break;
    }
    case Kind::Aov:
      if (args.empty() || args.size() > 2)
        throw std::invalid_argument(
            "\"aov\" takes a buffer name (or off) and an optional colormap");
      c.text = args[0];
      if (args.size() == 2) {
        Colormap map;
        if (!parseColormap(args[1], map)) {
          std::string list;
          for (const auto& n : colormapNames()) list += (list.empty() ? "" : ", ") + n;
          throw std::invalid_argument("unknown colormap " + quote(args[1]) +
                                      " (expected one of: " + list + ")");
        }
        c.colormap = args[1];
      }
      break;
    case Kind::Panels:
    case Kind::Moving:
      expectCount(name, args, 1, "on or off");
      if (args[0] != "on" && args[0] != "off")
        throw std::invalid_argument(name + " takes on or off, got " + quote(args[0]));
      c.on = args[0] == "on";
      break;
    case Kind::Screenshot:
    case Kind::ScreenshotWindow:
      if (!isPngName(c.text))
        throw std::invalid_argument(name + " writes PNG only: give the file a .png name");
      break;
    default:
      break;
  }
  return c;
}

}  // namespace

bool parseRole(const std::string& name, Role& out) {
  for (Role r : {Role::Context, Role::Interest, Role::Exterior, Role::Interior})
    if (name == roleName(r)) {
      out = r;
      return true;
    }
  return false;
}

Script parseScript(const std::string& text, const std::string& file) {
  Script script{file, {}};
  std::istringstream in(text);
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (const auto nul = line.find('\0'); nul != std::string::npos)
      throw Error(file, "line " + std::to_string(number) + ", column " + std::to_string(nul + 1),
                  "a NUL byte: a script is text");
    // '#' starts a comment only at the start of a line: paths may contain it.
    const std::string content = trim(line);
    if (content.empty() || content[0] == '#') continue;
    try {
      ScriptCommand c = parseLine(content);
      c.line = number;
      script.commands.push_back(std::move(c));
    } catch (const std::invalid_argument& e) {
      throw Error(file, "line " + std::to_string(number), e.what());
    }
  }
  return script;
}

Script loadScript(const std::filesystem::path& path) {
  // A folder would read as an empty script, a device (/dev/zero) without end.
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw Error(path.string(), "", "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string(), "", "cannot open script file");
  std::stringstream text;
  text << in.rdbuf();
  return parseScript(text.str(), path.string());
}

}  // namespace cutaway::view
