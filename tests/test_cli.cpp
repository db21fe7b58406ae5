// End-to-end tests of the `cutaway` program: each runs the real binary.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "cutaway/core/image.hpp"
#include "cutaway/io/raster_terrain.hpp"
#include "run_command.hpp"

namespace fs = std::filesystem;
using namespace cutaway;

namespace {

const std::string kBinary = CUTAWAY_BINARY;
const std::string kSource = CUTAWAY_SOURCE_DIR;
const std::string kData = CUTAWAY_TEST_DATA;

using test::Result;

// Runs `cutaway ARGS` capturing stdout and stderr separately.
Result run(const std::string& args) {
  return test::runCommand(kBinary + " " + args);
}

fs::path scratch(const std::string& name) {
  return test::scratchPath("cli", name);
}

int lines(const std::string& s) {
  return int(std::count(s.begin(), s.end(), '\n'));
}

}  // namespace

TEST(Cli, RenderWritesThePngAndSaysWhere) {
  const fs::path out = scratch("engine.png");
  const Result r =
      run("render " + kSource + "/examples/engine.json -o " + out.string() + " --size 160x120");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("wrote " + out.string()), std::string::npos) << r.out;
  const Rgba8Image image = readPng(out);
  EXPECT_EQ(image.width, 160);
  EXPECT_EQ(image.height, 120);
  // Not blank: the engine covers a good part of the picture.
  int nonBackground = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (image.at(x, y)[0] < 200 || image.at(x, y)[2] < 180) ++nonBackground;
  EXPECT_GT(nonBackground, image.width * image.height / 10);
}

TEST(Cli, AovRoundTripMatchesTheCamera) {
  const fs::path dir = scratch("aovs");
  const Result r = run("render " + kData + "/render/plane-facing.json -o " +
                       scratch("plane.png").string() + " --aov " + dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream indexFile(dir / "aovs.json");
  const auto index = nlohmann::json::parse(indexFile);
  std::map<std::string, nlohmann::json> byName;
  for (const auto& a : index["aovs"]) byName[a["name"]] = a;
  for (const char* name : {"depth", "viewDepth", "normal", "position", "objectId"}) {
    ASSERT_TRUE(byName.count(name)) << name;
    EXPECT_EQ(byName[name]["width"], 40);
    EXPECT_EQ(byName[name]["height"], 30);
    EXPECT_FALSE(byName[name]["meaning"].get<std::string>().empty());
    EXPECT_TRUE(fs::exists(dir / byName[name]["file"].get<std::string>()));
  }
  EXPECT_EQ(byName["normal"]["channels"], 3);
  EXPECT_EQ(byName["depth"]["channels"], 1);
  // The plane z = 0 faces the camera at distance 5 (near 1, far 11): its linear depth is 5
  // everywhere and its window depth is (f + n)/(2(f − n)) − f n/((f − n) d) + 1/2.
  const FloatImage viewDepth = readPfm(dir / "viewDepth.pfm");
  const FloatImage depth = readPfm(dir / "depth.pfm");
  const FloatImage normal = readPfm(dir / "normal.pfm");
  const double n = 1, f = 11, d = 5;
  const double expectedWindow = (f + n) / (2 * (f - n)) - f * n / ((f - n) * d) + 0.5;
  for (int y = 0; y < 30; y += 7)
    for (int x = 0; x < 40; x += 9) {
      EXPECT_NEAR(viewDepth.at(x, y)[0], 5.0, 1e-4) << x << "," << y;
      EXPECT_NEAR(depth.at(x, y)[0], expectedWindow, 1e-6) << x << "," << y;
      EXPECT_NEAR(normal.at(x, y)[2], 1.0, 1e-3) << x << "," << y;
    }
}

// A disk that fills part way through an AOV folder (here a 200 KB file-size limit: the 3-channel
// AOVs at 200×150 are 360 KB) leaves the folder as it was, or no folder, never an empty folder
// or temporaries (AtomicFiles.* fail later in the set).
// Out of memory for the CPU cutaway buffer (8192²: 3.8 GB of jump-flooding state, under a
// 3 GB limit): the error names the option, and nothing is written.
TEST(Cli, ACutawayBufferBeyondTheMemoryNamesItsOption) {
  if (test::kAddressSanitizer) GTEST_SKIP() << "ulimit -v cannot hold AddressSanitizer";
  const fs::path out = scratch("no-memory.png");
  const Result r = test::runCommand(
      "bash -c \"ulimit -v 3000000; " + kBinary + " render " + kSource +
      "/examples/engine-cutaway.json --size 160x120 --set cutters.adaptive.compute=cpu --set "
      "cutters.adaptive.bufferSize=8192 -o " +
      out.string() + "\"");
  EXPECT_EQ(r.exitCode, 1) << r.err;
  EXPECT_EQ(r.err,
            "cutaway: error: cutters.adaptive.bufferSize: out of memory for the 8192x8192 cutaway "
            "buffer on the CPU; use a smaller bufferSize, or \"compute\": \"gpu\"\n");
  EXPECT_FALSE(fs::exists(out));
}

TEST(Cli, AnAovFolderIsWrittenWholeOrNotAtAll) {
  const std::string scene = kData + "/render/plane-facing.json";
  const fs::path dir = scratch("whole-aovs"), fresh = scratch("no-aovs") / "frame" / "aovs";
  ASSERT_EQ(
      run("render " + scene + " -o " + scratch("whole.png").string() + " --aov " + dir.string())
          .exitCode,
      0);
  const auto contents = [](const fs::path& folder) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::directory_iterator(folder)) {
      std::ifstream is(entry.path(), std::ios::binary);
      files[entry.path().filename().string()].assign(std::istreambuf_iterator<char>(is), {});
    }
    return files;
  };
  const auto before = contents(dir);
  ASSERT_TRUE(before.count("aovs.json"));
  ASSERT_TRUE(before.count("normal.pfm"));
  // Made folders named with a trailing slash are taken apart too.
  const std::string slashed = (scratch("no-aovs-slash") / "a").string() + "/";
  for (const std::string& target : {dir.string(), fresh.string(), slashed}) {
    // SIGXFSZ ignored: the write fails with EFBIG, as a full disk fails with ENOSPC.
    const Result r = test::runCommand("bash -c \"trap '' XFSZ; ulimit -f 200; " + kBinary +
                                      " render " + scene + " --size 200x150 -o " +
                                      scratch("limited.png").string() + " --aov " + target + "\"");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find(".pfm"), std::string::npos) << r.err;
  }
  EXPECT_EQ(contents(dir), before);
  EXPECT_FALSE(fs::exists(scratch("no-aovs")));  // nor the folders made for it
  EXPECT_FALSE(fs::exists(scratch("no-aovs-slash")));
  EXPECT_FALSE(fs::exists(scratch("limited.png")));  // nor the picture written with them
}

// A run stopped by SIGTERM before it wrote its AOVs leaves no AOV folder: the folder is made
// with the AOVs, not when the outputs are checked (that one stayed, empty).
TEST(Cli, ARunStoppedBeforeItsAovsLeavesNoFolder) {
  const fs::path fresh = scratch("stopped-aovs") / "aovs", out = scratch("stopped.png");
  const Result r =
      test::runCommand("bash -c '" + kBinary + " render " + kSource +
                       "/examples/engine-cutaway.json --size 2400x1800 -o " + out.string() +
                       " --aov " + fresh.string() + " & sleep 1; kill -TERM $!; wait $!; echo $?'");
  EXPECT_EQ(r.out, "143\n") << r.err;  // 128 + SIGTERM: stopped while rendering
  EXPECT_FALSE(fs::exists(scratch("stopped-aovs")));
  EXPECT_FALSE(fs::exists(out));
}

// Stopped while the AOVs are written (the folder made, the files still temporaries): the signal
// handler removes the temporaries and then the folders the run made, here two deep.
TEST(Cli, ARunStoppedWhileWritingItsAovsLeavesNoFolder) {
  const fs::path top = scratch("stopped-writing"), fresh = top / "made" / "aovs";
  fs::remove_all(top);
  fs::create_directories(top);
  const Result r = test::runCommand(
      "bash -c '" + kBinary + " render " + kSource +
      "/examples/engine-cutaway.json --size 2400x1800 -o " + (top / "out.png").string() +
      " --aov " + fresh.string() + " & while [ ! -e " + fresh.string() +
      " ] && kill -0 $! 2>/dev/null; do sleep 0.005; done; sleep 0.1; kill -TERM $!; wait $!; "
      "echo $?'");
  EXPECT_EQ(r.out, "143\n") << r.err;  // stopped, not finished
  EXPECT_FALSE(fs::exists(top / "made"));
  EXPECT_FALSE(fs::exists(top / "out.png"));
  EXPECT_TRUE(fs::is_empty(top));  // no temporaries either
}

// An AOV folder written again holds the new frame's AOVs alone: the PFMs the earlier
// aovs.json listed and the new one does not are removed (another scene's cutaway buffers
// stayed beside the new index); files it did not list stay.
TEST(Cli, AnAovFolderWrittenAgainHoldsOnlyTheNewFramesAovs) {
  const fs::path dir = scratch("aovs-again");
  fs::remove_all(dir);
  const auto pfms = [&] {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".pfm") names.insert(e.path().filename().string());
    return names;
  };
  const auto listed = [&] {
    std::set<std::string> names;
    const nlohmann::json index = nlohmann::json::parse(std::ifstream(dir / "aovs.json"));
    for (const auto& a : index["aovs"]) names.insert(a["file"].get<std::string>());
    return names;
  };
  Result r = run("render " + kData + "/render/moving-box.json --size 32x24 -o " +
                 scratch("again-1.png").string() + " --aov " + dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::set<std::string> first = pfms();
  EXPECT_TRUE(first.count("cutawayDepth.pfm"));
  std::ofstream(dir / "notes.txt") << "mine";
  r = run("render " + kData + "/render/plane-facing.json --size 32x24 -o " +
          scratch("again-2.png").string() + " --aov " + dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(pfms(), listed());
  EXPECT_LT(pfms().size(), first.size());
  EXPECT_FALSE(fs::exists(dir / "cutawayDepth.pfm"));
  EXPECT_TRUE(fs::exists(dir / "notes.txt"));
  // A link to a folder that is gone is named as such (it said "File exists").
  const fs::path link = scratch("aovs-link");
  fs::remove(link);
  fs::create_directory_symlink(scratch("aovs-gone"), link);
  r = run("render " + kData + "/render/plane-facing.json --size 32x24 -o " +
          scratch("again-3.png").string() + " --aov " + link.string());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("aovs-link: cannot create AOV directory: it is a symbolic link to "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("aovs-gone, which does not exist"), std::string::npos) << r.err;
}

// An animation's outputs that a folder or a file already holds are refused before the first
// frame is written.
TEST(Cli, AnAnimationsTakenOutputsFailBeforeTheFirstFrame) {
  const std::string scene = kData + "/render/plane-facing.json";
  const fs::path dir = scratch("taken");
  fs::create_directories(dir / "f_2.png");
  Result r = run("render " + scene + " --frames 3 -o " + (dir / "f_%d.png").string());
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("f_2.png: is a directory"), std::string::npos) << r.err;
  fs::create_directories(dir / "aovs");
  std::ofstream(dir / "aovs" / "0003") << "a file";
  r = run("render " + scene + " --frames 3 -o " + (dir / "g_%d.png").string() + " --aov " +
          (dir / "aovs").string());
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("0003: --aov needs a directory"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "f_1.png"));
  EXPECT_FALSE(fs::exists(dir / "g_1.png"));
  EXPECT_FALSE(fs::exists(dir / "aovs" / "0001"));
  // The pattern in a folder's name: each frame's folder must be there, not the pattern's.
  fs::create_directories(dir / "d1");
  r = run("render " + scene + " --frames 2 -o " + (dir / "d%d" / "f.png").string());
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("no such folder: " + (dir / "d2").string()), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "d1" / "f.png"));
  fs::create_directories(dir / "d2");
  r = run("render " + scene + " --frames 2 -o " + (dir / "d%d" / "f.png").string());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "d1" / "f.png"));
  EXPECT_TRUE(fs::exists(dir / "d2" / "f.png"));
}

// A frame that fails while rendering (the volume's lines outgrow "mostSegments" as the camera
// turns) takes back the frames written before it, puts back the files they replaced, and
// names the frame; a run that succeeds leaves nothing of the files it replaced.
TEST(Cli, AnAnimationThatFailsPartWayLeavesTheEarlierOutputsAsTheyWere) {
  const fs::path dir = scratch("animation-undone");
  fs::remove_all(dir);
  fs::create_directories(dir / "out");
  // An ellipsoid's distance field, 200 × 48 × 48: its iso-lines seen side-on fit the budget,
  // seen from above they do not.
  std::vector<float> voxels;
  for (int k = 0; k < 48; ++k)
    for (int j = 0; j < 48; ++j)
      for (int i = 0; i < 200; ++i)
        voxels.push_back(
            float(std::sqrt(std::pow((i - 99.5) / 95, 2) + std::pow((j - 23.5) / 22, 2) +
                            std::pow((k - 23.5) / 22, 2))));
  std::ofstream(dir / "e.raw", std::ios::binary)
      .write(reinterpret_cast<const char*>(voxels.data()), std::streamsize(voxels.size() * 4));
  std::ofstream(dir / "e.json") << R"({"file": "e.raw", "dims": [200, 48, 48], "type": "f32"})";
  const auto sceneWith = [&](const std::string& lastEye) {
    std::ofstream(dir / "s.json") << R"({"volumes": [{"name": "v", "file": "e.json",
      "transferFunction": [{"value": 0, "opacity": 0}], "lines": {"isoValues": [{"value": 0.3},
      {"value": 0.4}, {"value": 0.5}, {"value": 0.6}, {"value": 0.7}, {"value": 0.8},
      {"value": 0.9}, {"value": 1}], "only": true, "mostSegments": 2000}}],
      "camera": {"path": [{"time": 0, "eye": [500, 23.5, 23.5], "target": [99.5, 23.5, 23.5]},
                          {"time": 1, "eye": )" +
                                         lastEye + R"(, "target": [99.5, 23.5, 23.5]}]}})";
  };
  const fs::path out = dir / "out";
  std::ofstream(out / "f_0002.png") << "an earlier frame";
  // An earlier AOV folder of frame 1 with a file of the user's: kept through both runs.
  fs::create_directories(out / "aovs" / "0001");
  std::ofstream(out / "aovs" / "0001" / "notes.txt") << "mine";
  // Frame 1 written through a symbolic link: the file it points to is what is put back.
  std::ofstream(dir / "linked.png") << "linked";
  fs::create_symlink(dir / "linked.png", out / "f_0001.png");
  const std::string args = " --frames 2 --size 100x75 -o " + (out / "f_%04d.png").string() +
                           " --aov " + (out / "aovs").string();
  sceneWith("[99.5, 23.5, 500]");
  Result r = run("render " + (dir / "s.json").string() + args);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("s.json: /volumes/0/lines: frame 2 of 2 (no frame written): the lines "
                       "hold more than 2000 segments"),
            std::string::npos)
      << r.err;
  std::vector<std::string> left;
  for (const auto& e : fs::recursive_directory_iterator(out)) left.push_back(e.path().filename());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left,
            (std::vector<std::string>{"0001", "aovs", "f_0001.png", "f_0002.png", "notes.txt"}));
  const auto text = [](const fs::path& file) {
    std::ifstream in(file);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_EQ(text(out / "f_0002.png"), "an earlier frame");
  EXPECT_TRUE(fs::is_symlink(out / "f_0001.png"));
  EXPECT_EQ(text(dir / "linked.png"), "linked");
  // Side-on throughout, both frames are drawn, the earlier file replaced.
  sceneWith("[500, 23.5, 30]");
  r = run("render " + (dir / "s.json").string() + args);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  left.clear();
  for (const auto& e : fs::directory_iterator(out)) left.push_back(e.path().filename());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"aovs", "f_0001.png", "f_0002.png"}));
  EXPECT_EQ(readPng(out / "f_0002.png").width, 100);
  EXPECT_TRUE(fs::is_symlink(out / "f_0001.png"));
  EXPECT_EQ(readPng(dir / "linked.png").width, 100);
  EXPECT_EQ(text(out / "aovs" / "0001" / "notes.txt"), "mine");
  EXPECT_TRUE(fs::exists(out / "aovs" / "0001" / "aovs.json"));
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().string().find(".old-"), std::string::npos) << e.path();
}

// A camera path whose eye passes through its target half-way: no frame is written, and the
// error names the file, the frame and its time.
TEST(Cli, AnAnimationsUnresolvableCameraFailsBeforeTheFirstFrame) {
  const fs::path dir = scratch("camera-through");
  fs::create_directories(dir);
  const fs::path scene = dir / "scene.json";
  std::ofstream(scene) << R"({"objects": [{"name": "plane", "file": ")" + kData +
                              R"(/meshes/cube.obj"}],
    "camera": {"path": [{"time": 0, "eye": [0, 0, 3], "target": [0, 0, -3]},
                        {"time": 1, "eye": [0, 0, -3], "target": [0, 0, 3]}]}})";
  Result r = run("render " + scene.string() + " --size 32x24 --frames 3 -o " +
                 (dir / "f_%d.png").string());
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("scene.json: /camera: at frame 2, 0.5 s: eye and target are 0 apart"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "f_1.png"));
  r = run("render " + scene.string() + " --size 32x24 --time 0.5 -o " + (dir / "t.png").string());
  EXPECT_NE(r.err.find("/camera: at 0.5 s: eye and target"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "t.png"));
}

TEST(Cli, InfoPrintsObjectsAndWatertightness) {
  const Result r = run("info " + kSource + "/examples/fan-room.json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto info = nlohmann::json::parse(r.out);
  ASSERT_EQ(info["objects"].size(), 5u);
  std::map<std::string, nlohmann::json> byName;
  for (const auto& o : info["objects"]) byName[o["name"]] = o;
  EXPECT_TRUE(byName["fan"]["watertight"].get<bool>());
  EXPECT_TRUE(byName["desk"]["watertight"].get<bool>());
  EXPECT_FALSE(byName["door"]["watertight"].get<bool>());  // a single open panel
  EXPECT_EQ(byName["fan"]["role"], "interest");
  EXPECT_GT(byName["fan"]["triangles"].get<int>(), 1000);
  EXPECT_EQ(info["triangles"].get<int>(), [&] {
    int sum = 0;
    for (const auto& o : info["objects"]) sum += o["triangles"].get<int>();
    return sum;
  }());
}

// `info` prints the style and every cutter option as the scene format writes them (what a scene
// file may hold, floats in their shortest exact form), which a scene file reads back unchanged;
// what the cutters make of the scene stands apart, under "resolved".
TEST(Cli, InfoPrintsTheStyleAndCuttersAsTheSceneFormatWritesThem) {
  const Result r = run("info " + kSource + "/examples/fan-room-cutaway.json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("\"edgeRegion\": 0.1,"), std::string::npos) << r.out;  // the default
  EXPECT_EQ(r.out.find("0.1000000"), std::string::npos) << r.out;  // no float widened to double
  const auto info = nlohmann::json::parse(r.out);
  EXPECT_EQ(info["style"]["name"], "gooch");
  EXPECT_EQ(info["style"]["lines"]["width"], 1.0);
  EXPECT_EQ(info["cutters"]["adaptive"]["angle"], 40.0);
  EXPECT_EQ(info["cutters"]["adaptive"]["cutSurfaces"], "watertight");
  EXPECT_EQ(info["cutters"]["adaptive"]["floorNormal"], nlohmann::json({0.0, 0.0, 1.0}));
  // The printed style and cutters, as a scene's, give the same again: each cutter's.
  for (const std::string name :
       {"fan-room-cutaway", "bunny-box-cutout", "bunny-clip", "bunny-box-breakaway"}) {
    const std::string source = kSource + "/examples/" + name + ".json";
    const Result first = run("info " + source);
    ASSERT_EQ(first.exitCode, 0) << first.err;
    const auto printed = nlohmann::json::parse(first.out);
    std::ifstream in(source);
    nlohmann::json scene = nlohmann::json::parse(in);
    scene["style"] = printed["style"];
    scene["cutters"] = printed["cutters"];
    for (auto& o : scene["objects"])
      if (o.contains("file") && fs::path(o["file"].get<std::string>()).is_relative())
        o["file"] = kSource + "/examples/" + o["file"].get<std::string>();
    const fs::path copy = scratch("info-" + name + ".json");
    std::ofstream(copy) << scene.dump(2);
    const Result again = run("info " + copy.string());
    ASSERT_EQ(again.exitCode, 0) << name << ": " << again.err;
    const auto second = nlohmann::json::parse(again.out);
    EXPECT_EQ(second["style"], printed["style"]) << name;
    EXPECT_EQ(second["cutters"], printed["cutters"]) << name;
    // The clip surfaces' maps are files or recipes, which the schemas do not write: bunny-clip's
    // noise map is left out, so its surface's map size is not the same again.
    if (name != "bunny-clip")
      EXPECT_EQ(second.value("resolved", nlohmann::json()),
                printed.value("resolved", nlohmann::json()))
          << name;
  }
}

// A volume scene end to end: `info` describes the volume as the file has it, `render` writes
// the picture and the volume AOVs, whose opacity covers the head.
TEST(Cli, VolumeSceneInfoAndRenderWithAovs) {
  const std::string scene = kSource + "/examples/mri-head-box-cut.json";
  const Result info = run("info " + scene);
  ASSERT_EQ(info.exitCode, 0) << info.err;
  const auto j = nlohmann::json::parse(info.out);
  ASSERT_EQ(j["volumes"].size(), 1u);
  EXPECT_EQ(j["volumes"][0]["dims"], nlohmann::json({181, 217, 181}));
  EXPECT_EQ(j["volumes"][0]["voxelType"], "u8");
  EXPECT_EQ(j["volumes"][0]["mode"], "composite");
  const fs::path dir = scratch("volume-aovs"), out = scratch("head.png");
  const Result r =
      run("render " + scene + " -o " + out.string() + " --size 96x96 --aov " + dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(fs::exists(out));
  const FloatImage opacity = readPfm(dir / "volumeOpacity.pfm");
  const FloatImage entry = readPfm(dir / "volumeEntryDepth.pfm");
  int opaque = 0, entered = 0;
  for (int y = 0; y < opacity.height; ++y)
    for (int x = 0; x < opacity.width; ++x) {
      opaque += opacity.at(x, y)[0] > 0.9f;
      entered += !std::isnan(entry.at(x, y)[0]);
    }
  EXPECT_GT(opaque, 96 * 96 / 5);
  EXPECT_GE(entered, opaque);
}

// A volume's lines end to end: the PNG, the SVG beside it, and the coverage AOV agree on where
// lines are drawn.
TEST(Cli, VolumeLinesRenderWithTheirSvgAndCoverage) {
  const std::string scene = kSource + "/examples/ct-stent-lines.json";
  const fs::path dir = scratch("lines-aovs"), out = scratch("lines.png"),
                 svg = scratch("lines.svg");
  const Result r = run("render " + scene + " -o " + out.string() + " --size 120x150 --aov " +
                       dir.string() + " --svg " + svg.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(fs::exists(out));
  std::ifstream in(svg);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.rfind("<?xml", 0), 0u);
  EXPECT_NE(text.find("viewBox='0 0 120 150'"), std::string::npos);
  std::size_t polylines = 0;
  for (std::size_t at = text.find("<polyline class='line"); at != std::string::npos;
       at = text.find("<polyline class='line", at + 1))
    ++polylines;
  EXPECT_GT(polylines, 20u);
  const FloatImage coverage = readPfm(dir / "volumeLineCoverage.pfm");
  int covered = 0;
  for (int y = 0; y < coverage.height; ++y)
    for (int x = 0; x < coverage.width; ++x) covered += coverage.at(x, y)[0] > 0.5f;
  EXPECT_GT(covered, 200);
}

// The house's furniture is hidden in its plain view: culled from the second frame on, and
// drawn every frame with --no-occlusion-culling.
TEST(Cli, BenchCullsHiddenObjectsUnlessAskedNotTo) {
  const std::string bench =
      "bench " + kSource + "/examples/house.json --size 64x48 --frames 1 --json";
  for (const bool culling : {true, false}) {
    const Result r = run(bench + (culling ? "" : " --no-occlusion-culling"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto runs = nlohmann::json::parse(r.out)["runs"];
    ASSERT_FALSE(runs.empty());
    for (const auto& run : runs)
      if (culling)
        EXPECT_GT(run["culledObjects"].get<int>(), 10) << run["label"];
      else
        EXPECT_EQ(run["culledObjects"].get<int>(), 0) << run["label"];
  }
}

// --simplify draws the engine's meshes as their simplified versions within --pixel-error:
// fewer triangles the coarser the error, every triangle at 0, and a picture that strays from
// the whole meshes' by little (a few pixels along silhouettes).
TEST(Cli, SimplifyDrawsFewerTrianglesWithinThePixelError) {
  const std::string engine = kSource + "/examples/engine.json --size 160x120 --samples 1";
  const auto triangles = [&](const std::string& options) {
    const Result r =
        run("bench " + engine + " --frames 1 --json --no-occlusion-culling " + options);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return nlohmann::json::parse(r.out)["runs"][0]["meshTriangles"].get<std::size_t>();
  };
  const std::size_t whole = triangles(""), fine = triangles("--simplify --pixel-error 0.5"),
                    coarse = triangles("--simplify --pixel-error 2");
  EXPECT_EQ(whole, 110336u);
  EXPECT_EQ(triangles("--simplify --pixel-error 0"), whole);
  EXPECT_LT(fine, whole * 3 / 4);
  EXPECT_LT(coarse, fine);
  const fs::path simplified = scratch("simplified.png"), full = scratch("whole.png");
  ASSERT_EQ(run("render " + engine + " --simplify -o " + simplified.string()).exitCode, 0);
  ASSERT_EQ(run("render " + engine + " -o " + full.string()).exitCode, 0);
  const Rgba8Image a = readPng(simplified), b = readPng(full);
  int differ = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c = 0; c < 3; ++c)
        if (std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c])) > 64) {
          ++differ;
          break;
        }
  std::printf("simplified: %zu and %zu of %zu triangles; %d pixels differ by more than 64\n", fine,
              coarse, whole, differ);
  EXPECT_LT(differ, a.width * a.height / 50);
}

// --svg on a scene whose volumes draw no lines is a command line the scene refuses: exit 2,
// the option named, nothing written.
TEST(Cli, SvgWithoutVolumeLinesIsAUsageError) {
  const fs::path png = scratch("no-lines.png"), svg = scratch("no-lines.svg");
  const Result r = run("render " + kSource + "/examples/engine.json --size 32x24 -o " +
                       png.string() + " --svg " + svg.string());
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("--svg: writes the volumes' lines"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(png));
  EXPECT_FALSE(fs::exists(svg));
}

TEST(Cli, BenchPrintsJsonAndTable) {
  const std::string scene = kData + "/render/plane-facing.json";
  const Result json = run("bench " + scene + " --frames 3 --json");
  ASSERT_EQ(json.exitCode, 0) << json.err;
  const auto result = nlohmann::json::parse(json.out);
  EXPECT_EQ(result["frames"], 3);
  std::vector<std::string> passes;
  for (const auto& p : result["passes"]) {
    passes.push_back(p["pass"]);
    EXPECT_LE(p["gpuMinMs"].get<double>(), p["gpuMedianMs"].get<double>());
    EXPECT_LE(p["gpuMedianMs"].get<double>(), p["gpuMaxMs"].get<double>());
  }
  EXPECT_EQ(passes, (std::vector<std::string>{"geometry", "visibleObjects", "lines", "composite"}));
  const Result table = run("bench " + scene + " --frames 2");
  ASSERT_EQ(table.exitCode, 0) << table.err;
  EXPECT_NE(table.out.find("frame (wall ms)"), std::string::npos) << table.out;
}

TEST(Cli, BadSceneIsOneLineErrorAndNoOutput) {
  const fs::path bad = scratch("bad.json");
  std::ofstream(bad) << R"({"objects": [{"name": "x", "file": "plane.obj", "role": "hero"}]})";
  const fs::path out = scratch("never.png");
  const Result r = run("render " + bad.string() + " -o " + out.string());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(bad.string() + ": /objects/0/role: unknown value \"hero\""),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(Cli, UnwritableOutputFailsWithoutPartialFiles) {
  const Result r = run("render " + kData + "/render/plane-facing.json -o /nonexistent-dir/out.png");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("/nonexistent-dir/out.png"), std::string::npos) << r.err;
}

// Issue 16: outputs and camera values the CLI used to accept; each a one-line error, a
// non-zero exit, and no file left behind.
TEST(Cli, BadOutputsAndCameraValuesAreRefusedBeforeRendering) {
  const std::string scene = kData + "/render/plane-facing.json";
  const fs::path dir =
      fs::temp_directory_path() / ("cutaway-cli-outputs-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string png = (dir / "out.png").string(), file = (dir / "a-file").string();
  std::ofstream(file) << "x";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"-o " + (dir / "out.jpg").string(), "only PNG"},
      {"-o ''", "empty"},
      {"-o " + dir.string(), "directory"},
      {"-o " + png + " --aov " + file, "needs a directory"},
      {"-o " + png + " --up 0,0,0", "zero vector"},
      {"-o " + png + " --time nan", "finite"},
      {"-o " + png + " --fov nan", "finite"},
      {"-o " + png + " --pixel-error -nan", "finite"},
      {"-o " + png + " --cutaway-angle nan", "finite"},
      {"-o " + png + " --eye 1,1e39,2", "beyond a 32-bit float's range"},
      // The option given is blamed, not one left at the scene's value.
      {"-o " + png + " --eye 0,5,0",
       "--eye: the viewing direction is parallel to the scene's up vector (0,1,0); give --up too"},
      {"-o " + png + " --up 0,0,1", "--up: up is parallel to the viewing direction"},
      {"-o " + png + " --eye 1e14,0,0 --target 99999990000000,0,0",
       "--eye and --target: at 0 s: eye and target are 8.39e+06 apart at 1e+14 from the origin, "
       "too close"},
      {"-o " + png + " --svg " + (dir / "lines.txt").string(), "give it a .svg name"},
      {"-o " + (dir / "a-file" / "out.png").string(), "a-file/out.png: not a folder: "},
      {"-o " + png + " --svg " + (dir / "lines.svg").string(), "no volume of"},
      {"-o " + png + " --frames 2 --svg " + (dir / "lines_%s.svg").string(), "frame pattern"},
      {"-o " + (dir / "f%0999d.png").string() + " --frames 2", "of width at most 99"},
      {"-o " + (dir / "missing" / "out.png").string(), "no such folder"},
      {"-o " + png + " --svg " + (dir / "missing" / "lines.svg").string(), "no such folder"}};
  // A device as the scene: refused, not read until memory runs out.
  const Result zero = run("render /dev/zero -o " + png);
  EXPECT_EQ(zero.exitCode, 1);
  EXPECT_NE(zero.err.find("/dev/zero: not a regular file"), std::string::npos) << zero.err;
  for (const auto& [arguments, reason] : cases) {
    const Result r = run("render " + scene + " " + arguments);
    EXPECT_NE(r.exitCode, 0) << arguments;
    EXPECT_EQ(lines(r.err), 1) << arguments << ": " << r.err;
    EXPECT_NE(r.err.find(reason), std::string::npos) << arguments << ": " << r.err;
    std::size_t left = 0;
    for (const auto& entry : fs::directory_iterator(dir)) left += entry.path() != file;
    EXPECT_EQ(left, 0u) << arguments << " left a file";
  }
  fs::remove_all(dir);
}

TEST(Cli, UsageErrors) {
  EXPECT_EQ(run("").exitCode, 2);
  const Result noFile = run("info ''");
  EXPECT_EQ(noFile.exitCode, 2);
  EXPECT_EQ(noFile.err, "cutaway: error: info: give a scene file, or a GIS file or raster\n");
  const Result noBench = run("bench");
  EXPECT_EQ(noBench.exitCode, 2);
  EXPECT_EQ(noBench.err, "cutaway: error: bench: give a scene file or --city SCALE\n");
  EXPECT_EQ(run("frobnicate").exitCode, 2);
  // A mistyped command is named, with the command it is closest to.
  const Result typo = run("rendr x.json -o x.png");
  EXPECT_EQ(typo.exitCode, 2);
  EXPECT_EQ(typo.err,
            "cutaway: error: unknown command \"rendr\" (did you mean render?); the commands are "
            "render, info, dem, options, bench (see --help)\n");
  // Numbers out of range say the range, not DBL_MAX in full; NaN and infinities are refused.
  for (const auto& [arguments, message] : std::vector<std::pair<std::string, std::string>>{
           {"dem --crs EPSG:27700 --extent 0 0 100 100 --cell inf -o d.tif",
            "--cell: expected a finite number above 0, got \"inf\""},
           {"dem --crs EPSG:27700 --extent 0 0 100 100 --relief -5 -o d.tif",
            "--relief: expected a finite number of at least 0, got \"-5\""},
           {"render " + kData + "/render/plane-facing.json -o x.png --fov inf",
            "--fov: expected a finite number in [1, 170], got \"inf\""},
           {"render " + kData + "/render/plane-facing.json -o x.png --up 1e300,1e300,0",
            "--up: \"1e300,1e300,0\": a coordinate lies beyond a 32-bit float's range"}}) {
    const Result r = run(arguments);
    EXPECT_EQ(r.exitCode, 2) << arguments;
    EXPECT_EQ(r.err, "cutaway: error: " + message + " (see --help)\n") << arguments;
  }
  // Values the parser takes but the command refuses are usage errors too (exit 2); a failing
  // input stays 1 (/dev/zero above).
  for (const std::string& arguments :
       {std::string("--size 0x0"), std::string("--size 16385x1"),
        std::string("--set cutters.adaptive.bufferSize=15"), std::string("--importance plane=2"),
        std::string("--up 0,0,0"), std::string("--cutaway-angle 30 --no-cutaway")}) {
    const Result r = run("render " + kData + "/render/plane-facing.json -o x.png " + arguments);
    EXPECT_EQ(r.exitCode, 2) << arguments << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1) << arguments << ": " << r.err;
  }
  // So are outputs the command cannot write by their names, one path for two outputs, a camera
  // the options place where none can be, and a DEM of too many cells (an outside trial found
  // each exiting 1); each names the option or the path.
  const fs::path taken = scratch("taken.png");
  for (const auto& [arguments, message] : std::vector<std::pair<std::string, std::string>>{
           {"-o ''", "--output: the file name is empty"},
           {"-o x.jpg", "x.jpg: only PNG is written"},
           {"-o x.png --svg x.svg.png", "x.svg.png: --svg writes SVG"},
           {"-o " + taken.string() + " --aov " + taken.string(),
            taken.string() + ": --aov names the folder of a file written too"},
           {"-o " + taken.string() + " --aov " + fs::relative(taken).string() + "/",
            ": --aov names the folder of a file written too"},
           {"-o x.png --eye 0,0,1e-30 --target 0,0,0", "--eye and --target: at 0 s: "}}) {
    const Result r = run("render " + kData + "/render/plane-facing.json " + arguments);
    EXPECT_EQ(r.exitCode, 2) << arguments << ": " << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << arguments << ": " << r.err;
    EXPECT_FALSE(fs::exists(taken)) << arguments;
  }
  // Render targets the device cannot allocate (llvmpipe: one texture past its size limit,
  // though memory is free) blame the size that asked for them, with the target's own size.
  const Result huge = run("render " + kData + "/render/plane-facing.json -o " + taken.string() +
                          " --size 12000x12000 --samples 4");
  if (huge.exitCode != 0) {
    EXPECT_EQ(huge.exitCode, 2) << huge.err;
    EXPECT_EQ(huge.err.rfind("cutaway: error: --size: 12000×12000", 0), 0u) << huge.err;
    EXPECT_NE(huge.err.find(": render target "), std::string::npos) << huge.err;
  }
  fs::remove(taken);
  const Result cells = run("dem --crs EPSG:27700 --extent 0 0 100 100 --cell 1e-3 -o " +
                           scratch("cells.tif").string());
  EXPECT_EQ(cells.exitCode, 2) << cells.err;
  EXPECT_NE(cells.err.find("--cell: more than 10⁸ cells"), std::string::npos) << cells.err;
  // Options at odds: a --set path given twice to different values, or set by an option of its
  // own too. The same value twice, or an option beside the one it sets, is not.
  for (const auto& [arguments, message] : std::vector<std::pair<std::string, std::string>>{
           {"--style toon --set style.name=hatching", "--set: style.name: at odds with --style"},
           {"--shadows --set style.shadows=false", "--set: style.shadows: at odds with --shadows"},
           {"--cutaway-angle 30 --set cutters.adaptive.angle=20",
            "--set: cutters.adaptive.angle: at odds with --cutaway-angle"},
           {"--no-cutaway --set cutters.adaptive.angle=20",
            "--set: cutters.adaptive.angle: at odds with --no-cutaway"},
           {"--set style.lines.width=2 --set style.lines.width=3",
            "--set: style.lines.width: given twice, as \"2\" and \"3\""}}) {
    const Result r = run("render " + kData + "/render/plane-facing.json -o x.png " + arguments);
    EXPECT_EQ(r.exitCode, 2) << arguments;
    EXPECT_EQ(r.err, "cutaway: error: " + message + "\n") << arguments;
  }
  const Result agree = run("render " + kData +
                           "/render/plane-facing.json -o x.png --size 16x12 "
                           "--set style.lines.width=2 --set style.lines.width=2 --shadows "
                           "--set style.shadows.size=1024");
  EXPECT_EQ(agree.exitCode, 0) << agree.err;
  const Result size = run("render " + kData + "/render/plane-facing.json -o x.png --size 12by3");
  EXPECT_NE(size.exitCode, 0);
  EXPECT_NE(size.err.find("--size"), std::string::npos) << size.err;
  const Result eye = run("render " + kData + "/render/plane-facing.json -o x.png --eye 1,2");
  EXPECT_EQ(eye.exitCode, 2);
  EXPECT_NE(eye.err.find("x,y,z"), std::string::npos) << eye.err;
  // An empty name is refused, not taken for the option left out.
  for (const char* option : {"--aov", "--svg"}) {
    const Result empty =
        run("render " + kData + "/render/plane-facing.json -o x.png " + option + " ''");
    EXPECT_EQ(empty.exitCode, 2) << option;
    EXPECT_NE(empty.err.find(std::string(option) + ": the name is empty"), std::string::npos)
        << empty.err;
  }
  // A device limit that an option broke names the option, not the scene's key.
  const Result samples = run("render " + kData + "/render/plane-facing.json -o x.png --samples 16");
  if (samples.exitCode != 0) {
    EXPECT_EQ(samples.exitCode, 2);
    EXPECT_EQ(samples.err.rfind("cutaway: error: --samples: 16 samples exceed the device's", 0), 0u)
        << samples.err;
  }
  fs::remove("x.png");
  const Result far = run("render " + kData + "/render/plane-facing.json -o x.png --eye 0,0,1e20");
  EXPECT_EQ(far.exitCode, 2);
  EXPECT_NE(far.err.find("--eye: beyond 1e15"), std::string::npos) << far.err;
  EXPECT_FALSE(fs::exists("x.png"));
}

TEST(Cli, HelpEverywhere) {
  for (const char* command : {"--help", "render --help", "info --help", "bench --help"}) {
    const Result r = run(command);
    EXPECT_EQ(r.exitCode, 0) << command;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << command << ": " << r.out;
  }
}

// --frames renders the animation (Burns08 Fig. 10: a moving object of interest drags its
// cutaway along); --time renders one instant of it, identical to the matching frame.
TEST(Cli, FramesAndTimeRenderTheAnimation) {
  const std::string scene = kData + "/render/moving-box.json";
  const fs::path pattern = scratch("move_%02d.png");
  const Result frames = run("render " + scene + " --frames 3 -o " + pattern.string());
  ASSERT_EQ(frames.exitCode, 0) << frames.err;
  for (int i = 1; i <= 3; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "move_%02d.png", i);
    EXPECT_TRUE(fs::exists(scratch(name))) << name;
  }
  const fs::path middle = scratch("middle.png");
  const Result single = run("render " + scene + " --time 1 -o " + middle.string() + " --aov " +
                            scratch("middle-aovs").string());
  ASSERT_EQ(single.exitCode, 0) << single.err;
  EXPECT_EQ(readPng(middle).pixels, readPng(scratch("move_02.png")).pixels);
  // At t = 1 the box is at x = -0.5…0.5: the wall is cut in front of it, at the centre.
  const FloatImage id = readPfm(scratch("middle-aovs") / "objectId.pfm");
  EXPECT_EQ(id.at(24, 16)[0], 1.0f);
  EXPECT_EQ(id.at(2, 16)[0], 0.0f);
  const Result bad = run("render " + scene + " --frames 2 -o " + scratch("a_%d_%d.png").string());
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.err.find("one %d"), std::string::npos) << bad.err;
  // %% is a percent sign, as printf has it.
  const Result percent =
      run("render " + scene + " --frames 2 -o " + scratch("at_100%%_%d.png").string());
  ASSERT_EQ(percent.exitCode, 0) << percent.err;
  EXPECT_TRUE(fs::exists(scratch("at_100%_1.png")));
  EXPECT_TRUE(fs::exists(scratch("at_100%_2.png")));
}

// With a cutter, bench measures the plain frame and the cutaway on both compute paths, at
// 512² and 1024², the simple and the contextual structure with R applied each way (Burns11
// Table 7.1's shape), with the CPU references and the jump-flooding accuracy.
TEST(Cli, BenchComparesPlainAndCutaway) {
  const Result r = run("bench " + kData + "/render/moving-box.json --frames 1 --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto result = nlohmann::json::parse(r.out);
  std::vector<std::string> labels;
  for (const auto& run : result["runs"]) labels.push_back(run["label"]);
  EXPECT_EQ(labels, (std::vector<std::string>{
                        "plain", "cutaway 512 gpu", "cutaway 512 cpu", "cutaway 1024 gpu",
                        "cutaway 1024 cpu", "simple cutaway", "contextual cutaway",
                        "contextual translucency", "contextual edge highlights"}));
  // The contextual structure runs the second surface's passes.
  const auto& passes = result["runs"][6]["passes"];
  EXPECT_TRUE(std::any_of(passes.begin(), passes.end(),
                          [](const auto& p) { return p["pass"] == "cutawayDilateC2"; }));
  EXPECT_GT(result["runs"][6]["frameRatioToPlain"].get<double>(), 0.0);
  // Translucency and edge highlights peel their layers.
  for (int run : {7, 8}) {
    const auto& layered = result["runs"][run]["passes"];
    EXPECT_TRUE(std::any_of(layered.begin(), layered.end(), [](const auto& p) {
      return p["pass"] == "translucentLayers";
    })) << result["runs"][run]["label"];
  }
  EXPECT_EQ(result["runs"][2]["computePath"], "cpu");
  EXPECT_GT(result["runs"][2]["cutawaySurfaceMs"].get<double>(), 0.0);
  for (const char* variant : {"jfa", "jfa+1", "1+jfa", "jfa+2"})
    EXPECT_LE(result["jumpFloodingErrorFraction"][variant].get<double>(), 0.05) << variant;
  EXPECT_TRUE(result["cpuReferencesMs"].contains("chamfer 5x5 512"));
}

// The cutter can be switched from the command line: --no-cutaway shows the wall in front of
// the object of interest, --cutaway-angle opens it again.
TEST(Cli, CutawayOptionsOverrideTheScene) {
  const std::string scene = kData + "/render/moving-box.json";
  auto centreId = [&](const std::string& options) {
    const fs::path dir = scratch("cutaway-options");
    const Result r = run("render " + scene + " --time 1 -o " + scratch("c.png").string() +
                         " --aov " + dir.string() + " " + options);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return readPfm(dir / "objectId.pfm").at(24, 16)[0];
  };
  EXPECT_EQ(centreId("--no-cutaway"), 0.0f);
  EXPECT_EQ(centreId("--cutaway-angle 10"), 1.0f);
  const Result both = run("render " + scene + " -o x.png --no-cutaway --cutaway-angle 10");
  EXPECT_NE(both.exitCode, 0);
  EXPECT_NE(both.err.find("--no-cutaway"), std::string::npos) << both.err;
}

// --set takes any option by its scene-file path; bad paths and values, and what they make of
// the scene, are one-line errors naming them, and nothing is written.
TEST(Cli, SetOverridesAnyOptionByItsPath) {
  const std::string scene = kSource + "/examples/bunny.json";
  const fs::path plain = scratch("set-plain.png"), cut = scratch("set-box.png");
  ASSERT_EQ(run("render " + scene + " --size 96x96 -o " + plain.string()).exitCode, 0);
  // A box cut switched on and placed from the command line takes a corner of the bunny.
  const Result r = run("render " + scene + " --size 96x96 -o " + cut.string() +
                       " --set cutters.boxCut.center=0.5,0.5,0.5 --set cutters.boxCut.size=1,1,1");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(readPng(plain).pixels, readPng(cut).pixels);
  for (const auto& [set, says] : std::vector<std::pair<std::string, std::string>>{
           {"nosuch.key=1", "nosuch.key: no such option"},
           {"cutters.boxCut.size=1,0,1",
            "cutters.boxCut.size: component 1 of \"1,0,1\" is outside"},
           {"cutters.adaptive.angle=200", "cutters.adaptive.angle"},
           {"style.shadows.size=1000", "style.shadows.size: value 1000 is not a power of two"},
           {"cutters.boxCut.size", "expected PATH=VALUE"},
           // Checked as the scene file would be: the schema's checks, then the scene's.
           {"'cutters.terrainOpening.terrain=('",
            "--set: cutters.terrainOpening.terrain: invalid regular expression \"(\""},
           {"cutters.cutout.jitter.pattern=image",
            "--set: cutters.cutout.jitter: pattern \"image\" needs an \"image\" file"},
           {"cutters.cutout=true", "--set: cutters.cutout: no object has role \"exterior\""}}) {
    const fs::path out = scratch("set-bad.png");
    const Result bad = run("render " + scene + " -o " + out.string() + " --set " + set);
    EXPECT_EQ(bad.exitCode, 2) << set;  // a command-line value the command refuses
    EXPECT_NE(bad.err.find(says), std::string::npos) << set << ": " << bad.err;
    EXPECT_EQ(lines(bad.err), 1) << bad.err;
    EXPECT_FALSE(fs::exists(out)) << set;
  }
  // Every pipe network's and volume's options too, as the viewer's `set` takes them.
  for (const auto& [example, set] : {std::pair{"pipes-street", "networks.radiusScale=2"},
                                     std::pair{"mri-head-clip", "volumes.mode=maximum"}}) {
    const fs::path before = scratch("set-member-plain.png"), after = scratch("set-member.png");
    const std::string file = kSource + "/examples/" + example + ".json --size 96x72 -o ";
    ASSERT_EQ(run("render " + file + before.string()).exitCode, 0);
    const Result member = run("render " + file + after.string() + " --set " + set);
    ASSERT_EQ(member.exitCode, 0) << member.err;
    EXPECT_NE(readPng(before).pixels, readPng(after).pixels) << set;
  }
  // --cutaway-angle is checked as --set is, and named: θ₁ above the contextual θ₂.
  const Result angle = run("render " + kSource + "/examples/engine-contextual.json --size 64x48 " +
                           "--cutaway-angle 80 -o " + scratch("angle.png").string());
  EXPECT_EQ(angle.exitCode, 2) << angle.err;
  EXPECT_NE(angle.err.find("--cutaway-angle: cutters.adaptive.contextual: the transition angle"),
            std::string::npos)
      << angle.err;
}

// --importance PATTERN=V grades objects by name or group (Burns11 §3.2) and changes the
// contextual cutaway; bad assignments are refused before anything is written.
TEST(Cli, ImportanceByNameOrGroupChangesTheContextualCutaway) {
  const std::string scene = kSource + "/examples/engine-contextual.json";
  const fs::path base = scratch("importance-base.png"), graded = scratch("importance-graded.png");
  ASSERT_EQ(run("render " + scene + " --size 96x72 -o " + base.string()).exitCode, 0);
  // The cylinders made as important as can be are trimmed nowhere: they hide the pistons.
  const Result r = run("render " + scene + " --size 96x72 -o " + graded.string() +
                       " --importance cylinders=1 --importance engine/nodes.72.=0");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(readPng(base).pixels, readPng(graded).pixels);
  for (const auto& [set, says] : std::vector<std::pair<std::string, std::string>>{
           {"nosuch=0.5", "--importance: nosuch: matches no object's name or group"},
           {"pistons=1.5", "importance must lie in [0, 1]"},
           {"pistons", "expected PATTERN=V"},
           {"pistons=high", "expected PATTERN=V"},
           {"'(=0.5'", "invalid regular expression \"(\""},
           {"'c{99999}=0.5'", "\"c{99999}\": it needs more states than a pattern may have"}}) {
    const fs::path out = scratch("importance-bad.png");
    const Result bad = run("render " + scene + " -o " + out.string() + " --importance " + set);
    EXPECT_EQ(bad.exitCode, 2) << set;
    EXPECT_NE(bad.err.find(says), std::string::npos) << set << ": " << bad.err;
    EXPECT_FALSE(fs::exists(out)) << set;
  }
}

// `cutaway options` lists every option with its schema's facts, as a table and as JSON.
TEST(Cli, OptionsListsEverySchema) {
  const Result table = run("options");
  ASSERT_EQ(table.exitCode, 0) << table.err;
  EXPECT_NE(table.out.find("cutters.boxCut.size"), std::string::npos);
  EXPECT_NE(table.out.find("style.gooch.alpha"), std::string::npos);
  EXPECT_NE(table.out.find("networks.radiusScale"), std::string::npos);
  EXPECT_NE(table.out.find("volumes.sampleDistance"), std::string::npos);
  const Result json = run("options --json");
  ASSERT_EQ(json.exitCode, 0) << json.err;
  const auto options = nlohmann::json::parse(json.out);
  ASSERT_TRUE(options.is_array());
  bool found = false;
  for (const auto& o : options)
    if (o["path"] == "cutters.adaptive.angle") {
      found = true;
      EXPECT_EQ(o["type"], "float");
      EXPECT_EQ(o["range"], "[0, 90]");
      EXPECT_EQ(o["default"], "45");
      EXPECT_EQ(o["live"], true);
    }
  EXPECT_TRUE(found);
  EXPECT_EQ(lines(table.out), int(options.size()) + 1);  // a header line, then one per option
}

TEST(Cli, CutoutAndBreakawayRenderWithTheirAovs) {
  for (const std::string scene : {"bunny-box-cutout", "bunny-box-breakaway"}) {
    const fs::path out = scratch(scene + ".png"), aovs = scratch(scene + "-aovs");
    const Result r = run("render " + kSource + "/examples/" + scene + ".json -o " + out.string() +
                         " --size 96x96 --aov " + aovs.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "") << "a watertight exterior needs no warning";
    EXPECT_EQ(readPng(out).width, 96);
    std::ifstream sidecar(aovs / "aovs.json");
    const auto meta = nlohmann::json::parse(sidecar);
    const std::string expected =
        scene == "bunny-box-cutout" ? "cutoutDistance" : "breakawayClipDepth";
    bool found = false;
    for (const auto& entry : meta["aovs"]) found |= entry["name"] == expected;
    EXPECT_TRUE(found) << meta.dump();
    EXPECT_TRUE(fs::exists(aovs / (expected + ".pfm")));
  }
}

TEST(Cli, InfoPrintsTheExteriorMainAxis) {
  const Result r = run("info " + kSource + "/examples/bunny-box-cutout.json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto info = nlohmann::json::parse(r.out);
  ASSERT_EQ(info["exteriors"].size(), 1u);
  const auto& box = info["exteriors"][0];
  EXPECT_EQ(box["name"], "box");
  // The hollow box is longest along x (2.5 × 2.4 × 2).
  EXPECT_NEAR(std::abs(box["mainAxis"][0].get<double>()), 1.0, 1e-4);
  EXPECT_GT(box["eigenvalues"][0].get<double>(), box["eigenvalues"][1].get<double>());
  EXPECT_EQ(info["cutters"]["cutout"]["angle"], 90.0);
}

TEST(Cli, OpenExteriorWarnsAndFlatObjectsFailClearly) {
  const Result warn = run("render " + kSource + "/examples/fan-room-breakaway.json -o " +
                          scratch("room.png").string() + " --size 64x48");
  EXPECT_EQ(warn.exitCode, 0) << warn.err;
  EXPECT_EQ(warn.err, "") << "the room says \"solid\": false, so nothing to warn about";
  const Result open = run("render " + kData + "/render/cutout_open_exterior.json -o " +
                          scratch("open.png").string() + " --size 64x48");
  EXPECT_EQ(open.exitCode, 0) << open.err;
  EXPECT_NE(open.err.find("exterior \"open\" is not watertight"), std::string::npos) << open.err;
  // The object's pointer and what to change; not Qhull's own words.
  for (const auto& [flat, why] :
       {std::pair<std::string, std::string>{"cutout_flat_exterior",
                                            ": /objects/0: exterior \"flat\" is flat (its points "
                                            "lie in one plane or on one line)"},
        {"breakaway_flat_interior",
         ": /objects/1: interior cluster \"the ungrouped interior objects\" is flat"}}) {
    const fs::path out = scratch(flat + ".png");
    const Result r = run("render " + kData + "/render/" + flat + ".json -o " + out.string());
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(flat + ".json" + why), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("QH"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

TEST(Cli, BenchComparesPlainCutoutAndBreakawayPerStyle) {
  const Result r =
      run("bench " + kSource + "/examples/bunny-box-cutout.json --frames 1 --size 64x64 --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto bench = nlohmann::json::parse(r.out);
  std::vector<std::string> labels;
  for (const auto& run : bench["runs"]) labels.push_back(run["label"]);
  for (const std::string style : {"gooch", "blinn-phong"})
    for (const std::string what : {"plain", "cutout", "breakaway"})
      EXPECT_NE(std::find(labels.begin(), labels.end(), what + " " + style), labels.end())
          << what << " " << style;
}

// A volume scene: plain ray casting, each cutter alone and both, at 512² and 1024²; the text
// summary gives each run's frame against the plain run of its own size.
TEST(Cli, BenchOfAVolumeComparesEachCutterWithThePlainRayCastingOfItsSize) {
  const fs::path scene = scratch("volume-bench.json");
  std::ofstream(scene) << R"({"resolution": [64, 64], "samples": 1,
      "volumes": [{"name": "brain", "file": "/usr/share/doc/libvolpack1-dev/examples/brainsmall.den",
                   "role": "exterior",
                   "transferFunction": [{"value": 30, "color": [0.9, 0.8, 0.7], "opacity": 0},
                                        {"value": 90, "color": [0.9, 0.8, 0.7], "opacity": 0.5}]}],
      "cutters": {"boxCut": {"center": [64, 64, 84], "size": [64, 64, 84]},
                  "cutout": true}})";
  const Result r = run("bench " + scene.string() + " --frames 1");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::size_t summary = r.out.find("\nsummary");
  ASSERT_NE(summary, std::string::npos) << r.out;
  std::map<std::string, std::pair<double, double>> rows;  // label: frame ms, × plain
  std::istringstream table(r.out.substr(summary + 1));
  std::string line;
  std::getline(table, line);  // the header
  while (std::getline(table, line) && !line.empty()) {
    const std::size_t numbers = line.find_first_of("0123456789", line.find("  "));
    std::istringstream values(line.substr(numbers));
    double ms = 0.0, ratio = 0.0;
    values >> ms >> ratio;
    std::string label = line.substr(0, numbers);
    label.erase(label.find_last_not_of(' ') + 1);
    rows[label] = {ms, ratio};
  }
  for (const std::string size : {"512²", "1024²"}) {
    const std::string plainLabel = "ray casting " + size;
    ASSERT_TRUE(rows.count(plainLabel)) << r.out;
    const double plain = rows[plainLabel].first;
    for (const std::string run : {"ray casting ", "boxCut ", "cutout ", "all cutters "}) {
      ASSERT_TRUE(rows.count(run + size)) << run + size << "\n" << r.out;
      const auto [ms, ratio] = rows[run + size];
      EXPECT_NEAR(ratio, ms / plain, 1e-3 + 1e-3 * ratio) << run + size << "\n" << r.out;
    }
  }
}

TEST(Cli, StyleNamesAndShadowsFlag) {
  const fs::path dir = scratch("toon-aovs");
  const Result r =
      run("render " + kData + "/render/box-shadow.json -o " + scratch("toon.png").string() +
          " --style toon --shadows --aov " + dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("toon"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir / "shadowMap.pfm"));
  const Result plain =
      run("render " + kData + "/render/plane-facing.json -o " + scratch("hatching.png").string() +
          " --style hatching --aov " + (dir / "plain").string());
  ASSERT_EQ(plain.exitCode, 0) << plain.err;
  EXPECT_FALSE(fs::exists(dir / "plain" / "shadowMap.pfm"));  // shadows are off by default
  const Result bad = run("render " + kData + "/render/plane-facing.json -o " +
                         scratch("bad.png").string() + " --style watercolour");
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("gooch,blinn-phong,toon,hatching"), std::string::npos) << bad.err;
}

TEST(Cli, ClipSurfacesWarnAboutOpenMeshesAndBench) {
  const Result r = run("render " + kSource + "/examples/engine-clip.json -o " +
                       scratch("engine-clip.png").string() + " --size 96x72");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("not watertight, so their cuts get no cap"), std::string::npos) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  const Result quiet = run("render " + kSource + "/examples/bunny-clip.json -o " +
                           scratch("bunny-clip.png").string() + " --size 64x64");
  EXPECT_EQ(quiet.err, "");
  const Result bench =
      run("bench " + kSource + "/examples/bunny-clip.json --frames 1 --size 64x64 --json");
  ASSERT_EQ(bench.exitCode, 0) << bench.err;
  std::vector<std::string> labels;
  const auto parsed = nlohmann::json::parse(bench.out);
  for (const auto& run : parsed["runs"]) labels.push_back(run["label"]);
  EXPECT_EQ(labels, (std::vector<std::string>{"plain", "clipped", "clipped + capped"}));
}

TEST(Cli, DemWritesAGeoTiffThatReadsBackAsItsNoise) {
  const std::string out = test::scratchPath("cli", "dem.tif").string();
  const auto r =
      run("dem --extent 265000 145000 265300 145200 --crs EPSG:27700 --cell 10 "
          "--relief 25 --base 40 --seed 1 -o " +
          out);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("30x20 Float32, EPSG:27700"), std::string::npos) << r.out;
  const RasterTerrain t = importRasterTerrain(out, {.offset = {265000.0, 145000.0, 0.0}});
  EXPECT_EQ(t.columns, 30);
  EXPECT_EQ(t.rows, 20);
  EXPECT_EQ(t.geoTransform, (std::array<double, 6>{265000, 10, 0, 145200, 0, -10}));
  const SyntheticDemOptions o{.min = {265000, 145000},
                              .max = {265300, 145200},
                              .crs = "EPSG:27700",
                              .cell = 10,
                              .base = 40,
                              .relief = 25,
                              .seed = 1};
  for (const auto& [c, row] : {std::pair{0, 0}, {29, 19}, {11, 7}})
    EXPECT_EQ(t.mesh.positions[t.node(c, row)].y,
              float(syntheticDemHeight(o, 265005.0 + 10 * c, 145195.0 - 10 * row)));
  const auto info = run("info " + out);
  ASSERT_EQ(info.exitCode, 0) << info.err;
  const auto j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["raster"]["size"], nlohmann::json({30, 20}));
  EXPECT_EQ(j["raster"]["crs"]["authority"], "EPSG:27700");
  EXPECT_EQ(j["raster"]["extent"], nlohmann::json({265000, 145000, 265300, 145200}));
  EXPECT_GE(j["raster"]["min"].get<double>(), 40.0);
  // Bad input: one line naming the place and the reason, no file.
  const std::string odd = test::scratchPath("cli", "odd.tif").string();
  // The extent and the CRS are command-line values: named by their options, exit 2; latitudes
  // past the pole in degrees too.
  for (const auto& [arguments, message] : std::vector<std::pair<std::string, std::string>>{
           {"--extent 0 0 15 20 --crs EPSG:27700",
            "--extent: the extent (0, 0) to (15, 20) must hold a whole, positive number of "
            "10-unit cells"},
           {"--extent 0 0 20 20 --crs EPSG:999999", "--crs: unknown CRS"},
           {"--extent -1e308 -1e308 1e308 1e308 --cell 1e308 --crs EPSG:27700",
            "--extent: the extent's width and height overflow 64-bit floats"},
           {"--extent 0 0 100 100 --crs EPSG:4326",
            "--extent: the extent (0, 0) to (100, 100) lies beyond the degrees of "
            "\"EPSG:4326\""}}) {
    const auto r = run("dem " + arguments + " -o " + odd);
    EXPECT_EQ(r.exitCode, 2) << arguments;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(odd)) << arguments;
  }
  // GDAL's reason names the file given, not the temporary one written first.
  const auto proc = run("dem --extent 0 0 20 20 --crs EPSG:27700 -o /proc/cutaway-dem.tif");
  EXPECT_EQ(proc.exitCode, 1);
  EXPECT_NE(proc.err.find("/proc/cutaway-dem.tif: cannot create"), std::string::npos) << proc.err;
  EXPECT_EQ(proc.err.find(".tmp-"), std::string::npos) << proc.err;
  const std::string png = test::scratchPath("cli", "dem.png").string();
  const auto named = run("dem --extent 0 0 20 20 --crs EPSG:27700 -o " + png);
  EXPECT_EQ(named.exitCode, 2);  // a command-line value, as `render -o x.jpg` is
  EXPECT_NE(named.err.find("dem.png: dem writes a GeoTIFF"), std::string::npos) << named.err;
  const auto base = run("dem --extent 0 0 20 20 --crs EPSG:27700 --base 1e39 -o " + odd);
  EXPECT_EQ(base.exitCode, 2);
  EXPECT_NE(base.err.find("--base: the base height must fit in Float32"), std::string::npos)
      << base.err;
  EXPECT_FALSE(std::filesystem::exists(png));
  // Heights beyond Float32 would be written as infinities.
  const auto huge = run("dem --extent 0 0 20 20 --crs EPSG:27700 --relief 1e39 -o " + odd);
  EXPECT_EQ(huge.exitCode, 2);  // command-line values the command refuses
  const auto nan = run("dem --extent 0 0 nan 20 --crs EPSG:27700 -o " + odd);
  EXPECT_EQ(nan.exitCode, 2);
  EXPECT_NE(nan.err.find("--extent: west, south, east and north must be finite"), std::string::npos)
      << nan.err;
  EXPECT_NE(huge.err.find("--relief: heights from --base to --base + --relief must fit in "
                          "Float32"),
            std::string::npos)
      << huge.err;
  EXPECT_FALSE(std::filesystem::exists(odd));
}

TEST(Cli, InfoDescribesGisLayers) {
  const auto r = run("info /usr/share/plplot5.15.0/ss/ss64ne_Building_Area.shp");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["layers"].size(), 1u);
  const auto& layer = j["layers"][0];
  EXPECT_EQ(layer["name"], "ss64ne_Building_Area");
  EXPECT_EQ(layer["geometryType"], "Polygon");
  EXPECT_EQ(layer["features"], 253);
  EXPECT_EQ(layer["crs"]["authority"], "EPSG:27700");
  EXPECT_EQ(layer["fields"], nlohmann::json({"fid", "FeatCode", "FeatDesc"}));
  EXPECT_EQ(layer["fieldTypes"], nlohmann::json({"String", "Integer64", "String"}));
  EXPECT_EQ(layer["extent"].size(), 4u);
  const std::string text = test::scratchPath("cli", "notes.txt").string();
  std::ofstream(text) << "not GIS data";
  const auto bad = run("info " + text);
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_NE(bad.err.find("notes.txt: cannot open as a GIS vector data source"), std::string::npos)
      << bad.err;
}

// Konev18 Fig. 15 as a frame sequence: the camera backs away from a junction of the SS64NE
// sewers (60 to 500 m; the opening closes at d_c = s² = 400 m, eq. 1), so the opened area
// shrinks from frame to frame and is gone at the junction in the last one.
TEST(Cli, ZoomSequenceClosesTheTerrainOpening) {
  const fs::path dir = scratch("zoom");
  fs::create_directories(dir);
  const Result r =
      run("render " + kSource + "/examples/ss64ne-zoom.json --size 192x120 --frames 4 -o " +
          (dir / "frame_%d.png").string() + " --aov " + (dir / "aovs").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  int previous = 192 * 120 + 1;
  bool centreOpen[4];
  for (int f = 0; f < 4; ++f) {
    char name[8];
    std::snprintf(name, sizeof name, "%04d", f + 1);
    const FloatImage cls = readPfm(dir / "aovs" / name / "terrainClass.pfm");
    int discarded = 0;
    for (float v : cls.data) discarded += v == 3.0f;
    EXPECT_LT(discarded, previous) << "frame " << f + 1;
    previous = discarded;
    centreOpen[f] = cls.at(96, 60)[0] == 3.0f;
  }
  EXPECT_TRUE(centreOpen[0]);
  EXPECT_FALSE(centreOpen[3]);
}

// Konev18 Table 1's rows from one bench run of a scene with pipe networks, at both sizes.
TEST(Cli, BenchOfANetworkSceneGivesTable1sRows) {
  const Result r = run("bench " + kSource + "/examples/pipes-street.json --frames 1 --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto result = nlohmann::json::parse(r.out);
  std::vector<std::string> labels;
  std::map<std::string, std::size_t> triangles;
  for (const auto& row : result["runs"]) {
    labels.push_back(row["label"]);
    triangles[labels.back()] = row["meshTriangles"];
  }
  std::vector<std::string> expected;
  for (const char* size : {"L", "H"})
    for (const char* row : {"Empty", "Terrain", "Shafts", "Pipes (B)", "Pipes (M)", "City"})
      expected.push_back(std::string(row) + " " + size);
  EXPECT_EQ(labels, expected);
  // The whole city draws the terrain's and the shafts' triangles, the terrain at the detail
  // the same view selects; billboard pipes are no mesh.
  for (const std::string size : {" L", " H"}) {
    EXPECT_EQ(triangles["Empty" + size], 0u);
    EXPECT_EQ(triangles["Pipes (B)" + size], 0u);
    EXPECT_GT(triangles["Terrain" + size], 0u);
    EXPECT_EQ(triangles["City" + size], triangles["Terrain" + size] + triangles["Shafts" + size]);
  }
}

// The generated city renders as a lit ground seen from above (green, not the black of a
// ground facing down) with the network's openings; without a scene or --city, one error.
TEST(Cli, RenderOfTheBenchmarkCity) {
  const fs::path out = scratch("city.png");
  const Result r = run("render --city 1 --size 160x100 -o " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Rgba8Image image = readPng(out);
  int ground = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const auto* p = image.at(x, y);
      ground += p[1] > 100 && p[1] > p[0] + 10 && p[1] > p[2] + 20;
    }
  EXPECT_GT(ground, image.width * image.height / 4);
  const Result none = run("render -o " + scratch("none.png").string());
  EXPECT_EQ(none.exitCode, 2);  // a command line without a scene
  EXPECT_EQ(none.err, "cutaway: error: render: give a scene file or --city SCALE\n");
}

// `info` describes each pipe network as loaded: pipes after the bend splitting, their cut
// stretches (the example cuts every pipe from 15% to 85% of its length) and the junction
// shaft, into which the four pipes open: each loses the shaft's inner radius, 0.7 − 0.12 m.
TEST(Cli, InfoDescribesPipeNetworks) {
  const Result r = run("info " + kSource + "/examples/pipes-street.json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto info = nlohmann::json::parse(r.out);
  ASSERT_EQ(info["networks"].size(), 1u);
  const auto& net = info["networks"][0];
  EXPECT_EQ(net["name"], "sewers");
  EXPECT_EQ(net["mode"], "billboards");
  EXPECT_EQ(net["pipes"], 4);
  EXPECT_EQ(net["cutPipes"], 4);
  EXPECT_NEAR(net["cutLength"].get<double>(), 0.7 * (net["length"].get<double>() + 4 * 0.58), 1e-3);
  EXPECT_EQ(net["shafts"], 1);
  EXPECT_EQ(net["radius"][0].get<float>(), 0.3f);
  EXPECT_EQ(net["radius"][1].get<float>(), 0.5f);
}

// --projection orthographic on a perspective scene keeps the view's height at the target, as
// the viewer's P does: a square in the target's plane covers as many pixels either way.
TEST(Cli, ProjectionOverrideKeepsTheSizeAtTheTarget) {
  const fs::path scene = scratch("flat.json");
  std::ofstream(scene) << R"({"resolution": [80, 60], "samples": 1,
    "camera": {"eye": [0, 0, 6], "target": [0, 0, 0], "fov": 40},
    "objects": [{"name": "flat", "file": ")" +
                              kData + R"(/meshes/flat.obj"}]})";
  const auto covered = [&](const std::string& options) {
    const fs::path dir = scratch("flat-aovs");
    const Result r = run("render " + scene.string() + " -o " + scratch("flat.png").string() +
                         " --aov " + dir.string() + options);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    int n = 0;
    for (float v : readPfm(dir / "objectId.pfm").data) n += v >= 0.0f;
    return n;
  };
  const int perspective = covered(""), orthographic = covered(" --projection orthographic");
  EXPECT_GT(perspective, 100);
  EXPECT_NEAR(orthographic, perspective, 0.03 * perspective);
}

// Coordinates in a projected CRS without the geo frame's offset: floats step by centimetres
// there; the render says which part lies far away and the offset that would bring it near.
TEST(Cli, FarCoordinatesAreWarnedAbout) {
  const fs::path scene = scratch("far.json");
  std::ofstream(scene) << R"({"resolution": [40, 30], "samples": 1, "camera": {"fit": true},
    "networks": [{"name": "mains", "wallThickness": 0.1,
                  "pipes": [{"lines": [[[265000, -2, -145000], [265010, -2, -145000]]], "radius": 0.5}]}]})";
  const Result r = run("render " + scene.string() + " -o " + scratch("far.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("warning: " + scene.string() + ": \"mains\" lies 2.65e+05 scene units"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("about [265005, 145000]"), std::string::npos) << r.err;
  // Nearer than 1e5 too, where a step is over a thousandth of the thing's size (a box 2.8
  // across at 9e4: steps of 0.008 speckle its lines); not a box 1000 across there, nor a unit
  // box at 1000.
  for (const auto& [translate, scale, warned] :
       {std::tuple{"[90000, 90000, 0]", "2.8", true},
        std::tuple{"[90000, 90000, 0]", "1000", false}, std::tuple{"[1000, 0, 0]", "1", false}}) {
    std::ofstream(scene) << R"({"resolution": [40, 30], "samples": 1, "camera": {"fit": true},
      "objects": [{"name": "box", "file": ")"
                         << kData << R"(/meshes/cube.obj", "transform": {"translate": )"
                         << translate << R"(, "scale": )" << scale << "}}]}";
    const Result near = run("render " + scene.string() + " -o " + scratch("far.png").string());
    ASSERT_EQ(near.exitCode, 0) << near.err;
    EXPECT_EQ(near.err.find("warning: " + scene.string() + ": \"box\" lies"),
              warned ? 0u : std::string::npos)
        << translate << " " << scale << ": " << near.err;
  }
}

// Issue 17: aovs.json says enough to recompute the cutaway depth from the files alone. On a
// non-square view (96 × 64) with a 48² buffer, Burns11 eq. 4.2 is worked here by brute force
// from anchorCone's z and m_E and the buffer's pixel size in view-plane units (its "values"),
// and compared with cutawayDepth, window depth = (NDC + 1)/2, clamped at the near plane. Both
// compute paths (CPU on llvmpipe, the GPU's passes) write anchorCone.
TEST(Cli, TheCutawayDepthIsRecomputedFromTheAovFilesAlone) {
  for (const std::string compute : {"cpu", "gpu"}) {
    const fs::path dir = scratch("recompute-" + compute);
    const Result r =
        run("render " + kSource + "/examples/engine-cutaway.json --size 96x64 -o " +
            scratch("recompute.png").string() + " --aov " + dir.string() +
            " --set cutters.adaptive.bufferSize=48 --set cutters.adaptive.compute=" + compute +
            " --set cutters.adaptive.jumpFlooding=jfa+2");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::ifstream indexFile(dir / "aovs.json");
    const auto index = nlohmann::json::parse(indexFile);
    std::map<std::string, nlohmann::json> byName;
    for (const auto& a : index["aovs"]) byName[a["name"]] = a;
    ASSERT_TRUE(byName.count("anchorCone") && byName.count("cutawayDepth")) << compute;
    const nlohmann::json& values = byName["cutawayDepth"]["values"];
    ASSERT_EQ(values["bufferSize"], 48);
    const double ux = values["viewPlanePerPixelX"], uy = values["viewPlanePerPixelY"];
    // The camera's projection says the same: 2 / (n · P00), 2 / (n · P11).
    const auto& P = index["camera"]["projectionMatrix"];
    EXPECT_NEAR(ux, 2.0 / 48.0 / P[0][0].get<double>(), 1e-9);
    EXPECT_NEAR(uy, 2.0 / 48.0 / P[1][1].get<double>(), 1e-9);
    EXPECT_NE(ux, uy);  // the buffer is stretched over a 3:2 view
    const FloatImage cone = readPfm(dir / "anchorCone.pfm"),
                     depth = readPfm(dir / "cutawayDepth.pfm");
    ASSERT_EQ(cone.width, 48);
    ASSERT_EQ(depth.width, 48);
    int seeds = 0, cut = 0, off = 0;
    double worst = 0.0;
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 48; ++x) {
        double c = -1.0;  // the near plane: nothing cut
        for (int qy = 0; qy < 48; ++qy)
          for (int qx = 0; qx < 48; ++qx) {
            const float* q = cone.at(qx, qy);
            if (q[0] <= -1.0f) continue;
            c = std::max(c, q[0] - q[1] * std::hypot((qx - x) * ux, (qy - y) * uy));
          }
        seeds += cone.at(x, y)[0] > -1.0f;
        cut += c > -1.0;
        const double error = std::abs((c + 1.0) / 2.0 - depth.at(x, y)[0]);
        worst = std::max(worst, error);
        off += error > 1e-5;
      }
    EXPECT_GT(seeds, 20) << compute;
    EXPECT_GT(cut, 48 * 48 / 4) << compute;
    // Jump flooding with two extra passes finds every pixel's best seed here (measured worst
    // 1e-7 on both paths).
    EXPECT_EQ(off, 0) << compute << ": worst " << worst;
  }
}

// Issue 17: aovs.json says which row of an offset map is t = 0, and the surface it belongs to.
// examples/bunny-clip.json's noisy relief: every cap pixel's position (position.pfm, capMask)
// lies on Trapp13 eq. 1's surface f = 0 with OM read from offsetMap_0.pfm as its meaning says
// (bottom row t = 0, bilinear between texel centres, repeating) and O, U, V, S from its
// values, within a tenth of the relief's height S_z (the cap mesh interpolates the map
// linearly between its grid's nodes; measured worst 0.06·S_z); read upside down, over a third
// of them are off by more (measured: 41%).
TEST(Cli, CapsLieOnTheReliefReadFromTheAovFilesAlone) {
  const fs::path dir = scratch("relief");
  const Result r = run("render " + kSource + "/examples/bunny-clip.json --size 200x150 -o " +
                       scratch("relief.png").string() + " --aov " + dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream indexFile(dir / "aovs.json");
  const auto index = nlohmann::json::parse(indexFile);
  nlohmann::json map;
  for (const auto& a : index["aovs"])
    if (a["name"] == "offsetMap_0") map = a;
  ASSERT_FALSE(map.is_null());
  const nlohmann::json& v = map["values"];
  const glm::dvec3 o(v["originX"], v["originY"], v["originZ"]), u(v["uX"], v["uY"], v["uZ"]),
      w(v["vX"], v["vY"], v["vZ"]);
  const double sx = v["scaleX"], sy = v["scaleY"], sz = v["height"];
  const glm::dvec3 n = glm::normalize(glm::cross(glm::normalize(u), glm::normalize(w)));
  const FloatImage om = readPfm(dir / "offsetMap_0.pfm"), cap = readPfm(dir / "capMask.pfm"),
                   pos = readPfm(dir / "position.pfm");
  // OM at (s, t): texel (i, j) with j counted from the bottom row (or, `flipped`, the top).
  const auto sample = [&](double s, double t, bool flipped) {
    const double x = s * om.width - 0.5, y = t * om.height - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const auto texel = [&](double i, double j) {
      const int col = int(i - om.width * std::floor(i / om.width));
      const int fromBottom = int(j - om.height * std::floor(j / om.height));
      return double(om.at(col, flipped ? fromBottom : om.height - 1 - fromBottom)[0]);
    };
    const double bottom = texel(fx, fy) + (x - fx) * (texel(fx + 1, fy) - texel(fx, fy));
    const double top = texel(fx, fy + 1) + (x - fx) * (texel(fx + 1, fy + 1) - texel(fx, fy + 1));
    return bottom + (y - fy) * (top - bottom);
  };
  int caps = 0, off = 0, offFlipped = 0;
  double worst = 0.0;
  for (int y = 0; y < cap.height; ++y)
    for (int x = 0; x < cap.width; ++x) {
      if (cap.at(x, y)[0] != 1.0f) continue;
      ++caps;
      const glm::dvec3 p(pos.at(x, y)[0], pos.at(x, y)[1], pos.at(x, y)[2]);
      const glm::dvec3 pn = p - glm::dot(p - o, n) * n;                             // eq. 3
      const double s = glm::dot(pn - o, u / glm::length(u)) / glm::length(u) * sx,  // eq. 2
          t = glm::dot(pn - o, w / glm::length(w)) / glm::length(w) * sy;
      const double plane = glm::dot(p, n) - glm::dot(n, o);
      const double f = std::abs(plane + sample(s, t, false) * sz);  // eq. 1
      worst = std::max(worst, f);
      off += f > 0.1 * sz;
      offFlipped += std::abs(plane + sample(s, t, true) * sz) > 0.1 * sz;
    }
  EXPECT_GT(caps, 1000);
  EXPECT_EQ(off, 0) << "of " << caps << " worst " << worst;
  EXPECT_GT(offFlipped, caps / 3) << "of " << caps;
}

// A closed mesh wound inward (a CAD export, marching cubes) is turned outward on import, so
// that every cutter reads its outside as the outside: the cutout, the adaptive cutaway and the
// box cut draw it as they draw the same cube wound outward, and `info` says it was turned. A
// hollow shell (a cavity wound inward inside an outward cube) keeps its winding.
TEST(Cli, AClosedMeshWoundInwardIsTurnedOutward) {
  std::ifstream in(kData + "/meshes/cube.obj");
  std::string outward, inward, hollow;
  for (std::string line; std::getline(in, line);) {
    outward += line + "\n";
    std::istringstream words(line);
    std::string f, a, b, c;
    if (words >> f >> a >> b >> c && f == "f") {
      inward += "f " + a + " " + c + " " + b + "\n";
      hollow += line + "\n";
    } else {
      inward += line + "\n";
      hollow += line + "\n";
    }
  }
  // The cavity: the cube shrunk about its centre, its faces turned inward.
  for (int i = 0; i < 8; ++i) {
    const int x = (i == 1 || i == 2 || i == 5 || i == 6),
              y = (i == 2 || i == 3 || i == 6 || i == 7), z = i >= 4;
    hollow += "v " + std::to_string(0.25 + 0.5 * x) + " " + std::to_string(0.25 + 0.5 * y) + " " +
              std::to_string(0.25 + 0.5 * z) + "\n";
  }
  std::istringstream faces(outward);
  for (std::string line; std::getline(faces, line);) {
    std::istringstream words(line);
    std::string f;
    int a, b, c;
    if (words >> f >> a >> b >> c && f == "f")
      hollow += "f " + std::to_string(a + 8) + " " + std::to_string(c + 8) + " " +
                std::to_string(b + 8) + "\n";
  }
  std::ofstream(scratch("outward.obj")) << outward;
  std::ofstream(scratch("inward.obj")) << inward;
  std::ofstream(scratch("hollow.obj")) << hollow;
  const auto scene = [&](const std::string& mesh, const std::string& cutter) {
    const fs::path file =
        scratch(mesh + "-" + std::to_string(std::hash<std::string>()(cutter)) + ".json");
    std::ofstream(file) << R"({"resolution": [96, 72], "samples": 1,
      "camera": {"eye": [3, 2, 4], "target": [0.5, 0.5, 0.5], "fov": 40},
      "objects": [{"name": "box", "file": ")"
                        << mesh << R"(.obj", "role": "exterior"},
                  {"name": "tetra", "file": ")"
                        << kData << R"(/meshes/tetra.obj", "role": "interior",
                   "transform": {"translate": [0.3, 0.3, 0.3], "scale": 0.4}}],
      "cutters": )" << cutter
                        << "}";
    return file.string();
  };
  for (const std::string cutter : {R"({"cutout": true})", R"({"adaptive": true})",
                                   R"({"boxCut": {"center": [1, 1, 1], "size": [1, 1, 1]}})"}) {
    const fs::path a = scratch("outward.png"), b = scratch("inward.png");
    const Result ra = run("render " + scene("outward", cutter) + " -o " + a.string());
    const Result rb = run("render " + scene("inward", cutter) + " -o " + b.string());
    ASSERT_EQ(ra.exitCode, 0) << ra.err;
    ASSERT_EQ(rb.exitCode, 0) << rb.err;
    EXPECT_EQ(readPng(a).pixels, readPng(b).pixels) << cutter;
  }
  const auto turned = [&](const std::string& mesh) {
    const Result r = run("info " + scene(mesh, R"({"cutout": true})"));
    EXPECT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_TRUE(j["objects"][0]["watertight"].get<bool>()) << mesh;
    return j["objects"][0]["windingReversed"].get<bool>();
  };
  EXPECT_FALSE(turned("outward"));
  EXPECT_TRUE(turned("inward"));
  EXPECT_FALSE(turned("hollow"));
}

// The cutout's wedge and the breakaway's hulls follow animated objects: an exterior cube
// moving over 2 s is cut at t = 2 as the cube placed there is, and a tetrahedron moving inside
// a cube opens the hole where it is (both were taken at the rest pose).
TEST(Cli, CutoutAndBreakawayFollowTheirAnimatedObjects) {
  const std::string cube = kData + "/meshes/cube.obj", tetra = kData + "/meshes/tetra.obj";
  const auto scene = [&](const std::string& name, const std::string& exterior,
                         const std::string& interior, const std::string& cutter) {
    const fs::path file = scratch(name + ".json");
    std::ofstream(file) << R"({"resolution": [96, 72], "samples": 1,
      "camera": {"eye": [2.5, 2, 3.5], "target": [0.8, 0.6, 0.5], "fov": 40},
      "objects": [{"name": "box", "file": ")"
                        << cube << R"(", "role": "exterior", )" << exterior << R"(},
                  {"name": "tetra", "file": ")"
                        << tetra << R"(", "role": "interior", )" << interior << R"(}],
      "cutters": )" << cutter
                        << "}";
    return file.string();
  };
  const std::string inside = R"("transform": {"translate": [0.55, 0.45, 0.3], "scale": 0.35})";
  const std::string breakaway = R"({"breakaway": {"offset": 0.1, "wallThickness": 0.05}})";
  const std::vector<std::pair<std::string, std::string>> pairs = {
      {scene("cutout-moving",
             R"("animation": [{"time": 0}, {"time": 2, "translate": [0.4, 0.3, 0]}])",
             R"("transform": {"translate": [0.95, 0.75, 0.3], "scale": 0.35})",
             R"({"cutout": true})"),
       scene("cutout-there", R"("transform": {"translate": [0.4, 0.3, 0]})",
             R"("transform": {"translate": [0.95, 0.75, 0.3], "scale": 0.35})",
             R"({"cutout": true})")},
      {scene("breakaway-moving", R"("color": [0.6, 0.65, 0.75])",
             R"("transform": {"translate": [0.15, 0.15, 0.3], "scale": 0.35},
                "animation": [{"time": 0}, {"time": 2, "translate": [0.4, 0.3, 0]}])",
             breakaway),
       scene("breakaway-there", R"("color": [0.6, 0.65, 0.75])", inside, breakaway)},
      // The default offset (5 % of the interior's size) from its size at rest, not from the
      // box its motion sweeps: the same rim as the object placed there.
      {scene("breakaway-default-moving", R"("color": [0.6, 0.65, 0.75])",
             R"("transform": {"translate": [0.15, 0.15, 0.3], "scale": 0.35},
                "animation": [{"time": 0}, {"time": 2, "translate": [0.4, 0.3, 0]}])",
             R"({"breakaway": true})"),
       scene("breakaway-default-there", R"("color": [0.6, 0.65, 0.75])", inside,
             R"({"breakaway": true})")}};
  for (const auto& [moving, there] : pairs) {
    const fs::path a = scratch("moving.png"), b = scratch("there.png"), rest = scratch("rest.png");
    const Result ra = run("render " + moving + " -o " + a.string() + " --time 2");
    const Result rb = run("render " + there + " -o " + b.string());
    const Result rr = run("render " + moving + " -o " + rest.string() + " --time 0");
    ASSERT_EQ(ra.exitCode, 0) << ra.err;
    ASSERT_EQ(rb.exitCode, 0) << rb.err;
    ASSERT_EQ(rr.exitCode, 0) << rr.err;
    // Pixels apart by more than 8 levels in a channel; the moved pose is composed in float
    // (rest transform, then the animation's), so a hull edge may round to its neighbour pixel.
    const auto apart = [](const Rgba8Image& x, const Rgba8Image& y) {
      int n = 0;
      for (std::size_t i = 0; i + 3 < x.pixels.size(); i += 4)
        for (std::size_t c = 0; c < 3; ++c)
          if (std::abs(int(x.pixels[i + c]) - int(y.pixels[i + c])) > 8) {
            ++n;
            break;
          }
      return n;
    };
    const Rgba8Image moved = readPng(a);
    EXPECT_LE(apart(moved, readPng(b)), 96 * 72 / 200) << moving;  // 0.5 %
    EXPECT_GE(apart(moved, readPng(rest)), 96 * 72 / 50) << moving << ": it should move";
  }
  const auto offsetOf = [&](const std::string& file) {
    const Result r = run("info " + file);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return nlohmann::json::parse(r.out)["resolved"]["breakaway"]["offset"].get<double>();
  };
  const double there = offsetOf(pairs[2].second);
  EXPECT_NEAR(offsetOf(pairs[2].first), there, 1e-6 * there);
}
