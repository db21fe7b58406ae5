// The viewer's parts that need no window: the script parser, the parameter tables, the
// camera moves and scene saving (apps/cutaway-view).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>

#include "camera_controller.hpp"
#include "colormap.hpp"
#include "cutaway/core/error.hpp"
#include "cutaway/cutters/adaptive.hpp"
#include "cutaway/cutters/breakaway.hpp"
#include "cutaway/cutters/clip_surfaces.hpp"
#include "cutaway/cutters/cutout.hpp"
#include "cutaway/render/techniques.hpp"
#include "cutaway/scene/scene_writer.hpp"
#include "parameters.hpp"
#include "run_command.hpp"
#include "script.hpp"
#include "transfer_edit.hpp"
#include "viewer_state.hpp"

namespace fs = std::filesystem;
using namespace cutaway;
using namespace cutaway::view;

namespace {

const std::string kData = CUTAWAY_TEST_DATA;

fs::path scratch(const std::string& name) {
  return test::scratchPath("view-core", name);
}

// The scene as the viewer holds it after loading: its camera resolved, fit off.
Scene viewerCopy(const Scene& original) {
  Scene current = original;
  current.camera = original.resolvedCamera();
  current.camera.fit = false;
  return current;
}

std::string scriptError(const std::string& text) {
  try {
    parseScript(text, "s.txt");
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(ViewerScript, ParsesEveryCommand) {
  const Script s = parseScript(R"(# a session
wait 3
orbit 30 -10
look 5 2
pan 0.1 -0.2
zoom 1.5
fly 0 0 2.5
projection orthographic
frame

select connecting rods
deselect
pick 10 20
role interest
importance 0.75
angle 40
angle off
set cutters.adaptive.angle 30
set style.name blinn-phong
set style.lines.color 0.1,0.2,0.3
aov cutawayDepth turbo
aov off
probe 1 2
time 1.5
key 2
clear-path
screenshot out dir/view #1.png
screenshot-window w.png
save saved.json
save-aovs aovs
panels off
moving on
quit
)",
                               "s.txt");
  ASSERT_EQ(s.commands.size(), 31u);
  using Kind = ScriptCommand::Kind;
  EXPECT_EQ(s.commands[0].kind, Kind::Wait);
  EXPECT_EQ(s.commands[0].line, 2);
  EXPECT_EQ(s.commands[1].numbers, (std::vector<float>{30, -10}));
  EXPECT_EQ(s.commands[6].text, "orthographic");
  EXPECT_EQ(s.commands[8].kind, Kind::Select);
  EXPECT_EQ(s.commands[8].line, 11);                 // the blank line counts
  EXPECT_EQ(s.commands[8].text, "connecting rods");  // names may hold spaces
  EXPECT_EQ(s.commands[13].numbers, (std::vector<float>{40}));
  EXPECT_EQ(s.commands[14].text, "off");
  EXPECT_EQ(s.commands[15].parameter, findParameter("cutters.adaptive.angle"));
  EXPECT_EQ(std::get<double>(s.commands[15].value), 30.0);
  EXPECT_EQ(std::get<std::string>(s.commands[16].value), "blinn-phong");
  EXPECT_EQ(std::get<glm::vec3>(s.commands[17].value), glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(s.commands[18].text, "cutawayDepth");
  EXPECT_EQ(s.commands[18].colormap, "turbo");
  EXPECT_EQ(s.commands[24].text, "out dir/view #1.png");  // paths keep spaces and '#'
  EXPECT_FALSE(s.commands[28].on);
  EXPECT_EQ(s.commands[29].kind, Kind::Moving);
  EXPECT_TRUE(s.commands[29].on);
  EXPECT_EQ(s.commands[30].kind, Kind::Quit);
}

struct BadLine {
  const char* name;
  std::string script;
  std::string error;
};

class ViewerScriptErrors : public testing::TestWithParam<BadLine> {};

TEST_P(ViewerScriptErrors, NameFileLineAndReason) {
  EXPECT_EQ(scriptError(GetParam().script), GetParam().error);
}

INSTANTIATE_TEST_SUITE_P(
    BadLines, ViewerScriptErrors,
    testing::Values(
        BadLine{"UnknownCommand", "wait 1\norbt 30 10\n",
                "s.txt: line 2: unknown command \"orbt\""},
        BadLine{"TooFewNumbers", "orbit 30\n",
                "s.txt: line 1: \"orbit\" takes 2 numbers, got 1 argument"},
        BadLine{"NotANumber", "zoom fast\n", "s.txt: line 1: expected a number, got \"fast\""},
        BadLine{"ZoomNotPositive", "zoom 0\n", "s.txt: line 1: zoom factor must be greater than 0"},
        BadLine{"ScreenshotJpeg", "screenshot out.jpg\n",
                "s.txt: line 1: screenshot writes PNG only: give the file a .png name"},
        BadLine{"BeyondFloat", "orbit 1e300 0\n",
                "s.txt: line 1: \"1e300\" lies beyond a 32-bit float's range"},
        BadLine{"BelowFloat", "zoom 1e-300\n",
                "s.txt: line 1: \"1e-300\" lies beyond a 32-bit float's range"},
        BadLine{"FractionalWait", "wait 1.5\n",
                "s.txt: line 1: wait takes a whole number of frames in [0, 100000]"},
        BadLine{"ImportanceRange", "\n\nimportance 2\n",
                "s.txt: line 3: importance must lie in [0, 1]"},
        BadLine{"UnknownRole", "role focus\n",
                "s.txt: line 1: unknown role \"focus\" (expected one of: context, interest, "
                "exterior, interior)"},
        BadLine{"AngleRange", "angle 120\n",
                "s.txt: line 1: cutaway angle must lie in [0, 90] degrees"},
        BadLine{"SetValueRange", "set cutters.adaptive.angle 95\n",
                "s.txt: line 1: cutters.adaptive.angle: value 95 is outside [0, 90]"},
        BadLine{"SetIntegerParameter", "set cutters.adaptive.bufferSize 100.5\n",
                "s.txt: line 1: cutters.adaptive.bufferSize: expected an integer, got 100.5"},
        BadLine{"SetBool", "set cutters.adaptive.outlines maybe\n",
                "s.txt: line 1: cutters.adaptive.outlines: expected true/false or on/off, got "
                "\"maybe\""},
        BadLine{"SetChoice", "set cutters.adaptive.compute gpu2\n",
                "s.txt: line 1: cutters.adaptive.compute: unknown value \"gpu2\" (expected one of: "
                "auto, "
                "gpu, cpu)"},
        BadLine{"SetColour", "set style.lines.color 1,2,0\n",
                "s.txt: line 1: style.lines.color: colour channels must lie in [0, 1], got "
                "\"1,2,0\""},
        BadLine{"SetMissingValue", "set cutters.adaptive.angle\n",
                "s.txt: line 1: \"set\" takes a parameter key and a value, got 1 argument"},
        BadLine{"Projection", "projection fisheye\n",
                "s.txt: line 1: projection must be perspective or orthographic, got \"fisheye\""},
        BadLine{"Colormap", "aov depth jet\n",
                "s.txt: line 1: unknown colormap \"jet\" (expected one of: auto, gray, turbo, rgb, "
                "normals, ids)"},
        BadLine{"SelectWithoutName", "select\n", "s.txt: line 1: \"select\" needs an argument"},
        BadLine{"QuitWithArgument", "quit now\n",
                "s.txt: line 1: \"quit\" takes no arguments, got 1 argument"},
        BadLine{"NegativePixel", "pick -1 3\n", "s.txt: line 1: pixel coordinates must be ≥ 0"},
        BadLine{"Panels", "panels maybe\n", "s.txt: line 1: panels takes on or off, got \"maybe\""},
        BadLine{"Moving", "moving 1\n", "s.txt: line 1: moving takes on or off, got \"1\""},
        // User text is quoted up to 60 characters: a 100 KB word does not fill the terminal.
        BadLine{"LongCommand", std::string(100000, 'x') + "\n",
                "s.txt: line 1: unknown command \"" + std::string(60, 'x') + "…\""},
        BadLine{"LongRole", "role " + std::string(100000, 'r') + "\n",
                "s.txt: line 1: unknown role \"" + std::string(60, 'r') +
                    "…\" (expected one of: context, interest, exterior, interior)"}),
    [](const testing::TestParamInfo<BadLine>& info) { return std::string(info.param.name); });

// A NUL byte would cut the rest of its line from the messages.
TEST(ViewerScript, ANulByteIsNamedWhereItIs) {
  EXPECT_EQ(scriptError(std::string("wait 1\nzoom 1\0 2\n", 16)),
            "s.txt: line 2, column 7: a NUL byte: a script is text");
}

TEST(ViewerScript, UnknownParameterListsTheKnownOnes) {
  const std::string e = scriptError("set cutters.adaptive.anlge 30\n");
  EXPECT_EQ(e.rfind("s.txt: line 1: unknown parameter \"cutters.adaptive.anlge\" (known: cutters.adaptive, "
                    "cutters.adaptive.angle,",
                    0),
            0u)
      << e;
}

TEST(ViewerScript, MissingFileIsAnError) {
  try {
    loadScript("/nonexistent/script.txt");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/script.txt: cannot open script file");
  }
}

TEST(ViewerParameters, EveryParameterReadsBackWhatWasSet) {
  Scene scene;
  // Clip surfaces come from the scene file; the viewer edits those there are.
  const ClipSurfaceOptions clip{.surfaces = std::vector<ClipSurface>(kMaxClipSurfaces)};
  scene.cutters.enable<ClipSurfaceOptions>() = clip;
  scene.networks.resize(2);  // likewise the pipe networks and the volumes
  scene.volumes.resize(2);
  for (SceneVolume& v : scene.volumes)  // with as many isovalues and planes as there can be
    v.lines = VolumeLineStyle{.isoValues = std::vector<VolumeLineIso>(8),
                              .planes = std::vector<VolumeLinePlane>(4)};
  for (const auto& group : parameterGroups())
    for (const auto& p : group.parameters) {
      SCOPED_TRACE(p.key);
      ASSERT_TRUE(p.get && p.set);
      // A slider spans part of the accepted range.
      if (p.sliderMax) EXPECT_TRUE(*p.sliderMax > p.min && *p.sliderMax <= p.max);
      ParameterValue v;
      switch (p.type) {
        case OptionSpec::Type::Bool:
          v = !std::get<bool>(p.value(scene));
          break;
        case OptionSpec::Type::Int:
        case OptionSpec::Type::Float:
          v = p.type == OptionSpec::Type::Int ? std::round((p.min + std::min(p.max, 4096.0)) / 2)
                                             : (p.min + std::min(p.max, 100.0)) / 2;
          break;
        case OptionSpec::Type::Choice:
          v = p.choices.back();
          break;
        case OptionSpec::Type::Color:
          v = glm::vec3(0.25f, 0.5f, 0.75f);
          break;
        case OptionSpec::Type::Direction:
          v = glm::vec3(0.0f, 0.0f, 1.0f);
          break;
        case OptionSpec::Type::Vec3:
          v = glm::vec3(0.5f, -2.0f, 3.0f);
          break;
        case OptionSpec::Type::Text:
          v = std::string("x.*");
          break;
      }
      // Turning a feature off drops its options (cutters.*, style.lines): re-enable.
      for (const char* feature : {"cutters.adaptive", "cutters.cutout", "cutters.breakaway",
                                  "cutters.terrainOpening", "style.lines"})
        if (p.key != feature) findParameter(feature)->assign(scene, true);
      if (!scene.cutters.find<ClipSurfaceOptions>()) scene.cutters.set("clipSurfaces", clip);
      p.assign(scene, v);
      ParameterValue stored = v;  // numbers are held as floats
      if (double* d = std::get_if<double>(&stored)) *d = double(float(*d));
      EXPECT_EQ(formatOptionValue(p.value(scene)), formatOptionValue(stored));
      EXPECT_EQ(findParameter(p.key), &p);
    }
}

TEST(ViewerParameters, SettingACutterOptionAddsTheCutter) {
  Scene scene;
  ASSERT_FALSE(scene.cutters.find<AdaptiveCutawayOptions>());
  findParameter("cutters.adaptive.angle")->assign(scene, 20.0);
  ASSERT_TRUE(scene.cutters.find<AdaptiveCutawayOptions>());
  EXPECT_EQ(scene.cutters.find<AdaptiveCutawayOptions>()->angle, 20.0f);
  findParameter("cutters.adaptive")->assign(scene, false);
  EXPECT_FALSE(scene.cutters.find<AdaptiveCutawayOptions>());
}

// Konev18's run-time options: every network at once, the shafts' object colours with them,
// and a redraw instead of a new renderer.
TEST(ViewerParameters, NetworkOptionsApplyToEveryNetworkLive) {
  ViewerState state;
  state.scene = loadScene(fs::path(CUTAWAY_SOURCE_DIR) / "examples/pipes-street.json");
  state.scene.networks.push_back(state.scene.networks.front());
  const Parameter& radius = *findParameter("networks.radiusScale");
  setParameter(state, radius, 1.5);
  EXPECT_TRUE(state.viewChanged);
  EXPECT_FALSE(state.sceneChanged);
  for (const PipeNetwork& n : state.scene.networks) EXPECT_EQ(n.radiusScale, 1.5f);
  EXPECT_THROW(parseOptionValue(radius, "0"), std::invalid_argument);
  const glm::vec3 outside(0.1f, 0.2f, 0.3f), cut(0.7f, 0.6f, 0.5f);
  setParameter(state, *findParameter("networks.color"), outside);
  setParameter(state, *findParameter("networks.cutColor"), cut);
  int shafts = 0;
  for (const SceneObject& o : state.scene.objects) {
    if (o.networkPart == NetworkPart::None) {
      EXPECT_NE(o.material.color, outside);
      continue;
    }
    EXPECT_EQ(o.material.color, o.networkPart == NetworkPart::ShaftInner ? cut : outside);
    ++shafts;
  }
  EXPECT_EQ(shafts, 2);
  // A uniform of a cutter is live too; what a cutter builds from (its texture) rebuilds.
  state.viewChanged = false;
  setParameter(state, *findParameter("cutters.terrainOpening.w"), 0.02);
  EXPECT_TRUE(state.viewChanged);
  EXPECT_FALSE(state.sceneChanged);
  setParameter(state, *findParameter("cutters.terrainOpening.resolution"), 512.0);
  EXPECT_TRUE(state.sceneChanged);
}

TEST(ViewerParameters, StyleChoicesAreTheLibrarysStyles) {
  EXPECT_EQ(findParameter("style.name")->choices, styleNames());
}

namespace {

Camera testCamera() {
  Camera c;
  c.eye = {0, 0, 10};
  c.target = {0, 0, 0};
  c.fovY = 40;
  return c;
}

}  // namespace

TEST(ViewerCamera, OrbitKeepsTheTargetAndTheDistance) {
  Camera c = testCamera();
  orbit(c, 90.0f, 0.0f);
  EXPECT_EQ(c.target, glm::vec3(0.0f));
  // A positive yaw carries the eye to the view's right (+x seen from +z).
  EXPECT_NEAR(c.eye.x, 10.0f, 1e-4f);
  EXPECT_NEAR(c.eye.z, 0.0f, 1e-4f);
  orbit(c, 0.0f, 30.0f);
  EXPECT_NEAR(glm::length(c.eye), 10.0f, 1e-4f);
  EXPECT_NEAR(c.eye.y, 10.0f * std::sin(glm::radians(30.0f)), 1e-4f);  // raised by 30°
}

TEST(ViewerCamera, OrbitStopsShortOfThePole) {
  Camera c = testCamera();
  orbit(c, 0.0f, 120.0f);
  const float polar = glm::degrees(std::acos(glm::dot(glm::normalize(c.eye), c.up)));
  EXPECT_NEAR(polar, kMinPolarDegrees, 1e-3f);
  EXPECT_GT(glm::length(glm::cross(glm::normalize(c.eye - c.target), c.up)), 1e-3f);
}

TEST(ViewerCamera, LookTurnsTheGazeAboutTheEye) {
  Camera c = testCamera();
  look(c, 90.0f, 0.0f);
  EXPECT_EQ(c.eye, glm::vec3(0, 0, 10));
  EXPECT_NEAR(c.target.x, 10.0f, 1e-4f);  // looking right, towards +x
  EXPECT_NEAR(c.target.z, 10.0f, 1e-4f);
}

TEST(ViewerCamera, PanMovesByViewHeights) {
  Camera c = testCamera();
  const float h = c.viewHeightAtTarget();
  EXPECT_NEAR(h, 2.0f * 10.0f * std::tan(glm::radians(20.0f)), 1e-5f);
  pan(c, 0.5f, 0.25f);
  EXPECT_NEAR(c.target.x, 0.5f * h, 1e-5f);
  EXPECT_NEAR(c.target.y, 0.25f * h, 1e-5f);
  EXPECT_NEAR(c.eye.z, 10.0f, 1e-5f);
}

TEST(ViewerCamera, ZoomAndFly) {
  Camera c = testCamera();
  zoom(c, 2.0f);
  EXPECT_NEAR(c.eye.z, 5.0f, 1e-5f);
  fly(c, glm::vec3(1.0f, 2.0f, 3.0f));  // right, up, forward
  EXPECT_NEAR(c.eye.x, 1.0f, 1e-5f);
  EXPECT_NEAR(c.eye.y, 2.0f, 1e-5f);
  EXPECT_NEAR(c.eye.z, 2.0f, 1e-5f);
  EXPECT_NEAR(c.target.z, -3.0f, 1e-5f);
}

TEST(ViewerCamera, ProjectionSwitchKeepsTheSizeAtTheTarget) {
  Camera c = testCamera();
  const float before = c.viewHeightAtTarget();
  c.setProjection(Projection::Orthographic);
  EXPECT_NEAR(c.height, before, 1e-5f);
  c.height *= 0.5f;
  c.setProjection(Projection::Perspective);
  EXPECT_NEAR(c.viewHeightAtTarget(), before * 0.5f, 1e-4f);
  EXPECT_NEAR(glm::length(c.eye - c.target), 5.0f, 1e-4f);
}

TEST(ViewerCamera, FrameBoundsFitsTheBoundingSphere) {
  Camera c = testCamera();
  Bounds b;
  b.extend(glm::vec3(4, 4, 4));
  b.extend(glm::vec3(6, 8, 5));
  const float aspect = 0.5f;  // portrait: the horizontal half-angle is the narrower
  frameBounds(c, b, aspect);
  EXPECT_EQ(c.target, b.center());
  const float tanX = std::tan(glm::radians(c.fovY) * 0.5f) * aspect;
  const float distance = glm::length(c.eye - c.target);
  // The sphere's angular radius equals the narrower half-angle (with the 5% margin).
  EXPECT_NEAR(std::asin(b.radius() * 1.05f / distance), std::atan(tanX), 1e-4f);
  EXPECT_NEAR(glm::normalize(c.eye - c.target).z, 1.0f, 1e-5f);  // direction kept
}

TEST(ViewerColormap, TurboEndsAndIds) {
  // Turbo runs from dark blue through green to dark red.
  const glm::vec3 low = turbo(0.15f), middle = turbo(0.5f), high = turbo(1.0f);
  EXPECT_LT(glm::length(turbo(0.0f)), 0.3f);
  EXPECT_GT(low.b, std::max(low.r, low.g));
  EXPECT_GT(middle.g, std::max(middle.r, middle.b));
  EXPECT_GT(high.r, 4.0f * std::max(high.g, high.b));
  EXPECT_LT(high.r, 0.7f);
  EXPECT_EQ(idColor(-1), glm::vec3(0.0f));
  EXPECT_NE(idColor(1), idColor(2));
  FloatImage ids(2, 1, 1);
  ids.data = {-1.0f, 3.0f};
  const Rgba8Image shown = applyColormap(ids, Colormap::Ids, finiteRange(ids, 0));
  EXPECT_EQ(shown.at(0, 0)[0], 0);
  EXPECT_EQ(shown.at(1, 0)[3], 255);
  FloatImage depth(3, 1, 1);
  depth.data = {0.0f, 4.0f, 9.0f};  // a background texel, then two objects
  EXPECT_EQ(finiteRange(depth, 0).min, 0.0f);
  EXPECT_EQ(finiteRange(depth, 0, {0, 1, 1}).min, 4.0f);
  EXPECT_EQ(finiteRange(depth, 0, {0, 1, 1}).max, 9.0f);
  EXPECT_EQ(resolveColormap(Colormap::Auto, "normal", 3), Colormap::Normals);
  EXPECT_EQ(resolveColormap(Colormap::Auto, "cutawayDepth", 1), Colormap::Turbo);
}

TEST(ViewerSelection, ObjectsByNameThenByGroup) {
  Scene scene;
  scene.objects.resize(3);
  scene.objects[0].name = "a", scene.objects[0].group = "g";
  scene.objects[1].name = "g", scene.objects[1].group = "";
  scene.objects[2].name = "c", scene.objects[2].group = "h";
  EXPECT_EQ(objectsNamed(scene, "a"), (std::vector<std::size_t>{0}));
  EXPECT_EQ(objectsNamed(scene, "g"), (std::vector<std::size_t>{1}));  // a name wins
  EXPECT_EQ(objectsNamed(scene, "h"), (std::vector<std::size_t>{2}));
  EXPECT_TRUE(objectsNamed(scene, "x").empty());
  EXPECT_EQ(groupsOf(scene), (std::vector<std::string>{"g", "", "h"}));
}

TEST(ViewerSelection, CameraKeysMustIncrease) {
  ViewerState state;
  addCameraKey(state, 1.0f);
  EXPECT_THROW(addCameraKey(state, 1.0f), Error);
  addCameraKey(state, 2.0f);
  EXPECT_EQ(state.cameraPath.size(), 2u);
}

TEST(ViewerSelection, PathPreviewInterpolatesTheRecordedKeys) {
  ViewerState state;
  state.scene.objects.resize(1);
  state.scene.objects[0].mesh = std::make_shared<Mesh>(makeBox({-1, -1, -1}, {1, 1, 1}));
  state.scene.camera.eye = {0, 0, 10};
  addCameraKey(state, 0.0f);
  state.scene.camera.eye = {0, 0, 20};
  addCameraKey(state, 2.0f);
  state.scene.camera.eye = {5, 0, 5};  // the interactive camera, elsewhere
  state.time = 0.5f;
  EXPECT_EQ(viewCamera(state).eye, glm::vec3(5, 0, 5));  // not previewing
  state.previewPath = true;
  EXPECT_NEAR(viewCamera(state).eye.z, 12.5f, 1e-5f);
  EXPECT_GT(viewCamera(state).near, 0.0f);  // resolved: near and far derived
}

// A scene with an object split into nodes (two_parts.obj), a whole-file object and a proxy.
constexpr const char* kSavedScene = R"({
  "resolution": [64, 48],
  "style": "gooch",
  "objects": [
    {"name": "parts", "file": "MESHES/two_parts.obj", "split": "nodes",
     "overrides": [{"match": ".*", "group": "all parts", "color": [0.2, 0.4, 0.6]}]},
    {"name": "cube", "file": "MESHES/cube.obj", "role": "interest", "params": {"cutawayAngle": 20}}
  ],
  "proxies": [{"name": "box", "box": {"min": [-1, -1, -1], "max": [1, 1, 1]}}],
  "cutters": {"adaptive": {"angle": 35}}
})";

TEST(ViewerSave, PatchedSceneReloadsWithTheViewersChanges) {
  std::string text = kSavedScene;
  const std::string meshes = kData + "/meshes";
  for (std::size_t at; (at = text.find("MESHES")) != std::string::npos;)
    text.replace(at, 6, meshes);
  const fs::path source = scratch("source.json");
  std::ofstream(source) << text;
  const Scene original = loadScene(source);
  ASSERT_EQ(original.objects.size(), 4u);  // two nodes, the cube, the proxy

  ViewerState state;
  state.scene = original;
  state.scene.objects[1].role = Role::Interest;  // a node: an override of its own
  state.scene.objects[1].importance = 0.9f;
  state.scene.objects[1].params["cutawayAngle"] = 12.5;
  state.scene.objects[2].params.erase("cutawayAngle");  // the entry's own parameter goes
  state.scene.objects[2].importance = 0.3f;
  state.scene.objects[3].importance = 0.7f;  // the proxy
  findParameter("cutters.adaptive.angle")->assign(state.scene, 50.0);
  findParameter("cutters.adaptive.ghostLines")->assign(state.scene, true);
  findParameter("style.lines.width")->assign(state.scene, 2.0);
  state.scene.camera.fit = false;
  state.scene.camera.eye = {1.5f, 2.25f, 7.1f};
  state.scene.camera.target = {0.1f, 0.2f, 0.3f};
  state.scene.camera.projection = Projection::Orthographic;
  state.scene.camera.height = 3.3f;
  state.scene.camera.path = {{0.0f, {1, 2, 7}, {0, 0, 0}}, {2.0f, {-1, 2, 7}, {0, 0, 0}}};
  state.scene.width = 80;

  const fs::path target = scratch("saved.json");
  const SceneDocument document = SceneDocument::load(source);
  document.save(original, state.scene, target);
  const Scene saved = loadScene(target);
  ASSERT_EQ(saved.objects.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    SCOPED_TRACE(saved.objects[i].name);
    EXPECT_EQ(saved.objects[i].name, state.scene.objects[i].name);
    EXPECT_EQ(saved.objects[i].role, state.scene.objects[i].role);
    EXPECT_EQ(saved.objects[i].importance, state.scene.objects[i].importance);
    EXPECT_EQ(saved.objects[i].params, state.scene.objects[i].params);
    EXPECT_EQ(saved.objects[i].material.color, original.objects[i].material.color);
    EXPECT_EQ(saved.objects[i].group, original.objects[i].group);
  }
  EXPECT_EQ(saved.cutters.find<AdaptiveCutawayOptions>()->angle, 50.0f);
  EXPECT_TRUE(saved.cutters.find<AdaptiveCutawayOptions>()->ghostLines);
  EXPECT_EQ(saved.style.lines->width, 2.0f);
  EXPECT_EQ(saved.camera.eye, state.scene.camera.eye);  // bit for bit
  EXPECT_EQ(saved.camera.target, state.scene.camera.target);
  EXPECT_EQ(saved.camera.height, 3.3f);
  EXPECT_EQ(saved.camera.projection, Projection::Orthographic);
  EXPECT_EQ(saved.camera.path.size(), 2u);
  EXPECT_EQ(saved.width, 80);
  EXPECT_EQ(saved.height, 48);

  // The untouched node has no override of its own; the touched one has exactly one, last.
  std::ifstream in(target);
  const auto json = nlohmann::ordered_json::parse(in);
  const auto& overrides = json["objects"][0]["overrides"];
  ASSERT_EQ(overrides.size(), 2u);
  EXPECT_EQ(overrides[0]["match"], ".*");
  EXPECT_EQ(overrides[1]["match"], escapeRegex(state.scene.objects[1].name.substr(6)));
  EXPECT_FALSE(json["objects"][1].contains("params"));
  EXPECT_EQ(json.begin().key(), "resolution");  // the author's key order is kept

  // Saving again from the saved file does not pile up overrides.
  const SceneDocument again = SceneDocument::load(target);
  ViewerState second;
  second.scene = saved;
  second.scene.objects[1].importance = 0.1f;
  again.save(saved, second.scene, target);
  std::ifstream in2(target);
  EXPECT_EQ(nlohmann::ordered_json::parse(in2)["objects"][0]["overrides"].size(), 2u);
  EXPECT_EQ(loadScene(target).objects[1].importance, 0.1f);
}

TEST(ViewerSave, RelativeMeshPathsFollowTheFileElsewhere) {
  const fs::path dir = scratch("relative");
  fs::create_directories(dir / "sub");
  fs::copy_file(kData + "/meshes/cube.obj", dir / "cube.obj", fs::copy_options::overwrite_existing);
  std::ofstream(dir / "scene.json") << R"({"objects": [{"name": "cube", "file": "cube.obj"}]})";
  const Scene original = loadScene(dir / "scene.json");
  Scene current = viewerCopy(original);
  SceneDocument::load(dir / "scene.json").save(original, current, dir / "sub" / "saved.json");
  EXPECT_EQ(loadScene(dir / "sub" / "saved.json").objects.size(), 1u);
  // Same folder: the path stays relative.
  SceneDocument::load(dir / "scene.json").save(original, current, dir / "same.json");
  std::ifstream in(dir / "same.json");
  EXPECT_EQ(nlohmann::json::parse(in)["objects"][0]["file"], "cube.obj");
  // A folder as the target is named as one (its relative paths once made it "mesh file not
  // found").
  try {
    SceneDocument::load(dir / "scene.json").save(original, current, dir / "sub");
    ADD_FAILURE() << "a folder was taken";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "sub").string() + ": is a directory, not a file");
  }
}

TEST(ViewerSave, EscapedNamesMatchThemselvesOnly) {
  EXPECT_EQ(escapeRegex("nodes[2]"), "nodes\\[2\\]");
  EXPECT_EQ(escapeRegex("a.b*c(d)|e"), "a\\.b\\*c\\(d\\)\\|e");
}

// The networks' edited options saved into their entries; the pipes stay as written.
TEST(ViewerSave, NetworkOptionsReadBack) {
  const fs::path examples = fs::path(CUTAWAY_SOURCE_DIR) / "examples";
  const Scene original = loadScene(examples / "pipes-street.json");
  Scene current = viewerCopy(original);
  findParameter("networks.radiusScale")->assign(current, 2.0);
  findParameter("networks.shaftOpening")->assign(current, -0.25);
  findParameter("networks.waterHigh")->assign(current, glm::vec3(0.0f, 0.1f, 0.4f));
  const fs::path target = scratch("pipes-street.json");
  SceneDocument::load(examples / "pipes-street.json").save(original, current, target);
  const Scene saved = loadScene(target);
  ASSERT_EQ(saved.networks.size(), 1u);
  EXPECT_EQ(saved.networks[0].radiusScale, 2.0f);
  EXPECT_EQ(saved.networks[0].shaftOpening, -0.25f);
  EXPECT_EQ(saved.networks[0].waterHigh, glm::vec3(0.0f, 0.1f, 0.4f));
  EXPECT_EQ(saved.networks[0].waterLow, original.networks[0].waterLow);
  EXPECT_EQ(saved.networks[0].pipes.size(), original.networks[0].pipes.size());
}

// The volumes' edited options saved into their entries; the files and the transfer functions
// left alone stay as written.
TEST(ViewerSave, VolumeOptionsReadBack) {
  const fs::path examples = fs::path(CUTAWAY_SOURCE_DIR) / "examples";
  const Scene original = loadScene(examples / "mri-head-box-cut.json");
  Scene current = viewerCopy(original);
  findParameter("volumes.sampleDistance")->assign(current, 0.25);
  findParameter("volumes.mode")->assign(current, std::string("maximum"));
  findParameter("volumes.shading")->assign(current, false);
  const fs::path target = scratch("mri-head-box-cut.json");
  SceneDocument::load(examples / "mri-head-box-cut.json").save(original, current, target);
  const Scene saved = loadScene(target);
  ASSERT_EQ(saved.volumes.size(), 1u);
  EXPECT_EQ(saved.volumes[0].sampleDistance, 0.25f);
  EXPECT_EQ(saved.volumes[0].mode, VolumeMode::Maximum);
  EXPECT_FALSE(saved.volumes[0].shading);
  EXPECT_EQ(saved.volumes[0].opacityDistance, original.volumes[0].opacityDistance);
  EXPECT_EQ(saved.volumes[0].transfer.rows.front().points.size(),
            original.volumes[0].transfer.rows.front().points.size());
  EXPECT_EQ(saved.volumes[0].source, original.volumes[0].source);
}

// A volume's lines edited in the viewer are saved under its "lines" and read back.
TEST(ViewerSave, VolumeLinesReadBack) {
  const fs::path examples = fs::path(CUTAWAY_SOURCE_DIR) / "examples";
  const Scene original = loadScene(examples / "mri-head-lines.json");
  Scene current = viewerCopy(original);
  findParameter("volumes.lines.isoValues.1.value")->assign(current, 80.0);
  findParameter("volumes.lines.suggestive")->assign(current, true);
  findParameter("volumes.lines.hidden")->assign(current, std::string("dimmed"));
  findParameter("volumes.lines.planes.0.distance")->assign(current, -10.0);
  const fs::path target = scratch("mri-head-lines.json");
  SceneDocument::load(examples / "mri-head-lines.json").save(original, current, target);
  const Scene saved = loadScene(target);
  ASSERT_EQ(saved.volumes.size(), 1u);
  ASSERT_TRUE(saved.volumes[0].lines);
  EXPECT_EQ(*saved.volumes[0].lines, *current.volumes[0].lines);
  EXPECT_EQ(saved.volumes[0].lines->isoValues[1].value, 80.0f);
  EXPECT_EQ(saved.volumes[0].lines->hidden, HiddenLines::Dimmed);
  EXPECT_EQ(saved.volumes[0].lines->planes[0].distance, -10.0f);
}

// The transfer-function editor's edits keep the scene file's rules.
TEST(ViewerTransfer, EditsKeepValuesIncreasingAndRowsOrdered) {
  std::vector<TransferPoint> row{{0.0f, {0, 0, 0}, 0.0f, 0.0f}, {10.0f, {1, 1, 1}, 1.0f, 1.0f}};
  EXPECT_EQ(insertTransferPoint(row, 2.5f, 0.7f), 1);
  EXPECT_FLOAT_EQ(row[1].color.r, 0.25f);  // colour and importance as the row had them there
  EXPECT_FLOAT_EQ(row[1].importance, 0.25f);
  EXPECT_FLOAT_EQ(row[1].opacity, 0.7f);
  EXPECT_EQ(insertTransferPoint(row, 2.5f, 0.1f), -1);  // a point has that value already
  moveTransferPoint(row, 1, 50.0f, 2.0f);  // past its neighbour: just below it; opacity ≤ 1
  EXPECT_LT(row[1].value, 10.0f);
  EXPECT_GT(row[1].value, 9.99f);
  EXPECT_EQ(row[1].opacity, 1.0f);
  moveTransferPoint(row, 0, -3.0f, -1.0f);
  EXPECT_EQ(row[0].value, -3.0f);
  EXPECT_EQ(row[0].opacity, 0.0f);
  EXPECT_TRUE(removeTransferPoint(row, 1));
  EXPECT_TRUE(removeTransferPoint(row, 1));
  EXPECT_FALSE(removeTransferPoint(row, 0));  // the last point stays
  // Labels: whole values, one apart at least.
  std::vector<TransferPoint> labels{
      {1.0f, {1, 0, 0}, 1.0f, 1.0f}, {2.0f, {0, 1, 0}, 1.0f, 1.0f}, {5.0f, {0, 0, 1}, 1.0f, 1.0f}};
  moveTransferPoint(labels, 1, 3.4f, 1.0f, true);
  EXPECT_EQ(labels[1].value, 3.0f);
  moveTransferPoint(labels, 1, 9.0f, 1.0f, true);
  EXPECT_EQ(labels[1].value, 4.0f);
  EXPECT_EQ(insertTransferPoint(labels, 2.2f, 1.0f, true), 1);
  EXPECT_EQ(labels[1].value, 2.0f);
  // Rows: a one-dimensional function turns two-dimensional and back.
  TransferFunction tf{{{0.0f, {{0.0f, {1, 1, 1}, 0.5f, 0.5f}}}}};
  EXPECT_EQ(insertTransferRow(tf, 40.0f), 1);
  EXPECT_TRUE(tf.twoDimensional());
  EXPECT_EQ(tf.rows[1].points, tf.rows[0].points);
  EXPECT_EQ(insertTransferRow(tf, 40.0f), -1);
  setTransferRowGradient(tf, 0, 100.0f);
  EXPECT_LT(tf.rows[0].gradient, 40.0f);
  setTransferRowGradient(tf, 1, -5.0f);
  EXPECT_GT(tf.rows[1].gradient, tf.rows[0].gradient);
  EXPECT_TRUE(removeTransferRow(tf, 0));
  EXPECT_FALSE(removeTransferRow(tf, 0));
  EXPECT_FALSE(tf.twoDimensional());
}

// An edited transfer function is saved under its key and reads back; one turned
// two-dimensional replaces the one-dimensional key.
TEST(ViewerSave, EditedTransferFunctionsReadBack) {
  const fs::path examples = fs::path(CUTAWAY_SOURCE_DIR) / "examples";
  const Scene original = loadScene(examples / "mri-head-box-cut.json");
  Scene current = viewerCopy(original);
  std::vector<TransferPoint>& row = current.volumes[0].transfer.rows.front().points;
  insertTransferPoint(row, 0.5f * (row[0].value + row[1].value), 0.3f);
  row.back().color = {0.1f, 0.2f, 0.3f};
  const fs::path target = scratch("mri-head-tf.json");
  SceneDocument::load(examples / "mri-head-box-cut.json").save(original, current, target);
  EXPECT_EQ(loadScene(target).volumes[0].transfer, current.volumes[0].transfer);
  insertTransferRow(current.volumes[0].transfer, 25.0f);
  current.volumes[0].transfer.rows[1].points.front().opacity = 0.9f;
  SceneDocument::load(examples / "mri-head-box-cut.json").save(original, current, target);
  EXPECT_EQ(loadScene(target).volumes[0].transfer, current.volumes[0].transfer);
}

// The Diepstraten03 and Trapp13 cutters' parameters saved: each edited value reads back, the
// clip surface keeps its offset map, and a cutter switched off leaves the file.
TEST(ViewerSave, CutoutBreakawayAndClipSurfaceChangesReadBack) {
  const fs::path dir = scratch("cutters");
  fs::create_directories(dir);
  const std::string cube = kData + "/meshes/cube.obj", tetra = kData + "/meshes/tetra.obj";
  std::ofstream(dir / "scene.json") << R"({"objects": [
      {"name": "box", "file": ")" + cube + R"(", "role": "exterior"},
      {"name": "tetra", "file": ")" + tetra +
                                           R"(", "role": "interior",
       "transform": {"scale": [0.3, 0.3, 0.3], "translate": [0.3, 0.3, 0.3]}}],
    "cutters": {"cutout": {"angle": 80},
                "clipSurfaces": {"surfaces": [{"origin": [-1, -1, 0.5], "u": [3, 0, 0], "v": [0, 3, 0],
                                               "offsetMap": {"pattern": "ridged", "seed": 3}}]}}})";
  const Scene original = loadScene(dir / "scene.json");
  Scene current = viewerCopy(original);
  findParameter("cutters.cutout.angle")->assign(current, 120.0);
  findParameter("cutters.cutout.facingCamera")->assign(current, false);
  findParameter("cutters.cutout.rotation")->assign(current, 30.0);
  findParameter("cutters.cutout.jitter.pattern")->assign(current, std::string("sawtooth"));
  findParameter("cutters.cutout.jitter.amplitude")->assign(current, 0.05);
  findParameter("cutters.breakaway")->assign(current, true);
  findParameter("cutters.breakaway.offset")->assign(current, 0.2);
  findParameter("cutters.breakaway.wallColor")->assign(current, glm::vec3(0.1f, 0.2f, 0.3f));
  findParameter("cutters.clipSurfaces.surfaces.0.position")->assign(current, 0.25);
  findParameter("cutters.clipSurfaces.combine")->assign(current, std::string("intersection"));
  findParameter("cutters.clipSurfaces.surfaces.0.height")->assign(current, 0.125);
  SceneDocument::load(dir / "scene.json").save(original, current, dir / "saved.json");
  const Scene saved = loadScene(dir / "saved.json");
  ASSERT_TRUE(saved.cutters.find<CutoutOptions>() && saved.cutters.find<BreakawayOptions>() &&
              saved.cutters.find<ClipSurfaceOptions>());
  EXPECT_EQ(saved.cutters.find<CutoutOptions>()->angle, 120.0f);
  EXPECT_EQ(saved.cutters.find<CutoutOptions>()->rotation, 30.0f);
  EXPECT_EQ(saved.cutters.find<CutoutOptions>()->jitter.pattern, CutoutJitter::Pattern::Sawtooth);
  EXPECT_EQ(saved.cutters.find<CutoutOptions>()->jitter.amplitude, 0.05f);
  EXPECT_EQ(saved.cutters.find<BreakawayOptions>()->offset, 0.2f);
  EXPECT_EQ(*saved.cutters.find<BreakawayOptions>()->wallColor, glm::vec3(0.1f, 0.2f, 0.3f));
  const ClipSurface& cs = saved.cutters.find<ClipSurfaceOptions>()->surfaces[0];
  EXPECT_NEAR(glm::dot(cs.origin, cs.normal()), 0.25f, 1e-6f);
  EXPECT_EQ(cs.scale.z, 0.125f);
  EXPECT_EQ(saved.cutters.find<ClipSurfaceOptions>()->combine, ClipSurfaceOptions::Combine::Intersection);
  // The offset map is still the ridged recipe of the original file.
  EXPECT_EQ(cs.offsetMap.data, original.cutters.find<ClipSurfaceOptions>()->surfaces[0].offsetMap.data);

  findParameter("cutters.cutout")->assign(current, false);
  SceneDocument::load(dir / "scene.json").save(original, current, dir / "without.json");
  std::ifstream in(dir / "without.json");
  EXPECT_FALSE(nlohmann::json::parse(in)["cutters"].contains("cutout"));
}
