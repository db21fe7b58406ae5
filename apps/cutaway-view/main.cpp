// cutaway-view — explores a scene with cutaways in a window (Burns11 ch. 6).
//
//   cutaway-view examples/engine-cutaway.json
//   cutaway-view examples/engine-cutaway.json --script session.txt --size 1024x768
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <regex>

#include "cutaway/core/atomic_file.hpp"
#include "cutaway/core/contained.hpp"
#include "cutaway/core/error.hpp"
#include "viewer.hpp"

int main(int argc, char** argv) {
  cutaway::startContainedHelper();  // while the process is small (cutaway/core/contained.hpp)
  cutaway::removeTemporariesOnSignals();  // a stopped run leaves no partial file behind
  CLI::App app{
      "cutaway-view: explore a scene with cutaways (mouse: orbit, pan, zoom; "
      "see docs/viewer.md)"};
  app.set_version_flag("--version", "cutaway-view 0.1.0");
  cutaway::view::ViewerOptions options;
  std::string scene, script, size;
  bool noPanels = false;
  app.add_option("scene", scene, "Scene file (JSON)")->required();
  app.add_option("--script", script,
                 "Replay a script of viewer actions and exit (docs/viewer.md lists the commands)");
  app.add_option("--size", size, "Window size WxH (default: the scene's resolution)");
  app.add_flag("--no-panels", noPanels, "Start with the panels hidden (H toggles them)");
  app.add_option("--interactive-fps", options.interactiveFps,
                 "While the view moves, draw frames that miss this rate at a lower resolution "
                 "(0: always at full size)")
      ->check([](const std::string& text) -> std::string {
        // CLI::Range lets NaN through.
        char* end = nullptr;
        const float fps = std::strtof(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !(fps >= 0.0f && fps <= 1000.0f))
          return "expected a number in [0, 1000], got " + cutaway::quote(text);
        return "";
      });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "cutaway-view: error: %s (see --help)\n", e.what());
    return 2;
  }
  // A refused command line exits 2, as the options above do.
  if (!size.empty()) {
    static const std::regex sizeRe(R"((\d{1,5})x(\d{1,5}))");
    std::smatch m;
    const char* why = nullptr;
    if (!std::regex_match(size, m, sizeRe)) {
      why = "expected WxH, e.g. 1024x768";
    } else {
      options.width = std::stoi(m[1]), options.height = std::stoi(m[2]);
      if (options.width < 1 || options.height < 1 || options.width > 16384 ||
          options.height > 16384)
        why = "width and height must be in [1, 16384]";
    }
    if (why) {
      std::fprintf(stderr, "cutaway-view: error: --size: %s, got %s\n", why,
                   cutaway::quote(size).c_str());
      return 2;
    }
  }
  try {
    options.scene = scene;
    options.script = script;
    options.panels = !noPanels;
    cutaway::view::Viewer viewer(options);
    return viewer.run();
  } catch (const cutaway::Error& e) {
    std::fprintf(stderr, "cutaway-view: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cutaway-view: internal error: %s\n", e.what());
    return 3;
  }
}
