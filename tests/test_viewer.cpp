// End-to-end tests of `cutaway-view`: the real program in a real window under Xvfb, driven
// by a script, its screenshot compared with `cutaway render` of the scene it saved.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>

#include "cutaway/core/image.hpp"
#include "run_command.hpp"

namespace fs = std::filesystem;
using namespace cutaway;

namespace {

const std::string kViewer = CUTAWAY_VIEW_BINARY;
const std::string kCli = CUTAWAY_BINARY;
const std::string kSource = CUTAWAY_SOURCE_DIR;

using test::Result;

Result run(const std::string& command) {
  return test::runCommand(command);
}

fs::path scratch(const std::string& name) {
  return test::scratchPath("view", name);
}

// scripts/setup-deps installs xvfb, so a missing xvfb-run is a failed set-up, not a skip
// (`ctest -E Viewer\\.` leaves these tests out on a machine without it).
bool hasXvfbRun() {
  return run("command -v xvfb-run >/dev/null").exitCode == 0;
}
constexpr const char* kNoXvfb = "xvfb-run is not installed (Debian package xvfb; scripts/setup-deps)";

// Runs the viewer under Xvfb: a private server (-a picks a free display number), a screen
// larger than any window the tests open, 24-bit colour so that the window has an RGB8
// default framebuffer, and -noreset: a server reset when the viewer disconnects signals
// xvfb-run (SIGUSR1) in the middle of its clean-up, which then fails ("problem while
// cleaning up temporary directory") and leaves the server running. The viewer's exit status
// and stderr are its own, kept apart from xvfb-run's.
// `shell` runs first in the viewer's shell (e.g. "ulimit -v 3000000; ").
Result runUnderXvfb(const std::string& args, const std::string& shell = "") {
  const fs::path rc = scratch("viewer.rc"), err = scratch("viewer.err");
  Result outer;
  // A second try when the server did not start (another Xvfb took the display meanwhile).
  for (int attempt = 0; attempt < 2; ++attempt) {
    fs::remove(rc);
    outer = run("xvfb-run -a -s '-screen 0 1280x1024x24 -noreset' sh -c '" + shell + kViewer + " " +
                args + " 2>" + err.string() + "; echo $? >" + rc.string() + "'");
    std::ifstream rcStream(rc), errStream(err);
    int status = -1;
    if (rcStream >> status)
      return {status, outer.out, std::string((std::istreambuf_iterator<char>(errStream)), {})};
  }
  return {-1, outer.out, "xvfb-run did not run the viewer: " + outer.err};
}

int count(const std::string& text, char c) {
  return int(std::count(text.begin(), text.end(), c));
}

// Pixels of the objectId AOV whose object is in `ids`.
int pixelsOf(const FloatImage& objectId, const std::set<int>& ids) {
  int n = 0;
  for (float v : objectId.data) n += ids.count(int(std::lround(v)));
  return n;
}

// `cutaway` on the rasteriser the viewer ran on: under Xvfb the viewer runs on Mesa (GLX has
// no other driver there); on a machine with a GPU the CLI would take the GPU's EGL device:
// keep it on Mesa's EGL too, so that both rasterise alike.
std::string cliLike(const Result& viewer) {
  const std::string mesaEgl = "/usr/share/glvnd/egl_vendor.d/50_mesa.json";
  return (viewer.out.find("llvmpipe") != std::string::npos && fs::exists(mesaEgl)
              ? "__EGL_VENDOR_LIBRARY_FILENAMES=" + mesaEgl + " "
              : std::string()) +
         kCli;
}

// The viewer's screenshot against `cutaway render` of the scene it saved. Both run Mesa's
// llvmpipe (GLX in the window, EGL surfaceless in the CLI) on the same scene values, bit for
// bit (floats are saved in their shortest exact form); the images were identical when this
// was written. The slack (a mean of 0.1/255, 0.05% of the pixels off by more than 32) is for
// a driver whose window and headless paths differ in rounding, not for a different image.
void expectSameImage(const Rgba8Image& shot, const Rgba8Image& ref) {
  ASSERT_EQ(ref.width, shot.width);
  ASSERT_EQ(ref.height, shot.height);
  double sum = 0;
  int different = 0;
  for (std::size_t i = 0; i < shot.pixels.size(); i += 4) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int d = std::abs(int(shot.pixels[i + c]) - int(ref.pixels[i + c]));
      sum += d;
      worst = std::max(worst, d);
    }
    different += worst > 32;
  }
  const double mean = sum / (3.0 * shot.width * shot.height);
  const double fraction = double(different) / (shot.width * shot.height);
  std::printf(
      "viewer vs cutaway render: mean difference %.4f / 255, %.5f%% of pixels off by > 32\n", mean,
      100.0 * fraction);
  EXPECT_LE(mean, 0.1) << "mean channel difference (of 255)";
  EXPECT_LE(fraction, 0.0005) << "fraction of pixels off by more than 32";
}

}  // namespace

TEST(Viewer, WithoutADisplayFailsWithOneLineSuggestingRender) {
  const Result r =
      run("env -u DISPLAY -u WAYLAND_DISPLAY " + kViewer + " " + kSource + "/examples/bunny.json");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_EQ(count(r.err, '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("cutaway-view: error: no display", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("cutaway render"), std::string::npos) << r.err;
}

// A refused command line exits 2, the size's as the other options'; a script or a scene that
// is a folder or a device is named so before anything is read (/dev/zero once grew without end).
TEST(Viewer, BadCommandLinesAndFilesAreRefusedBeforeAWindowOpens) {
  const std::string bunny = kSource + "/examples/bunny.json";
  for (const std::string& size : {"0x0", "20000x10", "big"}) {
    const Result r = run("env -u DISPLAY " + kViewer + " " + bunny + " --size " + size);
    EXPECT_EQ(r.exitCode, 2) << size;
    EXPECT_EQ(r.err.rfind("cutaway-view: error: --size: ", 0), 0u) << r.err;
  }
  const Result fps = run("env -u DISPLAY " + kViewer + " " + bunny + " --interactive-fps -1");
  EXPECT_EQ(fps.exitCode, 2) << fps.err;
  for (const std::string& file : {std::string("/dev/zero"), scratch("").string()}) {
    const Result script = run("env -u DISPLAY " + kViewer + " " + bunny + " --script " + file);
    EXPECT_EQ(script.exitCode, 1);
    EXPECT_NE(script.err.find(": not a regular file"), std::string::npos) << script.err;
    const Result scene = run("env -u DISPLAY " + kViewer + " " + file);
    EXPECT_EQ(scene.exitCode, 1);
    EXPECT_NE(scene.err.find(": not a regular file"), std::string::npos) << scene.err;
  }
}

TEST(Viewer, BadScriptIsRejectedBeforeAWindowOpens) {
  const fs::path script = scratch("bad.txt");
  std::ofstream(script) << "wait 1\norbit 30\n";
  // No display needed: the script is checked first.
  const Result r = run("env -u DISPLAY " + kViewer + " " + kSource +
                       "/examples/bunny.json --script " + script.string());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.err, "cutaway-view: error: " + script.string() +
                       ": line 2: \"orbit\" takes 2 numbers, got 1 argument\n");
}

TEST(Viewer, ScriptLineFailingAtRunTimeNamesTheLine) {
  ASSERT_TRUE(hasXvfbRun()) << kNoXvfb;
  const fs::path script = scratch("unknown-object.txt");
  std::ofstream(script) << "wait 1\nselect no such part\nquit\n";
  const Result r =
      runUnderXvfb(kSource + "/examples/bunny.json --size 160x120 --script " + script.string());
  EXPECT_EQ(r.exitCode, 1) << r.err;
  EXPECT_EQ(r.err, "cutaway-view: error: " + script.string() +
                       ": line 2: no object or group named \"no such part\"\n");
  // A 100 KB name is quoted up to 60 characters.
  std::ofstream(script) << "wait 1\nselect " << std::string(100000, 'n') << "\nquit\n";
  const Result longName =
      runUnderXvfb(kSource + "/examples/bunny.json --size 160x120 --script " + script.string());
  EXPECT_EQ(longName.exitCode, 1) << longName.err.substr(0, 200);
  EXPECT_EQ(longName.err, "cutaway-view: error: " + script.string() +
                              ": line 2: no object or group named \"" + std::string(60, 'n') +
                              "…\"\n");
  // A cutter the scene has no roles for, refused as `cutaway render --set` refuses it.
  std::ofstream(script) << "wait 1\nset cutters.breakaway true\nquit\n";
  const Result roles =
      runUnderXvfb(kSource + "/examples/bunny.json --size 160x120 --script " + script.string());
  EXPECT_EQ(roles.exitCode, 1) << roles.err;
  EXPECT_EQ(roles.err, "cutaway-view: error: " + script.string() +
                           ": line 2: set: /cutters/breakaway: no object has role \"exterior\": "
                           "nothing to cut (give the outside objects or volumes that role, or "
                           "match objects by name with \"overrides\")\n");
  // An option of a surface the scene does not have, named as `cutaway render --set` names it.
  std::ofstream(script) << "wait 1\nset cutters.clipSurfaces.surfaces.0.position 0.5\nquit\n";
  const Result entry =
      runUnderXvfb(kSource + "/examples/bunny.json --size 160x120 --script " + script.string());
  EXPECT_EQ(entry.exitCode, 1) << entry.err;
  EXPECT_EQ(entry.err, "cutaway-view: error: " + script.string() +
                           ": line 2: cutters.clipSurfaces.surfaces.0.position: no entry 0: "
                           "\"surfaces\" has 0 entries\n");
  // A pixel past the view, also past INT_MAX (it once wrapped to a negative int: a crash).
  for (const auto& [line, coordinates] :
       {std::pair{"probe 3000000000 1", "3000000000, 1"}, std::pair{"pick 1e30 1", "1e+30, 1"},
        std::pair{"pick 160 0", "160, 0"}}) {
    std::ofstream(script) << "wait 1\n" << line << "\nquit\n";
    const Result far =
        runUnderXvfb(kSource + "/examples/bunny.json --size 160x120 --script " + script.string());
    EXPECT_EQ(far.exitCode, 1) << far.err;
    EXPECT_EQ(far.err, "cutaway-view: error: " + script.string() + ": line 2: pixel (" +
                           coordinates + ") is outside the 160×120 view\n");
  }
}

// The issue's scenario: orbit, select the pistons, change the cutter, look at the cutaway
// depth, take screenshots, save the scene; the saved scene must render the same image with
// `cutaway render`, and the cutaway must show what the plain render hides.
TEST(Viewer, ScriptedSessionMatchesCutawayRenderOfTheSavedScene) {
  ASSERT_TRUE(hasXvfbRun()) << kNoXvfb;
  const fs::path view = scratch("view.png"), window = scratch("window.png"),
                 saved = scratch("saved.json"), aovs = scratch("view-aovs"),
                 script = scratch("session.txt");
  std::ofstream(script) << "# the session of tests/test_viewer.cpp\n"
                           "wait 2\n"
                           "orbit 25 8\n"
                           "zoom 1.1\n"
                           "select pistons\n"
                           "set cutters.adaptive.angle 30\n"
                           "angle 40\n"
                           "set style.lines.width 2\n"
                           "pick 320 240\n"
                           "deselect\n"
                           "screenshot "
                        << view.string()
                        << "\n"
                           "save-aovs "
                        << aovs.string()
                        << "\n"
                           // A camera path whose first key is the screenshot's camera.
                           "key 0\n"
                           "orbit 40 0\n"
                           "key 2\n"
                           "save "
                        << saved.string()
                        << "\n"
                           "aov cutawayDepth\n"
                           "probe 320 240\n"
                           "probe 0 0\n"
                           "select crankshaft\n"
                           "wait 1\n"
                           "screenshot-window "
                        << window.string()
                        << "\n"
                           "quit\n";
  const Result r = runUnderXvfb(kSource + "/examples/engine-cutaway.json --size 640x480 --script " +
                                script.string());
  ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
  // The 512² texel under each pixel's centre, rows from the top as in the saved PFM.
  EXPECT_NE(r.out.find("probe 320 240: cutawayDepth [256, 256]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("probe 0 0: cutawayDepth [0, 0]"), std::string::npos) << r.out;
  // The centre of the view shows a part of the engine (picked through the object-id AOV).
  EXPECT_NE(r.out.find("pick 320 240: engine/"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("saved " + saved.string()), std::string::npos) << r.out;

  // The rendered view: its size, and the engine covers a good part of it.
  const Rgba8Image shot = readPng(view);
  ASSERT_EQ(shot.width, 640);
  ASSERT_EQ(shot.height, 480);
  int covered = 0;
  for (int y = 0; y < shot.height; ++y)
    for (int x = 0; x < shot.width; ++x)
      covered += shot.at(x, y)[0] < 200 || shot.at(x, y)[2] < 180;
  EXPECT_GT(covered, shot.width * shot.height / 10);

  // `cutaway render` of the saved scene (at time 0: the first key of its camera path, the
  // screenshot's camera): the same image.
  const std::string cli = cliLike(r);
  const fs::path reference = scratch("reference.png");
  const Result rendered = run(cli + " render " + saved.string() + " -o " + reference.string() +
                              " --aov " + scratch("saved-aovs").string());
  ASSERT_EQ(rendered.exitCode, 0) << rendered.err;
  expectSameImage(shot, readPng(reference));

  // The cutaway shows the objects of interest: their pixels in the viewer's object ids
  // against those of a plain render (--no-cutaway) of the saved scene.
  const auto info = nlohmann::json::parse(run(kCli + " info " + saved.string()).out);
  std::set<int> interest;
  for (const auto& o : info["objects"])
    if (o["role"] == "interest" && !o["proxy"].get<bool>()) interest.insert(o["index"].get<int>());
  ASSERT_EQ(interest.size(), 7u);  // 2 pistons, 2 rods, 2 pins, the crankshaft
  const Result plain =
      run(cli + " render " + saved.string() + " --no-cutaway -o " + scratch("plain.png").string() +
          " --aov " + scratch("plain-aovs").string());
  ASSERT_EQ(plain.exitCode, 0) << plain.err;
  const int visibleCut = pixelsOf(readPfm(aovs / "objectId.pfm"), interest);
  const int visiblePlain = pixelsOf(readPfm(scratch("plain-aovs") / "objectId.pfm"), interest);
  std::printf("interest pixels: %d with the cutaway, %d without\n", visibleCut, visiblePlain);
  EXPECT_GT(visibleCut, 2 * visiblePlain) << visibleCut << " vs " << visiblePlain;
  EXPECT_GT(visibleCut, shot.width * shot.height / 50);

  // The saved scene holds the session's changes in the documented format.
  std::ifstream in(saved);
  const auto json = nlohmann::json::parse(in);
  EXPECT_EQ(json["cutters"]["adaptive"]["angle"], 30.0);
  EXPECT_EQ(json["style"]["lines"]["width"], 2.0);
  int pistonOverrides = 0;
  for (const auto& o : json["objects"][0]["overrides"])
    if (o.contains("params") && o["params"].value("cutawayAngle", 0.0) == 40.0) ++pistonOverrides;
  EXPECT_EQ(pistonOverrides, 2);
  ASSERT_EQ(json["camera"]["path"].size(), 2u);
  EXPECT_EQ(json["camera"]["path"][1]["time"], 2.0);

  // The window screenshot shows the panels over the view: ImGui's dark windows where the
  // rendered image is light.
  const Rgba8Image ui = readPng(window);
  ASSERT_EQ(ui.width, 640);
  double panel = 0;
  for (int y = 60; y < 100; ++y)
    for (int x = 20; x < 60; ++x) panel += ui.at(x, y)[0] + ui.at(x, y)[1] + ui.at(x, y)[2];
  EXPECT_LT(panel / (3.0 * 40 * 40), 90.0);
}

// The importance slider's script command changes the contextual cutaway (Burns11 eqs.
// 7.1–7.3): the cylinders at importance 1 are trimmed nowhere, and the saved scene renders as
// the viewer shows it.
TEST(Viewer, ImportanceChangesTheContextualCutaway) {
  ASSERT_TRUE(hasXvfbRun()) << kNoXvfb;
  const fs::path before = scratch("importance-before.png"), after = scratch("importance-after.png"),
                 saved = scratch("importance.json"), script = scratch("importance.txt");
  std::ofstream(script) << "wait 1\nscreenshot " << before.string()
                        << "\nselect cylinders\nimportance 1\nscreenshot " << after.string()
                        << "\nsave " << saved.string() << "\nquit\n";
  const Result r = runUnderXvfb(kSource + "/examples/engine-contextual.json --size 320x240 --script " +
                                script.string());
  ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
  const Rgba8Image shot = readPng(after);
  EXPECT_NE(readPng(before).pixels, shot.pixels);
  const fs::path reference = scratch("importance-reference.png");
  const Result rendered = run(cliLike(r) + " render " + saved.string() + " -o " + reference.string());
  ASSERT_EQ(rendered.exitCode, 0) << rendered.err;
  expectSameImage(shot, readPng(reference));
}

// A live option of a switchable group that is off (the lines' width with the lines off)
// switches the group on, as `cutaway render --set` does: the next frame draws the lines, and
// is the image `cutaway render` makes of the saved scene (the width alone was a uniform, and
// the lines stayed off until some later change rebuilt the renderer).
TEST(Viewer, ALiveOptionOfAGroupThatIsOffSwitchesItOn) {
  ASSERT_TRUE(hasXvfbRun()) << kNoXvfb;
  const fs::path off = scratch("lines-off.png"), on = scratch("lines-on.png"),
                 saved = scratch("lines.json"), script = scratch("lines.txt");
  std::ofstream(script) << "set style.lines off\nwait 1\nscreenshot " << off.string()
                        << "\nset style.lines.width 2\nscreenshot " << on.string() << "\nsave "
                        << saved.string() << "\nquit\n";
  const Result r =
      runUnderXvfb(kSource + "/examples/bunny.json --size 200x150 --script " + script.string());
  ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
  const Rgba8Image shot = readPng(on);
  EXPECT_NE(readPng(off).pixels, shot.pixels);
  const fs::path reference = scratch("lines-reference.png");
  const Result rendered =
      run(cliLike(r) + " render " + saved.string() + " -o " + reference.string());
  ASSERT_EQ(rendered.exitCode, 0) << rendered.err;
  expectSameImage(shot, readPng(reference));
}

// Konev18 §5's radius and §6's colours changed in a running viewer: the renderer is kept and
// draws them the next frame, which must be the image a fresh `cutaway render` of the saved
// scene makes.
TEST(Viewer, NetworkOptionsChangeLiveAndSave) {
  ASSERT_TRUE(hasXvfbRun()) << kNoXvfb;
  const fs::path view = scratch("pipes.png"), saved = scratch("pipes.json"),
                 script = scratch("pipes.txt");
  std::ofstream(script) << "wait 1\n"
                           "set networks.radiusScale 1.8\n"
                           "set networks.cutColor 0.1,0.1,0.9\n"
                           "set networks.waterLow 0.9,0.1,0.1\n"
                           "set networks.waterHigh 0.9,0.1,0.1\n"
                           "set networks.shaftOpening 0\n"
                           "screenshot "
                        << view.string() << "\nsave " << saved.string()
                        << "\naov terrainDistance\nprobe 10 10\nquit\n";
  const Result r = runUnderXvfb(kSource + "/examples/pipes-street.json --size 320x200 --script " +
                                script.string());
  ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
  // The terrain opening's distance texture is no frame target, yet the inspector shows it.
  EXPECT_NE(r.out.find("probe 10 10: terrainDistance"), std::string::npos) << r.out;
  const fs::path reference = scratch("pipes-reference.png");
  const Result rendered =
      run(cliLike(r) + " render " + saved.string() + " -o " + reference.string());
  ASSERT_EQ(rendered.exitCode, 0) << rendered.err;
  const Rgba8Image shot = readPng(view);
  expectSameImage(shot, readPng(reference));
  // The water took the new colour: strongly red pixels, which the example has none of.
  int red = 0;
  for (int y = 0; y < shot.height; ++y)
    for (int x = 0; x < shot.width; ++x)
      red += shot.at(x, y)[0] > 150 && shot.at(x, y)[1] < 80 && shot.at(x, y)[2] < 80;
  EXPECT_GT(red, 50);
  std::ifstream in(saved);
  EXPECT_EQ(nlohmann::json::parse(in)["networks"][0]["radiusScale"].get<float>(), 1.8f);
}

// Reloading and opening scenes: a file that fails to load, or that the device cannot render
// (16 samples on llvmpipe, which takes 4), leaves the last good scene on screen and says why,
// and the next edit still applies; a good one replaces it at the window's size (not the
// file's resolution), and `reload` reads the file again keeping the view.
// A frame that needs more memory than there is (a CPU cutaway buffer of 8192², 3.8 GB of
// jump-flooding state, under a 3 GB limit) gives way to the last scene drawn, as a scene
// the device refuses does; the error names the option.
TEST(Viewer, AFrameWithoutMemoryKeepsTheLastGoodScene) {
  ASSERT_TRUE(hasXvfbRun()) << kNoXvfb;
  if (test::kAddressSanitizer) GTEST_SKIP() << "ulimit -v cannot hold AddressSanitizer";
  const fs::path script = scratch("memory.txt"), before = scratch("memory-before.png"),
                 after = scratch("memory-after.png"), turned = scratch("memory-turned.png");
  std::ofstream(script) << "set cutters.adaptive.compute cpu\nwait 1\nscreenshot "
                        << before.string() << "\nset cutters.adaptive.bufferSize 8192\nscreenshot "
                        << after.string() << "\norbit 30 0\nscreenshot " << turned.string()
                        << "\nquit\n";
  const Result r = runUnderXvfb(
      kSource + "/examples/engine-cutaway.json --size 160x120 --script " + script.string(),
      "ulimit -v 3000000; ");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find(script.string() +
                       ": line 4: cutters.adaptive.bufferSize: out of memory for the 8192x8192 "
                       "cutaway buffer on the CPU"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("(the last good scene stays)"), std::string::npos) << r.err;
  const Rgba8Image a = readPng(before), b = readPng(after), c = readPng(turned);
  EXPECT_EQ(b.pixels, a.pixels);  // the 512² buffer's picture
  EXPECT_NE(c.pixels, a.pixels);  // and the viewer goes on drawing
}

// A move that 32-bit floats cannot draw is undone and reported, also as a script's first
// command (before any frame: back to the file's camera); the next one applies.
TEST(Viewer, AViewFloatsCannotDrawStaysWhereItWas) {
  ASSERT_TRUE(hasXvfbRun()) << kNoXvfb;
  std::vector<fs::path> shots;
  for (int i = 0; i < 4; ++i)
    shots.push_back(scratch("unresolvable-" + std::to_string(i) + ".png"));
  const fs::path script = scratch("unresolvable.txt");
  std::ofstream(script) << "zoom 1e30\nscreenshot " << shots[0].string()
                        << "\nzoom 1e30\nscreenshot " << shots[1].string()
                        << "\npan 1e30 0\nscreenshot " << shots[2].string()
                        << "\nzoom 2\nscreenshot " << shots[3].string() << "\nquit\n";
  const Result r =
      runUnderXvfb(kSource + "/examples/bunny.json --size 160x120 --script " + script.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(count(r.err, '\n'), 3) << r.err;
  for (const char* line : {": line 1: ", ": line 3: "})
    EXPECT_NE(
        r.err.find(script.string() + line +
                   "the view stays where it was (camera: its view and projection are not finite"),
        std::string::npos)
        << r.err;
  const Rgba8Image first = readPng(shots[0]);
  EXPECT_EQ(readPng(shots[1]).pixels, first.pixels);
  EXPECT_EQ(readPng(shots[2]).pixels, first.pixels);
  EXPECT_NE(readPng(shots[3]).pixels, first.pixels);
}

TEST(Viewer, AFailedReloadKeepsTheLastGoodScene) {
  ASSERT_TRUE(hasXvfbRun()) << kNoXvfb;
  const std::string bunny = R"({"resolution": [200, 100], "samples": 1, "objects": [
      {"name": "bunny", "file": "/usr/share/glmark2/models/bunny.obj", "color": )";
  const fs::path red = scratch("red.json"), blue = scratch("blue.json"),
                 broken = scratch("broken.json"), tooMany = scratch("too-many.json"),
                 far = scratch("far.json"), script = scratch("reload.txt");
  std::ofstream(red) << bunny << "[0.9, 0.1, 0.1]}]}";
  std::ofstream(blue) << bunny << "[0.1, 0.2, 0.9]}]}";
  std::ofstream(broken) << bunny << "[0.1, 0.2, 0.9]}";
  std::string sixteen = bunny;
  sixteen.replace(sixteen.find("\"samples\": 1"), 12, "\"samples\": 16");
  std::ofstream(tooMany) << sixteen << "[0.1, 0.9, 0.1]}]}";
  // Its first frame fails (a view 1e14 away: floats cannot draw it), after the renderer was
  // made: the file, its document and the view go back too, so a reload reads the old file.
  std::ofstream(far)
      << bunny << "[0.1, 0.9, 0.1]}], \"camera\": {\"eye\": [1e14, 0, 0], \"target\": [0, 0, 0]}}";
  std::vector<fs::path> shots;
  for (int i = 0; i < 9; ++i) shots.push_back(scratch("reload-" + std::to_string(i) + ".png"));
  std::ofstream(script) << "wait 1\nscreenshot " << shots[0].string()  // red
                        << "\nopen " << broken.string() << "\nscreenshot " << shots[1].string()
                        << "\nopen " << tooMany.string() << "\nscreenshot " << shots[2].string()
                        << "\nset style.name toon\nscreenshot " << shots[3].string() << "\nopen "
                        << blue.string() << "\norbit 40 10\nscreenshot " << shots[4].string()
                        << "\nreload\nscreenshot " << shots[5].string() << "\nopen "
                        << blue.string() << "\nscreenshot " << shots[6].string() << "\nopen "
                        << far.string() << "\nscreenshot " << shots[7].string()
                        << "\nreload\nscreenshot " << shots[8].string() << "\nquit\n";
  const Result r = runUnderXvfb(red.string() + " --size 160x120 --script " + script.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  // Each failure names the script's line, then the file's own place.
  EXPECT_NE(
      r.err.find("cutaway-view: " + script.string() + ": line 3: " + broken.string() + ": line "),
      std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("invalid JSON"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("16 samples exceed the device's"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(": line 16: camera: the depth range from near"), std::string::npos) << r.err;
  EXPECT_EQ(count(r.err, '\n'), 3) << r.err;
  EXPECT_NE(r.err.find("(the last good scene stays)"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("opened " + blue.string()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("reloaded " + blue.string()), std::string::npos) << r.out;
  EXPECT_NE(r.out.rfind("reloaded " + blue.string()), r.out.find("reloaded " + blue.string()))
      << r.out;  // the reload after the failed open reads blue.json again
  std::vector<Rgba8Image> images;
  for (const fs::path& shot : shots) {
    images.push_back(readPng(shot));
    EXPECT_EQ(images.back().width, 160) << shot;  // the window's size, not the file's 200×100
    EXPECT_EQ(images.back().height, 120) << shot;
  }
  const auto balance = [](const Rgba8Image& image, int a, int b) {
    long sum = 0;
    for (std::size_t i = 0; i < image.pixels.size(); i += 4)
      sum += long(image.pixels[i + a]) - long(image.pixels[i + b]);
    return sum;
  };
  // The red bunny through both failures; the edit after them (a new style: a new renderer)
  // applies.
  EXPECT_EQ(images[1].pixels, images[0].pixels);
  EXPECT_EQ(images[2].pixels, images[0].pixels);
  EXPECT_NE(images[3].pixels, images[0].pixels);
  EXPECT_GT(balance(images[0], 0, 2), 0);
  // The blue bunny, orbited; the reload keeps that view, opening again takes the file's.
  EXPECT_LT(balance(images[4], 0, 2), 0);
  EXPECT_EQ(images[5].pixels, images[4].pixels);
  EXPECT_NE(images[6].pixels, images[4].pixels);
  EXPECT_EQ(images[7].pixels, images[6].pixels);
  EXPECT_EQ(images[8].pixels, images[6].pixels);
}

// Issue 18's interactive resolution: while the view moves (the script's `moving on` stands
// for a mouse drag) and a full frame misses --interactive-fps, the window shows the view
// rendered at 1/d of its size without multisampling, stretched bilinearly; once the view
// rests, the frame at full size. With --interactive-fps 0 every frame is at full size.
namespace {

constexpr int kMovingWidth = 480, kMovingHeight = 360;

// A viewer session on `example` that moves the view, saves it and takes the window's picture
// moving and at rest (moving-TAG.png, rest-TAG.png), under a goal of `fps`.
Result movingSession(const std::string& example, const std::string& tag, const std::string& fps) {
  const fs::path script = scratch("moving-" + tag + ".txt");
  std::ofstream(script) << "moving on\norbit 30 10\nsave " << scratch("moving.json").string()
                        << "\nscreenshot-window " << scratch("moving-" + tag + ".png").string()
                        << "\nmoving off\nscreenshot-window "
                        << scratch("rest-" + tag + ".png").string() << "\nquit\n";
  return runUnderXvfb(kSource + "/examples/" + example + " --no-panels --size " +
                      std::to_string(kMovingWidth) + "x" + std::to_string(kMovingHeight) +
                      " --interactive-fps " + fps + " --script " + script.string());
}

// Checks that session's moving picture against `cutaway render --simplify` of the saved view
// at w×h and one sample (`settings(w, h)` adding what else the moving frame changes), and its
// resting one against the full render; returns the CLI, the full render's file.
std::pair<std::string, fs::path> expectMovingThenFullFrames(
    const Result& r, const std::function<std::string(int, int)>& settings) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(
      r.out, m, std::regex(R"(while the view moves: (\d+)x(\d+) \(1/(\d) of 480x360\))")))
      << r.out;
  if (m.empty()) return {};
  // ⌈√(full frame / 1 ms)⌉ within [2, 8]: 8 on llvmpipe, where the full frame takes > 49 ms.
  const int d = std::stoi(m[3]), w = std::stoi(m[1]), h = std::stoi(m[2]);
  EXPECT_GE(d, 2) << r.out;
  EXPECT_LE(d, 8) << r.out;
  EXPECT_EQ(w, kMovingWidth / d);
  EXPECT_EQ(h, kMovingHeight / d);

  // The meshes' simplified versions within the pixel error of that size, stretched with
  // bilinear filtering (texel centres at (i + ½)·d); GL's filter weights round, by a level at
  // most when this was written.
  const std::string cli = cliLike(r);
  const fs::path small = scratch("moving-small.png");
  const Result rendered = run(
      cli + " render " + scratch("moving.json").string() + " --size " + std::to_string(w) + "x" +
      std::to_string(h) + " --samples 1 --simplify " + settings(w, h) + " -o " + small.string());
  EXPECT_EQ(rendered.exitCode, 0) << rendered.err;
  if (rendered.exitCode != 0) return {};
  const Rgba8Image ref = readPng(small), moving = readPng(scratch("moving-reduced.png"));
  EXPECT_EQ(moving.width, kMovingWidth);
  EXPECT_EQ(moving.height, kMovingHeight);
  if (moving.width != kMovingWidth || moving.height != kMovingHeight) return {};
  double sum = 0;
  int worst = 0;
  for (int y = 0; y < kMovingHeight; ++y)
    for (int x = 0; x < kMovingWidth; ++x) {
      const float u = (x + 0.5f) * w / kMovingWidth - 0.5f,
                  v = (y + 0.5f) * h / kMovingHeight - 0.5f;
      const int x0 = int(std::floor(u)), y0 = int(std::floor(v));
      const float fx = u - x0, fy = v - y0;
      const auto texel = [&](int i, int j, int c) {
        return float(ref.at(std::clamp(i, 0, w - 1), std::clamp(j, 0, h - 1))[c]);
      };
      for (int c = 0; c < 3; ++c) {
        const float expected =
            (1 - fy) * ((1 - fx) * texel(x0, y0, c) + fx * texel(x0 + 1, y0, c)) +
            fy * ((1 - fx) * texel(x0, y0 + 1, c) + fx * texel(x0 + 1, y0 + 1, c));
        const int diff = int(std::lround(std::abs(expected - moving.at(x, y)[c])));
        sum += diff;
        worst = std::max(worst, diff);
      }
    }
  const double mean = sum / (3.0 * kMovingWidth * kMovingHeight);
  std::printf("moving frame vs the %dx%d render stretched: mean %.3f, worst %d (of 255)\n", w, h,
              mean, worst);
  EXPECT_LE(mean, 0.1);
  EXPECT_LE(worst, 2);

  // At rest: the full-size frame, which the reduced one is not.
  const Rgba8Image rest = readPng(scratch("rest-reduced.png"));
  const fs::path full = scratch("rest-reference.png");
  EXPECT_EQ(run(cli + " render " + scratch("moving.json").string() + " --size 480x360 -o " +
                full.string())
                .exitCode,
            0);
  expectSameImage(rest, readPng(full));
  EXPECT_NE(moving.pixels, rest.pixels);
  return {cli, full};
}

}  // namespace

TEST(Viewer, WhileTheViewMovesAFrameTooSlowIsDrawnSmallerThenAtFullSize) {
  ASSERT_TRUE(hasXvfbRun()) << kNoXvfb;
  // A goal of 1 ms: no frame meets it, so the moving frame is drawn smaller.
  const Result r = movingSession("engine.json", "reduced", "1000");
  ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
  const auto [cli, full] = expectMovingThenFullFrames(r, [](int, int) { return ""; });
  ASSERT_FALSE(cli.empty());

  // Off: the moving frame is the full one.
  const Result off = movingSession("engine.json", "full", "0");
  ASSERT_EQ(off.exitCode, 0) << off.out << off.err;
  EXPECT_EQ(off.out.find("while the view moves"), std::string::npos) << off.out;
  expectSameImage(readPng(scratch("moving-full.png")), readPng(full));
}

// A moving adaptive cutaway also takes its buffer no finer than the smaller image, and its
// open meshes' cut surfaces unmarked (house-moving-bunny's walls and floors are open meshes).
TEST(Viewer, AMovingCutawayTakesASmallerBufferAndUnmarkedCutSurfaces) {
  ASSERT_TRUE(hasXvfbRun()) << kNoXvfb;
  const Result r = movingSession("house-moving-bunny.json", "reduced", "1000");
  ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
  expectMovingThenFullFrames(r, [](int w, int h) {
    return "--set cutters.adaptive.cutSurfaces=unmarked --set cutters.adaptive.bufferSize=" +
           std::to_string(std::bit_ceil(unsigned(std::max(w, h))));
  });
}
