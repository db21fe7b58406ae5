// Scripts of viewer actions, one per line, replayed by `cutaway-view --script FILE`: the
// viewer's automated tests drive the real window and UI with them, and they record a
// session's steps in a file one can read. docs/viewer.md is the command reference.
//
//   orbit 30 10
//   select pistons
//   set cutters.adaptive.angle 30
//   screenshot out/view.png
//   quit
//
// Parsing checks every line (command, argument count, numbers, ranges, parameter keys and
// values) before anything runs; names of objects and AOVs are checked when the line runs,
// against the scene. Errors name the file and line: "s.txt: line 3: unknown command "orbt"".
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "cutaway/scene/scene.hpp"
#include "parameters.hpp"

namespace cutaway::view {

struct ScriptCommand {
  enum class Kind {
    Wait,              // wait N
    Orbit,             // orbit YAW PITCH
    Look,              // look YAW PITCH
    Pan,               // pan DX DY
    Zoom,              // zoom FACTOR
    Fly,               // fly RIGHT UP FORWARD
    Projection,        // projection perspective|orthographic
    Frame,             // frame
    Select,            // select NAME
    Deselect,          // deselect
    Pick,              // pick X Y
    Role,              // role ROLE
    Importance,        // importance V
    Angle,             // angle DEG|off
    Set,               // set KEY VALUE
    Aov,               // aov NAME|off [COLORMAP]
    Probe,             // probe X Y
    Time,              // time T
    Key,               // key T
    ClearPath,         // clear-path
    Screenshot,        // screenshot FILE
    ScreenshotWindow,  // screenshot-window FILE
    Save,              // save FILE
    Reload,            // reload
    Open,              // open FILE
    SaveAovs,          // save-aovs DIR
    Panels,            // panels on|off
    Moving,            // moving on|off: the view's changes count as a mouse drag's
    Timings,           // timings: print the last frame's size and times
    Quit,              // quit
  };
  Kind kind;
  int line = 0;                          // 1-based line in the script file
  std::vector<float> numbers;            // numeric arguments in order
  std::string text;                      // name, file, role, AOV, projection; "off" for Angle/Aov
  std::string colormap;                  // Aov: optional colormap name
  bool on = false;                       // Panels, Moving
  const Parameter* parameter = nullptr;  // Set
  ParameterValue value;                  // Set
};

struct Script {
  std::string file;  // for messages
  std::vector<ScriptCommand> commands;
};

// Throws cutaway::Error(file, "line N", reason) for the first bad line.
Script parseScript(const std::string& text, const std::string& file);
Script loadScript(const std::filesystem::path& path);

// "context", "interest", "exterior", "interior"; false for anything else.
bool parseRole(const std::string& name, Role& out);

}  // namespace cutaway::view
