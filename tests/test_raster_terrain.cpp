// Raster terrain (io/raster_terrain.hpp): small GeoTIFFs written here through GDAL with known
// samples, placed through the scene's frame (offset in double, north towards −z), subsampled,
// nodata filled from the nearest valid node, reprojected node by node; every error; and the
// synthetic DEM read back equal to its noise function.
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "cutaway/core/error.hpp"
#include "cutaway/geometry/grid_lod.hpp"
#include "cutaway/io/raster_terrain.hpp"
#include "expect_error.hpp"

namespace fs = std::filesystem;
using namespace cutaway;

using test::expectError;

namespace {

class RasterTerrainTest : public ::testing::Test {
 protected:
  void SetUp() override {
    GDALAllRegister();
    dir_ = fs::temp_directory_path() /
           ("cutaway-raster-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A Float32 GeoTIFF of `width` × rows samples; an empty `crs` or `gt` leaves it out.
  fs::path tiff(const std::string& name, int width, const std::vector<float>& samples,
                std::vector<double> gt, const std::string& crs = "EPSG:27700",
                std::optional<double> nodata = {}) {
    const fs::path file = dir_ / name;
    const int height = int(samples.size()) / width;
    GDALDatasetUniquePtr d(GetGDALDriverManager()->GetDriverByName("GTiff")->Create(
        file.c_str(), width, height, 1, GDT_Float32, nullptr));
    EXPECT_EQ(d->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, width, height,
                                            const_cast<float*>(samples.data()), width, height,
                                            GDT_Float32, 0, 0, nullptr),
              CE_None);
    if (!gt.empty()) d->SetGeoTransform(gt.data());
    if (!crs.empty()) {
      OGRSpatialReference srs;
      srs.SetFromUserInput(crs.c_str());
      d->SetSpatialRef(&srs);
    }
    if (nodata) d->GetRasterBand(1)->SetNoDataValue(*nodata);
    return file;
  }

  fs::path dir_;
};

// Every triangle of the mesh, stored or implied, turns counter-clockwise seen from above.
void expectFacingUp(const Mesh& mesh) {
  for (std::size_t i = 0; i < mesh.triangleCount(); ++i) {
    const glm::uvec3 t = mesh.triangle(i);
    EXPECT_GT(
        glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x])
            .y,
        0.0f)
        << "triangle " << i;
  }
}

}  // namespace

TEST_F(RasterTerrainTest, GridNodesSitAtPixelCentresInTheSceneFrame) {
  // 4 × 3 samples of 10 m, north-west corner at (265000, 150000).
  const fs::path file =
      tiff("dem.tif", 4, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}, {265000, 10, 0, 150000, 0, -10});
  const RasterTerrain t =
      importRasterTerrain(file, {.heightScale = 2.0, .offset = {265000.0, 149900.0, 5.0}});
  EXPECT_EQ(t.columns, 4);
  EXPECT_EQ(t.rows, 3);
  EXPECT_EQ(t.crs.authority, "EPSG:27700");
  ASSERT_EQ(t.mesh.positions.size(), 12u);
  ASSERT_TRUE(t.mesh.impliedTriangles());
  EXPECT_EQ(t.mesh.triangleCount(), 2u * 3u * 2u);
  // Node (1, 2): E = 265015, N = 149975, h = 10 → x = 15, y = 2·10 − 5, z = −(75).
  EXPECT_EQ(t.mesh.positions[t.node(1, 2)], glm::vec3(15.0f, 15.0f, -75.0f));
  EXPECT_EQ(t.mesh.positions[t.node(0, 0)], glm::vec3(5.0f, -3.0f, -95.0f));
  EXPECT_EQ(t.minHeight, 1.0);
  EXPECT_EQ(t.maxHeight, 12.0);
  // Triangles face up, and so do the smooth normals of this plane-like ramp.
  expectFacingUp(t.mesh);
  for (const glm::vec3& n : t.mesh.normals) {
    EXPECT_GT(n.y, 0.0f);
    EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
  }
  // A plane h = E/10 + ... has one normal everywhere: check at an inner node against the
  // plane's gradient (heights ×2: dy/dx = 0.2, dy/dz = 0.2·4·… per 10 m = 0.8).
  const glm::vec3 expected = glm::normalize(glm::vec3(-0.2f, 1.0f, -0.8f));
  EXPECT_NEAR(glm::distance(t.mesh.normals[t.node(1, 1)], expected), 0.0f, 1e-5f);
}

// Rasters stored south-up (dy > 0) or east-to-west (dx < 0) mirror the grid: their implied
// triangles still face up, and the level of detail takes the layout.
TEST_F(RasterTerrainTest, MirroredRastersFaceUpToo) {
  for (const std::vector<double>& transform :
       {std::vector<double>{0, 1, 0, 0, 0, 1}, std::vector<double>{4, -1, 0, 3, 0, -1},
        std::vector<double>{0, 1, 0, 3, 0, -1}, std::vector<double>{4, -1, 0, 0, 0, 1}}) {
    const fs::path file = tiff("dem.tif", 4, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}, transform);
    const RasterTerrain t = importRasterTerrain(file, {});
    SCOPED_TRACE("dx " + std::to_string(transform[1]) + ", dy " + std::to_string(transform[5]));
    ASSERT_EQ(t.mesh.triangleCount(), 12u);
    expectFacingUp(t.mesh);
    EXPECT_TRUE(GridLod::build(t.mesh));
  }
}

TEST_F(RasterTerrainTest, StepTakesEveryKthSample) {
  std::vector<float> samples(5 * 5);
  for (int i = 0; i < 25; ++i) samples[std::size_t(i)] = float(i);
  const fs::path file = tiff("dem.tif", 5, samples, {0, 1, 0, 5, 0, -1});
  const RasterTerrain t = importRasterTerrain(file, {.step = 2});
  EXPECT_EQ(t.columns, 3);
  EXPECT_EQ(t.rows, 3);
  EXPECT_EQ(t.mesh.positions[t.node(2, 1)], glm::vec3(4.5f, 14.0f, -2.5f));  // sample (4, 2)
  expectError([&] { importRasterTerrain(file, {.step = 5}); }, {"dem.tif", "2 × 2", "step 5"});
}

TEST_F(RasterTerrainTest, NodataTakesTheNearestValidHeight) {
  const fs::path file = tiff("dem.tif", 4,
                             {-9999, -9999, 7, -9999,  //
                              -9999, 3, -9999, -9999,  //
                              -9999, -9999, -9999, 5},
                             {0, 1, 0, 3, 0, -1}, "EPSG:27700", -9999.0);
  const RasterTerrain t = importRasterTerrain(file);
  EXPECT_EQ(t.filledNodata, 9);
  const auto h = [&](int c, int r) { return t.mesh.positions[t.node(c, r)].y; };
  EXPECT_EQ(h(1, 0), 7.0f);  // one step from 3 (below) and from 7 (right): 7 comes first
  EXPECT_EQ(h(0, 0), 7.0f);  // two steps from both: through (1, 0)
  EXPECT_EQ(h(3, 0), 7.0f);
  EXPECT_EQ(h(3, 1), 5.0f);  // one step from 5, two from 7
  EXPECT_EQ(h(2, 2), 5.0f);
  EXPECT_EQ(h(0, 2), 3.0f);
  EXPECT_EQ(t.minHeight, 3.0);
  EXPECT_EQ(t.maxHeight, 7.0);
  const fs::path empty =
      tiff("empty.tif", 2, {-1, -1, -1, -1}, {0, 1, 0, 2, 0, -1}, "EPSG:27700", -1.0);
  expectError([&] { importRasterTerrain(empty); }, {"empty.tif", "no valid sample"});
  // `cutaway info`: a band of nodata only has no range; a file cut short is an error, not that.
  EXPECT_FALSE(describeRaster(empty).minimum.has_value());
  expectError([&] { describeRaster(fs::path(CUTAWAY_TEST_DATA) / "fuzz/raster/truncated.tif"); },
              {"truncated.tif", "cannot read band 1", "IReadBlock"});
  // A GeoTIFF cut before its georeferencing tags: GDAL's own message says why there is none.
  const fs::path whole = fs::path(empty).replace_filename("whole.tif");
  writeSyntheticDem(whole, {.min = {0.0, 0.0}, .max = {1000.0, 1000.0}, .crs = "EPSG:27700"});
  std::ifstream in(whole, std::ios::binary);
  std::string bytes(std::istreambuf_iterator<char>(in), {});
  const fs::path cut = fs::path(whole).replace_filename("cut.tif");
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, 300);
  expectError([&] { importRasterTerrain(cut); },
              {"cut.tif", "the raster has no geotransform", "IO error"});
}

TEST_F(RasterTerrainTest, ReprojectsEachNode) {
  // A raster in UTM 30N around Exmoor, placed in British National Grid.
  const fs::path file =
      tiff("utm.tif", 2, {10, 20, 30, 40}, {450000, 100, 0, 5670000, 0, -100}, "EPSG:32630");
  const RasterTerrain t =
      importRasterTerrain(file, {.targetCrs = "EPSG:27700", .offset = {265000.0, 145000.0, 0.0}});
  EXPECT_EQ(t.sceneCrs.authority, "EPSG:27700");
  OGRSpatialReference utm, bng;
  utm.SetFromUserInput("EPSG:32630");
  bng.SetFromUserInput("EPSG:27700");
  utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  bng.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> ct(OGRCreateCoordinateTransformation(&utm, &bng));
  double x = 450150, y = 5669850;  // node (1, 1)'s pixel centre
  ASSERT_TRUE(ct->Transform(1, &x, &y));
  const glm::vec3 p = t.mesh.positions[t.node(1, 1)];
  EXPECT_NEAR(p.x, x - 265000.0, 1e-3);
  EXPECT_NEAR(p.z, -(y - 145000.0), 1e-3);
  EXPECT_EQ(p.y, 40.0f);
}

TEST_F(RasterTerrainTest, ErrorsNameTheFileAndTheReason) {
  expectError([&] { importRasterTerrain(dir_ / "none.tif"); }, {"none.tif", "not found"});
  std::ofstream(dir_ / "text.tif") << "not a raster";
  expectError([&] { importRasterTerrain(dir_ / "text.tif"); },
              {"text.tif", "cannot open as a raster"});
  const fs::path plain = tiff("plain.tif", 2, {1, 2, 3, 4}, {}, "");
  expectError([&] { importRasterTerrain(plain); }, {"plain.tif", "no geotransform"});
  const fs::path rotated = tiff("rotated.tif", 2, {1, 2, 3, 4}, {0, 1, 0.2, 2, 0.1, -1});
  expectError([&] { importRasterTerrain(rotated); }, {"rotated.tif", "rotated"});
  const fs::path noCrs = tiff("nocrs.tif", 2, {1, 2, 3, 4}, {0, 1, 0, 2, 0, -1}, "");
  expectError([&] { importRasterTerrain(noCrs, {.targetCrs = "EPSG:27700"}); },
              {"nocrs.tif", "no CRS"});
  expectError([&] { importRasterTerrain(plain.parent_path() / "rotated.tif", {.step = 0}); },
              {"step"});
  const fs::path good = tiff("good.tif", 2, {1, 2, 3, 4}, {0, 1, 0, 2, 0, -1});
  expectError([&] { importRasterTerrain(good, {.targetCrs = "EPSG:999999"}); },
              {"good.tif", "unknown target CRS"});
  // Geotransforms that cannot place distinct nodes: none, or nodes beyond float's reach.
  std::ofstream(dir_ / "zero.asc") << "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 0\n"
                                      "1 2\n3 4\n";
  expectError([&] { importRasterTerrain(dir_ / "zero.asc"); }, {"zero.asc", "the cell size is 0"});
  const fs::path far = tiff("far.tif", 2, {1, 2, 3, 4}, {1e300, 1, 0, 2, 0, -1});
  expectError([&] { importRasterTerrain(far); },
              {"far.tif", "grid node (0, 0) lies", "beyond the 1e15"});
  const fs::path tiny = tiff("tiny.tif", 2, {1, 2, 3, 4}, {0, 1e-300, 0, 2, 0, -1});
  expectError([&] { importRasterTerrain(tiny); },
              {"tiny.tif", "grid node (0, 0) and grid node (1, 0) fall on one point"});
  // A header claiming 64752 × 65535 samples (34 GB of grid; fuzzing): refused before reading.
  const fs::path huge =
      fs::path(CUTAWAY_TEST_DATA) / "fuzz/raster/header-claims-64752-by-65535.tif";
  expectError([&] { importRasterTerrain(huge); },
              {"64752 × 65535 nodes is beyond the limit of 33554432", "larger \"step\""});
}

TEST_F(RasterTerrainTest, SyntheticDemReadsBackAsItsNoiseFunction) {
  const SyntheticDemOptions o{.min = {265000, 145000},
                              .max = {265400, 145300},
                              .crs = "EPSG:27700",
                              .cell = 20,
                              .base = 40,
                              .relief = 25,
                              .seed = 3};
  const fs::path file = dir_ / "synthetic.tif";
  writeSyntheticDem(file, o);
  const RasterInfo info = describeRaster(file);
  EXPECT_EQ(info.dataType, "Float32");
  EXPECT_EQ(info.width, 20);
  EXPECT_EQ(info.height, 15);
  const RasterTerrain t = importRasterTerrain(file, {.offset = {265000.0, 145000.0, 0.0}});
  EXPECT_EQ(t.columns, 20);
  EXPECT_EQ(t.rows, 15);
  EXPECT_EQ(t.crs.authority, "EPSG:27700");
  EXPECT_EQ(t.geoTransform, (std::array<double, 6>{265000, 20, 0, 145300, 0, -20}));
  for (const auto& [c, r] : {std::pair{0, 0}, {19, 14}, {7, 3}, {12, 9}}) {
    const double e = 265000 + 20 * (c + 0.5), n = 145300 - 20 * (r + 0.5);
    const glm::vec3 p = t.mesh.positions[t.node(c, r)];
    EXPECT_EQ(p.y, float(syntheticDemHeight(o, e, n))) << c << ", " << r;
    EXPECT_EQ(p.x, float(e - 265000));
    EXPECT_EQ(p.z, float(-(n - 145000)));
    EXPECT_GE(p.y, 40.0f);
    EXPECT_LE(p.y, 65.0f);
  }
  expectError(
      [&] {
        writeSyntheticDem(dir_ / "odd.tif",
                          {.min = {0, 0}, .max = {15, 20}, .crs = "EPSG:27700", .cell = 10});
      },
      {"odd.tif", "whole"});
  EXPECT_FALSE(fs::exists(dir_ / "odd.tif"));
}
