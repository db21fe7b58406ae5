// GIS vector import through GDAL/OGR (Konev18 §5's input: pipes as attributed polylines,
// shafts as points): GeoJSON written here with known coordinates and attributes, the offset
// arithmetic in double precision, reprojection against the projection's natural origin, every
// error case, and real Ordnance Survey layers in British National Grid from libplplot-data.
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "cutaway/core/error.hpp"
#include "cutaway/io/gis_import.hpp"
#include "expect_error.hpp"

namespace fs = std::filesystem;
using namespace cutaway;

using test::expectError;

namespace {

const fs::path kOsData = "/usr/share/plplot5.15.0/ss";  // libplplot-data, scripts/setup-deps

class GisImportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("cutaway-gis-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& text) {
    const fs::path file = dir_ / name;
    std::ofstream(file) << text;
    return file;
  }

  // A GeoJSON FeatureCollection; `crs` an EPSG code for the (2008) "crs" member, 0 = none
  // (GeoJSON's default, WGS 84 longitude/latitude).
  fs::path geojson(const std::string& name, const std::string& features, int crs = 0) {
    std::string text = R"({"type": "FeatureCollection", )";
    if (crs)
      text += R"("crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::)" +
              std::to_string(crs) + R"("}}, )";
    return write(name, text + R"("features": [)" + features + "]}");
  }

  static std::string feature(const std::string& geometry, const std::string& properties) {
    return R"({"type": "Feature", "properties": {)" + properties + R"(}, "geometry": )" + geometry +
           "}";
  }

  fs::path dir_;
};

}  // namespace

TEST_F(GisImportTest, LineStringsAndMultiLineStringsWithAttributes) {
  const fs::path file =
      geojson("pipes.geojson",
              feature(R"({"type": "LineString", "coordinates": [[0, 0], [10, 0], [10, 5]]})",
                      R"("radius": 0.5, "water_level": 0.25, "name": "a")") +
                  "," +
                  feature(R"({"type": "MultiLineString", "coordinates": [[[1, 1], [2, 2]],
                     [[3, 3], [4, 3], [5, 4]]]})",
                          R"("radius": 1, "water_level": null, "name": "b")"));
  const GisLines lines = importGisLines(file, {.attributes = {"radius", "water_level"}});
  EXPECT_FALSE(lines.hasZ);
  EXPECT_EQ(lines.layer.featureCount, 2);
  EXPECT_EQ(lines.crs.authority,
            "EPSG:4326");  // GeoJSON's default CRS (RFC 7946), in x = lon order
  ASSERT_EQ(lines.polylines.size(), 3u);
  const GisPolyline& a = lines.polylines[0];
  EXPECT_EQ(a.part, 0);
  ASSERT_EQ(a.points.size(), 3u);
  EXPECT_EQ(a.points[1], glm::vec3(10, 0, 0));
  EXPECT_EQ(a.points[2], glm::vec3(10, 5, 0));
  EXPECT_EQ(a.attributes, (std::vector<double>{0.5, 0.25}));
  // The two parts of the MultiLineString share their feature's id and attributes.
  const GisPolyline& b0 = lines.polylines[1];
  const GisPolyline& b1 = lines.polylines[2];
  EXPECT_EQ(b0.featureId, b1.featureId);
  EXPECT_NE(b0.featureId, a.featureId);
  EXPECT_EQ(b0.part, 0);
  EXPECT_EQ(b1.part, 1);
  EXPECT_EQ(b1.points, (std::vector<glm::vec3>{{3, 3, 0}, {4, 3, 0}, {5, 4, 0}}));
  EXPECT_EQ(b0.attributes[0], 1.0);
  EXPECT_TRUE(std::isnan(b1.attributes[1]));  // a null value is NaN and counted
  EXPECT_EQ(lines.report.missingAttributeValues, 1);
  EXPECT_EQ(lines.report.features, 2);
  ASSERT_TRUE(lines.layer.extent);
  EXPECT_EQ(lines.layer.extent->min, glm::dvec2(0, 0));
  EXPECT_EQ(lines.layer.extent->max, glm::dvec2(10, 5));
}

TEST_F(GisImportTest, ThreeDimensionalNodesKeepTheirHeights) {
  const fs::path file = geojson(
      "pipes3d.geojson",
      feature(R"({"type": "LineString", "coordinates": [[0, 0, -2.5], [4, 0, -3], [4, 0, -7]]})",
              R"("radius": 0.3)") +
          "," +
          feature(R"({"type": "MultiLineString", "coordinates": [[[0, 1, -1], [0, 2, -1.5]]]})",
                  R"("radius": 0.2)"));
  const GisLines lines = importGisLines(file, {.attributes = {"radius"}});
  EXPECT_TRUE(lines.hasZ);
  ASSERT_EQ(lines.polylines.size(), 2u);
  // Same x, y but different heights: a vertical segment, not a repeated node.
  EXPECT_EQ(lines.polylines[0].points,
            (std::vector<glm::vec3>{{0, 0, -2.5f}, {4, 0, -3}, {4, 0, -7}}));
  EXPECT_EQ(lines.polylines[1].points, (std::vector<glm::vec3>{{0, 1, -1}, {0, 2, -1.5f}}));
  EXPECT_EQ(lines.report.repeatedNodes, 0);
}

// British National Grid coordinates are ~10⁵ m, where float's spacing is 1/32 m: the offset
// must be subtracted in double before the conversion to float.
TEST_F(GisImportTest, OffsetIsSubtractedInDoubleBeforeFloat) {
  const fs::path file = geojson("bng.geojson",
                                feature(R"({"type": "LineString", "coordinates":
                 [[465123.25, 164321.75, 12.5], [465200.3, 164400.7, 11.0]]})",
                                        R"("radius": 0.4)"),
                                27700);
  const GisLines lines = importGisLines(file, {.offset = {465000.0, 164000.0, 10.0}});
  EXPECT_EQ(lines.crs.authority, "EPSG:27700");
  EXPECT_EQ(lines.offset, glm::dvec3(465000.0, 164000.0, 10.0));
  ASSERT_EQ(lines.polylines.size(), 1u);
  const std::vector<glm::vec3>& p = lines.polylines[0].points;
  EXPECT_EQ(p[0], glm::vec3(123.25f, 321.75f, 2.5f));
  // 465200.3 is not a multiple of 1/32: rounding it to float first would be off by up to
  // 1/64 m; subtracting in double first leaves float's rounding of 200.3 and 400.7
  // (half a float ulp: 2⁻¹⁷ m and 2⁻¹⁶ m ≈ 1.5e-5 m).
  EXPECT_EQ(p[1].x, float(465200.3 - 465000.0));
  EXPECT_EQ(p[1].y, float(164400.7 - 164000.0));
  EXPECT_NE(p[1].x, float(465200.3) - 465000.0f);
  EXPECT_NEAR(p[1].x, 200.3, 1.6e-5);
  EXPECT_NEAR(p[1].y, 400.7, 1.6e-5);
}

// Reprojection checked against a closed form: in OSGB 1936 geographic coordinates (EPSG:4277,
// the datum British National Grid is defined on) the projection's true origin 2° W, 49° N
// maps to its false origin (400000, −100000) m in EPSG:27700.
TEST_F(GisImportTest, ReprojectsToTheTargetCrs) {
  const fs::path file =
      geojson("osgb36.geojson",
              feature(R"({"type": "Point", "coordinates": [-2.0, 49.0]})", R"("depth": 3)"), 4277);
  const GisPoints points = importGisPoints(
      file,
      {.attributes = {"depth"}, .targetCrs = "EPSG:27700", .offset = {400000.0, -100000.0, 0.0}});
  EXPECT_EQ(points.layer.crs.authority, "EPSG:4277");
  EXPECT_EQ(points.crs.authority, "EPSG:27700");
  ASSERT_EQ(points.points.size(), 1u);
  EXPECT_NEAR(points.points[0].position.x, 0.0, 1e-3);
  EXPECT_NEAR(points.points[0].position.y, 0.0, 1e-3);
  EXPECT_EQ(points.points[0].attributes, std::vector<double>{3.0});
}

TEST_F(GisImportTest, RepeatedNodesAndZeroLengthPartsAreDroppedAndCounted) {
  const fs::path file = geojson(
      "repeated.geojson",
      feature(
          R"({"type": "LineString", "coordinates": [[0, 0], [0, 0], [1, 0], [1, 0], [1, 0], [2, 1]]})",
          "") +
          "," + feature(R"({"type": "LineString", "coordinates": [[5, 5], [5, 5]]})", "") + "," +
          feature("null", ""));
  const GisLines lines = importGisLines(file);
  ASSERT_EQ(lines.polylines.size(), 1u);
  EXPECT_EQ(lines.polylines[0].points, (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {2, 1, 0}}));
  EXPECT_EQ(lines.report.repeatedNodes, 4);  // 3 in the first line, 1 in the second
  EXPECT_EQ(lines.report.degenerateParts, 1);
  EXPECT_EQ(lines.report.featuresWithoutGeometry, 1);
  EXPECT_EQ(lines.report.features, 3);
}

TEST_F(GisImportTest, PointLayerForShafts) {
  const fs::path file = geojson(
      "shafts.geojson",
      feature(R"({"type": "Point", "coordinates": [465010.5, 164020.25, 40]})",
              R"("depth": 4.5, "water_level": 1)") +
          "," +
          feature(
              R"({"type": "MultiPoint", "coordinates": [[465001, 164002, 41], [465003, 164004, 42]]})",
              R"("depth": 3, "water_level": 0.5)"),
      27700);
  const GisPoints shafts = importGisPoints(
      file, {.attributes = {"water_level", "depth"}, .offset = {465000.0, 164000.0, 40.0}});
  EXPECT_TRUE(shafts.hasZ);
  ASSERT_EQ(shafts.points.size(), 3u);
  EXPECT_EQ(shafts.points[0].position, glm::vec3(10.5f, 20.25f, 0.0f));
  EXPECT_EQ(shafts.points[0].attributes, (std::vector<double>{1.0, 4.5}));
  EXPECT_EQ(shafts.points[2].position, glm::vec3(3, 4, 2));
  EXPECT_EQ(shafts.points[2].part, 1);
  EXPECT_EQ(shafts.points[1].featureId, shafts.points[2].featureId);
}

TEST_F(GisImportTest, ListsLayers) {
  const fs::path file = geojson(
      "list.geojson",
      feature(R"({"type": "LineString", "coordinates": [[0, 0], [1, 1]]})", R"("radius": 1)"),
      27700);
  const std::vector<GisLayerInfo> layers = listGisLayers(file);
  ASSERT_EQ(layers.size(), 1u);
  EXPECT_EQ(layers[0].featureCount, 1);
  EXPECT_EQ(layers[0].crs.authority, "EPSG:27700");
  EXPECT_EQ(layers[0].fields, std::vector<std::string>{"radius"});
  EXPECT_EQ(layers[0].geometryType, "Line String");
}

// A GeoPackage written here through OGR with two layers, as a utility would deliver a network:
// "sewers" (3-D MultiLineStrings) and "shafts" (3-D points) in ETRS89 / UTM 32N (EPSG:25832,
// Konev18's Cologne). UTM northings of 5.6·10⁶ m have a float spacing of 0.5 m, so the offset
// is what keeps 5645678.25 at 678.25.
TEST_F(GisImportTest, GeoPackageLayersByName) {
  GDALAllRegister();
  const fs::path file = dir_ / "network.gpkg";
  {
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
    ASSERT_NE(driver, nullptr);
    GDALDatasetUniquePtr dataset(driver->Create(file.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    ASSERT_TRUE(dataset);
    OGRSpatialReference utm;
    ASSERT_EQ(utm.importFromEPSG(25832), OGRERR_NONE);
    auto addLayer = [&](const char* name, OGRwkbGeometryType type, const char* wkt) {
      OGRLayer* layer = dataset->CreateLayer(name, &utm, type, nullptr);
      ASSERT_NE(layer, nullptr);
      OGRFieldDefn radius("radius", OFTReal);
      ASSERT_EQ(layer->CreateField(&radius), OGRERR_NONE);
      OGRFeature feature(layer->GetLayerDefn());
      feature.SetField("radius", 0.6);
      OGRGeometry* geometry = nullptr;
      ASSERT_EQ(OGRGeometryFactory::createFromWkt(wkt, &utm, &geometry), OGRERR_NONE);
      feature.SetGeometryDirectly(geometry);
      ASSERT_EQ(layer->CreateFeature(&feature), OGRERR_NONE);
    };
    addLayer("sewers", wkbMultiLineString25D,
             "MULTILINESTRING Z ((356789.5 5645678.25 48,356799.5 5645678.25 47.5))");
    addLayer("shafts", wkbPoint25D, "POINT Z (356789.5 5645678.25 50)");
  }
  const GisImportOptions utmOffset{.offset = {356000.0, 5645000.0, 0.0}};
  expectError([&] { importGisLines(file); }, {"network.gpkg", "2 layers", "sewers", "name one"});
  GisImportOptions options = utmOffset;
  options.layer = "sewers";
  options.attributes = {"radius"};
  const GisLines sewers = importGisLines(file, options);
  EXPECT_EQ(sewers.crs.authority, "EPSG:25832");
  EXPECT_TRUE(sewers.hasZ);
  ASSERT_EQ(sewers.polylines.size(), 1u);
  EXPECT_EQ(sewers.polylines[0].points,
            (std::vector<glm::vec3>{{789.5f, 678.25f, 48.0f}, {799.5f, 678.25f, 47.5f}}));
  EXPECT_EQ(sewers.polylines[0].attributes, std::vector<double>{0.6});
  options.layer = "shafts";
  const GisPoints shafts = importGisPoints(file, options);
  ASSERT_EQ(shafts.points.size(), 1u);
  EXPECT_EQ(shafts.points[0].position, glm::vec3(789.5f, 678.25f, 50.0f));
  expectError([&] { importGisLines(file, options); },
              {"network.gpkg", "layer shafts", "Point", "not lines"});
  EXPECT_EQ(listGisLayers(file).size(), 2u);
}

// ---- errors: file, place (layer / feature) and reason -----------------------------------

TEST_F(GisImportTest, ErrorsNameTheFileThePlaceAndTheReason) {
  const std::string line = feature(R"({"type": "LineString", "coordinates": [[0, 0], [1, 1]]})",
                                   R"("radius": 1, "name": "x")");
  const fs::path lines = geojson("lines.geojson", line);
  const fs::path points = geojson(
      "points.geojson", feature(R"({"type": "Point", "coordinates": [0, 0]})", R"("depth": 1)"));
  const fs::path mixed = geojson(
      "mixed.geojson",
      line + "," +
          feature(R"({"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [1, 1], [0, 0]]]})",
                  R"("radius": 2, "name": "y")"));
  const fs::path empty = geojson("empty.geojson", "");
  const fs::path garbage = write("garbage.geojson", "{ this is not json");
  // A CSV layer with a WKT geometry column has no CRS.
  const fs::path noCrs = write("nocrs.csv", "WKT,radius\n\"LINESTRING (0 0,1 1)\",1\n");

  expectError([&] { importGisLines(dir_ / "missing.shp"); }, {"missing.shp", "not found"});
  expectError([&] { importGisLines(garbage); }, {"garbage.geojson", "cannot open"});
  expectError([&] { importGisLines(lines, {.layer = "sewers"}); },
              {"lines.geojson", "layer sewers", "no such layer", "lines"});
  expectError([&] { importGisLines(points); },
              {"points.geojson", "layer points", "Point", "not lines"});
  expectError([&] { importGisPoints(lines); }, {"lines.geojson", "Line String", "not points"});
  expectError([&] { importGisLines(mixed); },
              {"mixed.geojson", "layer mixed, feature 1", "POLYGON", "not a line"});
  expectError([&] { importGisLines(empty); }, {"empty.geojson", "layer empty", "empty"});
  expectError(
      [&] {
        importGisLines(lines, {.attributes = {"radius", "diameter"}});
      },
      {"lines.geojson", "layer lines", "\"diameter\"", "fields: radius, name"});
  expectError([&] { importGisLines(lines, {.attributes = {"name"}}); },
              {"lines.geojson", "\"name\"", "String", "not numbers"});
  expectError([&] { importGisLines(noCrs, {.targetCrs = "EPSG:27700"}); },
              {"nocrs.csv", "layer nocrs", "no CRS", "EPSG:27700"});
  expectError([&] { importGisLines(lines, {.targetCrs = "EPSG:999999"}); },
              {"lines.geojson", "unknown target CRS \"EPSG:999999\""});
  // Latitude 95° exists in no CRS: PROJ refuses it, and the error names the feature.
  const fs::path pole = geojson(
      "pole.geojson", feature(R"({"type": "Point", "coordinates": [0, 95]})", R"("depth": 1)"));
  expectError([&] { importGisPoints(pole, {.targetCrs = "EPSG:27700"}); },
              {"pole.geojson", "layer pole, feature 0", "cannot transform (0.000000, 95.000000)"});
  // Without reprojection a layer without CRS is fine.
  EXPECT_EQ(importGisLines(noCrs).polylines.size(), 1u);
  EXPECT_FALSE(importGisLines(noCrs).crs.known());
}

// ---- real data: Ordnance Survey OpenData tile SS64NE (libplplot-data) --------------------

TEST_F(GisImportTest, ReadsOrdnanceSurveyShapefilesInBritishNationalGrid) {
  for (const char* name : {"ss64ne_Water_Line.shp", "ss64ne_Road_Centreline.shp"}) {
    const fs::path file = kOsData / name;
    ASSERT_TRUE(fs::exists(file)) << file << " is missing: run scripts/setup-deps";
    const GisLayerInfo info = listGisLayers(file).at(0);
    ASSERT_TRUE(info.extent) << name;
    // The offset: the tile's south-west corner, rounded to whole metres.
    const glm::dvec3 offset(std::floor(info.extent->min.x), std::floor(info.extent->min.y), 0.0);
    const GisLines lines = importGisLines(file, {.offset = offset});
    EXPECT_EQ(lines.crs.authority, "EPSG:27700") << name;
    EXPECT_NE(lines.crs.name.find("British National Grid"), std::string::npos) << lines.crs.name;
    EXPECT_GT(lines.polylines.size(), 10u) << name;
    // SS64NE: the 5 km square with south-west corner (265000, 145000).
    EXPECT_GE(info.extent->min.x, 264000.0);
    EXPECT_LE(info.extent->max.x, 271000.0);
    EXPECT_GE(info.extent->min.y, 144000.0);
    EXPECT_LE(info.extent->max.y, 151000.0);
    // Every node inside the extent: coordinates < 10⁴ m after the offset, so float keeps
    // them to 1e-3 m.
    for (const GisPolyline& p : lines.polylines) {
      ASSERT_GE(p.points.size(), 2u);
      for (const glm::vec3& q : p.points) {
        EXPECT_GE(q.x + offset.x, info.extent->min.x - 1e-3) << name << " feature " << p.featureId;
        EXPECT_LE(q.x + offset.x, info.extent->max.x + 1e-3) << name << " feature " << p.featureId;
        EXPECT_GE(q.y + offset.y, info.extent->min.y - 1e-3) << name << " feature " << p.featureId;
        EXPECT_LE(q.y + offset.y, info.extent->max.y + 1e-3) << name << " feature " << p.featureId;
      }
    }
  }
}

// A shapefile cut short (a copy interrupted, a disk full) is an error naming the first feature
// GDAL could not read, not a network that silently lost its second half.
TEST_F(GisImportTest, ATruncatedShapefileIsAnError) {
  for (const char* suffix : {".shp", ".shx", ".dbf", ".prj"})
    fs::copy_file(kOsData / (std::string("ss64ne_Road_Centreline") + suffix),
                  dir_ / (std::string("roads") + suffix));
  const std::size_t whole = importGisLines(dir_ / "roads.shp").polylines.size();
  ASSERT_GT(whole, 100u);
  fs::resize_file(dir_ / "roads.shp", fs::file_size(dir_ / "roads.shp") / 2);
  expectError([&] { importGisLines(dir_ / "roads.shp"); },
              {"roads.shp: layer roads, feature ",
               "GDAL could not read it (the file is truncated or damaged)"});
}

TEST_F(GisImportTest, PolygonsWithHolesForFootprints) {
  const fs::path file = geojson("buildings.geojson",
                                feature(R"({"type": "Polygon", "coordinates": [
                   [[0, 0], [10, 0], [10, 0], [10, 8], [0, 8], [0, 0]],
                   [[2, 2], [4, 2], [4, 4], [2, 4], [2, 2]],
                   [[6, 6], [7, 6], [6, 6]]]})",
                                        R"("height": 12)") +
                                    "," +
                                    feature(R"({"type": "MultiPolygon", "coordinates": [
                   [[[20, 0, 5], [24, 0, 5], [24, 3, 5], [20, 0, 5]]],
                   [[[30, 0], [31, 1], [32, 2], [30, 0]]]]})",
                                            R"("height": null)"),
                                27700);
  const GisPolygons p =
      importGisPolygons(file, {.attributes = {"height"}, .offset = {0.0, 0.0, 1.0}});
  EXPECT_TRUE(p.hasZ);
  EXPECT_EQ(p.crs.authority, "EPSG:27700");
  ASSERT_EQ(p.polygons.size(), 2u);
  const GisPolygon& a = p.polygons[0];
  // The closing node and the repeated (10, 0) are gone; the sliver hole is dropped.
  EXPECT_EQ(a.outer, (std::vector<glm::vec3>{{0, 0, -1}, {10, 0, -1}, {10, 8, -1}, {0, 8, -1}}));
  ASSERT_EQ(a.holes.size(), 1u);
  EXPECT_EQ(a.holes[0].size(), 4u);
  EXPECT_EQ(a.attributes, std::vector<double>{12});
  const GisPolygon& b = p.polygons[1];
  EXPECT_EQ(b.part, 0);
  EXPECT_EQ(b.outer, (std::vector<glm::vec3>{{20, 0, 4}, {24, 0, 4}, {24, 3, 4}}));
  EXPECT_TRUE(std::isnan(b.attributes[0]));
  EXPECT_EQ(p.report.repeatedNodes, 1);    // (10, 0); closing nodes are not repeats
  EXPECT_EQ(p.report.degenerateRings, 2);  // the sliver hole, the collinear triangle
  EXPECT_EQ(p.report.degenerateParts, 1);  // the collinear triangle was a whole part

  const fs::path lines = geojson(
      "lines.geojson", feature(R"({"type": "LineString", "coordinates": [[0, 0], [1, 1]]})", ""));
  expectError([&] { importGisPolygons(lines); }, {"lines.geojson", "not polygons"});
  // A bow tie's two lobes cancel: its ring encloses no area, and the error says so.
  const fs::path bowtie = geojson("bowtie.geojson", feature(R"({"type": "Polygon", "coordinates":
                   [[[0, 0], [10, 10], [10, 0], [0, 10], [0, 0]]]})",
                                                            ""));
  expectError([&] { importGisPolygons(bowtie); },
              {"bowtie.geojson", "no polygon with three distinct nodes enclosing an area"});
  // Nodes beyond float's reach are named as such, not left to collapse onto one another.
  const fs::path far = geojson("far.geojson", feature(R"({"type": "Polygon", "coordinates":
                   [[[1e300, 0], [2e300, 0], [2e300, 1e300], [1e300, 0]]]})",
                                                      ""));
  expectError([&] { importGisPolygons(far); },
              {"far.geojson", "layer far, feature 0",
               "a node lies 1e+300 scene units from the origin, beyond the 1e15"});
}

TEST_F(GisImportTest, OrdnanceSurveyBuildingFootprints) {
  const GisPolygons b = importGisPolygons(kOsData / "ss64ne_Building_Area.shp",
                                          {.offset = {265000.0, 145000.0, 0.0}});
  EXPECT_EQ(b.layer.featureCount, 253);
  EXPECT_EQ(b.crs.authority, "EPSG:27700");
  EXPECT_GE(b.polygons.size(), 253u);
  for (const GisPolygon& p : b.polygons)
    for (const glm::vec3& v : p.outer) {
      EXPECT_GE(v.x, 0.0f);
      EXPECT_LE(v.x, 5000.0f);
      EXPECT_GE(v.y, 0.0f);
      EXPECT_LE(v.y, 5000.0f);
    }
}
