#include "cutaway/core/contained.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "cutaway/core/error.hpp"
#include "cutaway/io/gis_import.hpp"
#include "cutaway/io/mesh_import.hpp"
#include "cutaway/io/raster_terrain.hpp"
#include "cutaway/io/volume_import.hpp"
#include "expect_error.hpp"
#include "fuzz/fuzz_targets.hpp"
#include "run_command.hpp"

using namespace cutaway;

namespace {

// `read()` once in this process and once through the child.
template <class Read>
auto hereAndThere(Read&& read) {
  ::setenv("CUTAWAY_IMPORT_CONTAINED", "0", 1);
  auto here = read();
  ::unsetenv("CUTAWAY_IMPORT_CONTAINED");
  return std::pair(std::move(here), read());
}

void expectSameCrs(const GisCrs& a, const GisCrs& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.authority, b.authority);
  EXPECT_EQ(a.wkt, b.wkt);
}

void expectSameMesh(const Mesh& a, const Mesh& b) {
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.triangles, b.triangles);
  ASSERT_EQ(a.grid.has_value(), b.grid.has_value());
  if (a.grid) {
    EXPECT_EQ(a.grid->columns, b.grid->columns);
    EXPECT_EQ(a.grid->rows, b.grid->rows);
    EXPECT_EQ(a.grid->cell, b.grid->cell);
  }
  EXPECT_EQ(a.report.droppedDegenerate, b.report.droppedDegenerate);
  EXPECT_EQ(a.report.normalsComputed, b.report.normalsComputed);
  EXPECT_EQ(a.report.boundaryEdges, b.report.boundaryEdges);
  EXPECT_EQ(a.report.nonManifoldEdges, b.report.nonManifoldEdges);
  EXPECT_EQ(a.report.misorientedEdges, b.report.misorientedEdges);
  EXPECT_EQ(a.report.watertight, b.report.watertight);
}

void expectSameLayer(const GisLayerImport& a, const GisLayerImport& b) {
  EXPECT_EQ(a.layer.name, b.layer.name);
  EXPECT_EQ(a.layer.geometryType, b.layer.geometryType);
  EXPECT_EQ(a.layer.featureCount, b.layer.featureCount);
  expectSameCrs(a.layer.crs, b.layer.crs);
  ASSERT_TRUE(a.layer.extent && b.layer.extent);
  EXPECT_EQ(a.layer.extent->min, b.layer.extent->min);
  EXPECT_EQ(a.layer.extent->max, b.layer.extent->max);
  EXPECT_EQ(a.layer.fields, b.layer.fields);
  EXPECT_EQ(a.layer.fieldTypes, b.layer.fieldTypes);
  expectSameCrs(a.crs, b.crs);
  EXPECT_EQ(a.offset, b.offset);
  EXPECT_EQ(a.hasZ, b.hasZ);
  EXPECT_EQ(a.report.features, b.report.features);
  EXPECT_EQ(a.report.featuresWithoutGeometry, b.report.featuresWithoutGeometry);
  EXPECT_EQ(a.report.repeatedNodes, b.report.repeatedNodes);
  EXPECT_EQ(a.report.degenerateParts, b.report.degenerateParts);
  EXPECT_EQ(a.report.missingAttributeValues, b.report.missingAttributeValues);
  EXPECT_EQ(a.report.degenerateRings, b.report.degenerateRings);
}

ContainmentLimits limits(double seconds, std::uint64_t megabytes) {
  ContainmentLimits l;
  l.seconds = seconds;
  l.memoryBytes = megabytes << 20;
  return l;
}

// The parsers the tests run in workers, registered before the helper starts. An argument is
// a size in bytes or megabytes where one is needed.
std::string pattern(std::size_t size) {
  std::string bytes(size, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = char(i * 2654435761u >> 24);
  return bytes;
}

bool warmed = false;  // set by the warm-up, in the helper

const bool kRegistered = [] {
  registerContainedWarmUp([] { warmed = true; });
  registerContainedParser("test-warm",
                          [](std::string_view) { return std::string(warmed ? "1" : "0"); });
  registerContainedParser("test-pattern",
                          [](std::string_view a) { return pattern(std::stoul(std::string(a))); });
  registerContainedParser("test-pid", [](std::string_view) { return std::to_string(::getpid()); });
  registerContainedParser("test-error", [](std::string_view) -> std::string {
    throw Error("mesh.ply", "header line 3", "a count too large");
  });
  registerContainedParser("test-long-error", [](std::string_view) -> std::string {
    throw Error("mesh.ply", "", "a reason of 100 KB: " + std::string(100000, 'x'));
  });
  registerContainedParser("test-exception", [](std::string_view) -> std::string {
    throw std::runtime_error("vector::reserve");
  });
  registerContainedParser("test-abort", [](std::string_view) -> std::string { std::abort(); });
  registerContainedParser("test-segv", [](std::string_view) -> std::string {
    std::raise(SIGSEGV);
    return "";
  });
  registerContainedParser("test-exit", [](std::string_view) -> std::string { ::_exit(3); });
  registerContainedParser("test-sleep", [](std::string_view) -> std::string {
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
  });
  registerContainedParser("test-allocate", [](std::string_view a) {
    // Megabytes touched page by page, one byte of them handed back.
    const std::string big(std::size_t(std::stoul(std::string(a))) << 20, 'y');
    return big.substr(0, 1);
  });
  return true;
}();

ContainedReply run(const std::string& id, const std::string& arguments = "",
                   const ContainmentLimits& l = limits(60, 64)) {
  return runContained("input.bin", "the test parser", id, arguments, l);
}

void expectContainedError(const std::string& id, const std::string& arguments,
                          const ContainmentLimits& l, std::initializer_list<std::string> parts) {
  test::expectError([&] { run(id, arguments, l); }, parts);
}

}  // namespace

TEST(Contained, TheWorkersBytesComeBackWhole) {
  // 48 MB with a pattern: more than a socket or a page holds, every byte checked.
  const ContainedReply reply = run("test-pattern", std::to_string(48u << 20), limits(60, 1024));
  ASSERT_EQ(reply.bytes().size(), 48u << 20);
  EXPECT_TRUE(reply.bytes() == pattern(48u << 20));
  // An empty result is a result.
  EXPECT_EQ(run("test-pattern", "0").bytes().size(), 0u);
}

TEST(Contained, TheHelpersWarmUpIsEveryWorkersAndNotTheProgramsOwn) {
  EXPECT_EQ(run("test-warm").bytes(), "1");
  EXPECT_FALSE(warmed);
}

TEST(Contained, EachFileHasAFreshWorker) {
  const std::string first(run("test-pid").bytes()), second(run("test-pid").bytes());
  EXPECT_NE(first, std::to_string(::getpid()));
  EXPECT_NE(first, second);
}

TEST(Contained, AnErrorTheWorkerThrowsComesBackAsThrown) {
  try {
    run("test-error");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), "mesh.ply");
    EXPECT_EQ(e.place(), "header line 3");
    EXPECT_EQ(e.reason(), "a count too large");
  }
  expectContainedError("test-exception", "", limits(60, 64),
                       {"input.bin: the test parser failed on this file: vector::reserve"});
  // A reason beyond what one message holds comes back cut, not lost.
  try {
    run("test-long-error");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.reason().size(), 4096u);
    EXPECT_EQ(e.reason().rfind("a reason of 100 KB: xxx", 0), 0u);
  }
  expectContainedError("test-unknown", "", limits(60, 64),
                       {"failed on this file: no parser \"test-unknown\""});
}

TEST(Contained, ACrashIsAnErrorNamingTheFileAndTheSignal) {
  expectContainedError("test-abort", "", limits(60, 64),
                       {"input.bin: the test parser crashed on this file (Aborted)"});
  expectContainedError("test-segv", "", limits(60, 64),
                       {"input.bin: the test parser crashed on this file (Segmentation fault)"});
  expectContainedError("test-exit", "", limits(60, 64), {"crashed on this file (exit status 3)"});
  // The next file goes on as before.
  EXPECT_EQ(run("test-pattern", "5").bytes(), pattern(5));
}

TEST(Contained, TheWorkerLeavesWhatTheProgramBufferedToTheProgram) {
  // Output buffered before the helper starts or a worker runs is written once, by the
  // program: helper and worker leave by _exit, which flushes no stream and runs no exit
  // handler of the program's.
  const std::string path = ::testing::TempDir() + "cutaway-contained-buffered.txt";
  std::FILE* f = std::fopen(path.c_str(), "w");
  ASSERT_TRUE(f);
  std::fputs("written once", f);
  run("test-pattern", "4");
  EXPECT_THROW(run("test-error"), Error);
  std::fclose(f);
  std::FILE* in = std::fopen(path.c_str(), "r");
  char text[64] = {};
  const std::size_t n = std::fread(text, 1, sizeof text - 1, in);
  std::fclose(in);
  std::remove(path.c_str());
  EXPECT_EQ(std::string(text, n), "written once");
}

TEST(Contained, AWorkerPastItsTimeIsStopped) {
  const auto start = std::chrono::steady_clock::now();
  expectContainedError("test-sleep", "", limits(0.5, 64),
                       {"input.bin: the test parser took longer than 0.5 s on this file"});
  const double took =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(took, 0.5);
  EXPECT_LT(took, 10.0);  // a bound for a starved machine, not a speed goal
}

TEST(Contained, AWorkerPastItsMemoryIsStopped) {
  // 1 GB under a 64 MB limit. AddressSanitizer's allocator dies on a failed mapping rather
  // than throwing, which is a crash.
  if (test::kAddressSanitizer)
    expectContainedError("test-allocate", "1024", limits(60, 64),
                         {"input.bin: the test parser crashed"});
  else
    expectContainedError(
        "test-allocate", "1024", limits(60, 64),
        {"input.bin: the test parser needed more than 64 MB of memory for this file"});
  // Within the limit it runs.
  EXPECT_EQ(run("test-allocate", "32").bytes(), "y");
}

TEST(Contained, BadLimitsInTheEnvironmentAreRefused) {
  ::setenv("CUTAWAY_IMPORT_SECONDS", "-3", 1);
  // The variable is named in the reason too: a scene loader puts its own file and place first.
  test::expectError([] { importLimits(); },
                    {"the environment variable CUTAWAY_IMPORT_SECONDS must be a number in (0, "
                     "86400], not \"-3\""});
  ::setenv("CUTAWAY_IMPORT_SECONDS", "2.5", 1);
  ::setenv("CUTAWAY_IMPORT_MEMORY_MB", "12x", 1);
  test::expectError([] { importLimits(); }, {"CUTAWAY_IMPORT_MEMORY_MB", "12x"});
  ::setenv("CUTAWAY_IMPORT_MEMORY_MB", "100", 1);
  const ContainmentLimits l = importLimits();
  EXPECT_EQ(l.seconds, 2.5);
  EXPECT_EQ(l.memoryBytes, 100u << 20);
  ::unsetenv("CUTAWAY_IMPORT_SECONDS");
  ::unsetenv("CUTAWAY_IMPORT_MEMORY_MB");
  EXPECT_EQ(importLimits().seconds, 300.0);
  // Containment is 0 or 1: "maybe" was taken as 1 without a word.
  ::setenv("CUTAWAY_IMPORT_CONTAINED", "maybe", 1);
  test::expectError([] { importsContained(); },
                    {"the environment variable CUTAWAY_IMPORT_CONTAINED must be 0 or 1, not "
                     "\"maybe\""});
  ::setenv("CUTAWAY_IMPORT_CONTAINED", "0", 1);
  EXPECT_FALSE(importsContained());
  ::unsetenv("CUTAWAY_IMPORT_CONTAINED");
  EXPECT_TRUE(importsContained());
}

// The contained import hands back exactly what the in-process import builds: names, places,
// every vertex, normal and index, the report and the colour.
TEST(Contained, AMeshImportedInTheChildIsTheMeshImportedHere) {
  for (const char* file :
       {"/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
        CUTAWAY_SOURCE_DIR "/examples/data/hollow-box.obj"}) {
    SCOPED_TRACE(file);
    const auto [here, there] = hereAndThere([&] { return importMeshNodes(file); });
    ASSERT_EQ(here.size(), there.size());
    for (std::size_t i = 0; i < here.size(); ++i) {
      EXPECT_EQ(here[i].name, there[i].name);
      EXPECT_EQ(here[i].id, there[i].id);
      EXPECT_EQ(here[i].color, there[i].color);
      expectSameMesh(here[i].mesh, there[i].mesh);
    }
  }
}

// The same for GDAL's readers: a layer's lines and polygons with their attributes, CRS, extent
// and report; a raster's terrain and description.
TEST(Contained, GisLayersAndRastersReadInTheChildAreTheOnesReadHere) {
  const std::string ss = "/usr/share/plplot5.15.0/ss/";
  GisImportOptions options;
  options.attributes = {"FEATCODE"};
  options.targetCrs = "EPSG:27700";
  options.offset = {264000.0, 144000.0, 0.0};
  const auto [lines, linesThere] =
      hereAndThere([&] { return importGisLines(ss + "ss64ne_Road_Centreline.shp", options); });
  const auto [areas, areasThere] =
      hereAndThere([&] { return importGisPolygons(ss + "ss64ne_Building_Area.shp", options); });
  ASSERT_GT(lines.polylines.size(), 10u);
  ASSERT_GT(areas.polygons.size(), 10u);
  expectSameLayer(lines, linesThere);
  expectSameLayer(areas, areasThere);
  ASSERT_EQ(lines.polylines.size(), linesThere.polylines.size());
  for (std::size_t i = 0; i < lines.polylines.size(); ++i) {
    EXPECT_EQ(lines.polylines[i].featureId, linesThere.polylines[i].featureId);
    EXPECT_EQ(lines.polylines[i].part, linesThere.polylines[i].part);
    EXPECT_EQ(lines.polylines[i].points, linesThere.polylines[i].points);
    EXPECT_EQ(lines.polylines[i].attributes, linesThere.polylines[i].attributes);
  }
  ASSERT_EQ(areas.polygons.size(), areasThere.polygons.size());
  for (std::size_t i = 0; i < areas.polygons.size(); ++i) {
    EXPECT_EQ(areas.polygons[i].featureId, areasThere.polygons[i].featureId);
    EXPECT_EQ(areas.polygons[i].part, areasThere.polygons[i].part);
    EXPECT_EQ(areas.polygons[i].outer, areasThere.polygons[i].outer);
    EXPECT_EQ(areas.polygons[i].holes, areasThere.polygons[i].holes);
    EXPECT_EQ(areas.polygons[i].attributes, areasThere.polygons[i].attributes);
  }
  const auto [layers, layersThere] =
      hereAndThere([&] { return listGisLayers(ss + "ss64ne_Water_Line.shp"); });
  ASSERT_EQ(layers.size(), 1u);
  ASSERT_EQ(layersThere.size(), 1u);
  EXPECT_EQ(layers[0].name, layersThere[0].name);
  EXPECT_EQ(layers[0].fields, layersThere[0].fields);

  const std::string dem = CUTAWAY_SOURCE_DIR "/examples/data/ss64ne-dem.tif";
  RasterTerrainOptions rasterOptions;
  rasterOptions.step = 2;
  rasterOptions.offset = {264000.0, 144000.0, 0.0};
  const auto [terrain, terrainThere] =
      hereAndThere([&] { return importRasterTerrain(dem, rasterOptions); });
  expectSameMesh(terrain.mesh, terrainThere.mesh);
  EXPECT_EQ(terrain.columns, terrainThere.columns);
  EXPECT_EQ(terrain.rows, terrainThere.rows);
  expectSameCrs(terrain.crs, terrainThere.crs);
  expectSameCrs(terrain.sceneCrs, terrainThere.sceneCrs);
  EXPECT_EQ(terrain.geoTransform, terrainThere.geoTransform);
  EXPECT_EQ(terrain.filledNodata, terrainThere.filledNodata);
  EXPECT_EQ(terrain.minHeight, terrainThere.minHeight);
  EXPECT_EQ(terrain.maxHeight, terrainThere.maxHeight);
  const auto [info, infoThere] = hereAndThere([&] { return describeRaster(dem); });
  EXPECT_EQ(info.driver, infoThere.driver);
  EXPECT_EQ(info.width, infoThere.width);
  EXPECT_EQ(info.height, infoThere.height);
  EXPECT_EQ(info.bands, infoThere.bands);
  EXPECT_EQ(info.dataType, infoThere.dataType);
  expectSameCrs(info.crs, infoThere.crs);
  EXPECT_EQ(info.geoTransform, infoThere.geoTransform);
  EXPECT_EQ(info.nodata, infoThere.nodata);
  EXPECT_EQ(info.minimum, infoThere.minimum);
  EXPECT_EQ(info.maximum, infoThere.maximum);
  EXPECT_TRUE(isRaster(dem));
  EXPECT_FALSE(isRaster(ss + "ss64ne_Water_Line.shp"));
}

// GDCM reads a DICOM series in a worker: two slices (the fuzz corpus's seed, split into its
// files), rescaled by slope 2 and intercept −1024, are the same volume read here and there.
TEST(Contained, ADicomSeriesReadInTheChildIsTheOneReadHere) {
  std::ifstream in(CUTAWAY_TEST_DATA "/fuzz/volume-dicom/valid-two-slices-explicit",
                   std::ios::binary);
  const std::string seed{std::istreambuf_iterator<char>(in), {}};
  const std::size_t split = seed.find(fuzz::kPartSeparator);
  ASSERT_NE(split, std::string::npos);
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("cutaway-dicom-" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "1.dcm", std::ios::binary) << seed.substr(0, split);
  std::ofstream(folder / "2.dcm", std::ios::binary)
      << seed.substr(split + fuzz::kPartSeparator.size());
  const auto [here, there] = hereAndThere([&] { return importVolume(folder); });
  std::filesystem::remove_all(folder);
  EXPECT_EQ(here.dims, glm::ivec3(4, 3, 2));
  ASSERT_EQ(here.values.size(), 24u);
  EXPECT_EQ(here.values[1], 2.0f * 1.0f - 1024.0f);
  EXPECT_EQ(here.dims, there.dims);
  EXPECT_EQ(here.values, there.values);
  EXPECT_EQ(here.indexToWorld, there.indexToWorld);
  EXPECT_EQ(here.voxelType, there.voxelType);
  EXPECT_EQ(here.minValue, there.minValue);
  EXPECT_EQ(here.maxValue, there.maxValue);
}

// The helper killed between two files (by the user, or the kernel out of memory): the next
// file starts a new one and is read.
TEST(Contained, AKilledHelperIsStartedAgain) {
  run("test-pattern", "3");  // the helper is running
  std::vector<pid_t> children;  // this process's, from /proc/PID/stat's ppid
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(entry.path() / "stat");
    std::string line;
    if (!std::getline(stat, line)) continue;
    const std::size_t close = line.rfind(')');  // the name may hold spaces and parentheses
    std::istringstream rest(close == std::string::npos ? "" : line.substr(close + 2));
    char state = 0;
    pid_t parent = 0;
    if (rest >> state >> parent && parent == ::getpid()) children.push_back(pid_t(std::stol(name)));
  }
  ASSERT_FALSE(children.empty());
  for (const pid_t pid : children) ::kill(pid, SIGKILL);
  // Dead (a zombie, its socket closed), and left for the library to reap.
  for (const pid_t pid : children)
    for (int i = 0; i < 500; ++i) {
      std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
      std::string line;
      std::getline(stat, line);
      const std::size_t close = line.rfind(')');
      if (close == std::string::npos || line.substr(close + 2, 1) == "Z") break;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  EXPECT_EQ(run("test-pattern", "6").bytes(), pattern(6));
}
