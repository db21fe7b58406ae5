// Scene objects from GIS data (docs/scene-format.md, "raster" and "footprints"): a synthetic
// DEM as the ground, footprints on it whose base is the lowest terrain height under their
// vertices (brute-force rays against the whole ground here), blocks as tall as asked.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "cutaway/io/raster_terrain.hpp"
#include "cutaway/scene/scene.hpp"
#include "expect_error.hpp"

namespace fs = std::filesystem;
using namespace cutaway;

TEST(GeoScene, FootprintsStandOnTheRasterTerrain) {
  const fs::path dir = fs::temp_directory_path() / ("cutaway-geo-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  writeSyntheticDem(dir / "dem.tif", {.min = {265000, 145000},
                                      .max = {265200, 145200},
                                      .crs = "EPSG:27700",
                                      .cell = 10,
                                      .base = 40,
                                      .relief = 25,
                                      .wavelength = 100});
  std::ofstream(dir / "b.geojson") << R"({"type": "FeatureCollection",
    "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::27700"}},
    "features": [
     {"type": "Feature", "properties": {"h": 12}, "geometry": {"type": "Polygon", "coordinates":
       [[[265050, 145050], [265080, 145050], [265080, 145070], [265050, 145070], [265050, 145050]]]}},
     {"type": "Feature", "properties": {"h": null}, "geometry": {"type": "Polygon", "coordinates":
       [[[265120, 145120], [265150, 145125], [265130, 145160], [265120, 145120]]]}}]})";
  const std::string text = R"({"geo": {"crs": "EPSG:27700", "offset": [265000, 145000]},
    "objects": [
      {"name": "ground", "raster": {"file": "dem.tif", "step": 1}, "color": [0.5, 0.6, 0.4]},
      {"name": "blocks", "footprints": {"file": "b.geojson", "height": {"field": "h", "default": 7},
                                        "on": "ground"}, "role": "exterior"},
      {"name": "flat", "footprints": {"file": "b.geojson", "height": 3}}]})";
  const Scene scene = parseScene(text, "geo.json", dir);
  const SceneObject& ground = *scene.find("ground");
  EXPECT_EQ(ground.mesh->positions.size(), 20u * 20u);
  EXPECT_EQ(ground.material.color, glm::vec3(0.5f, 0.6f, 0.4f));
  const SceneObject& blocks = *scene.find("blocks");
  EXPECT_EQ(blocks.role, Role::Exterior);
  EXPECT_TRUE(blocks.mesh->report.watertight);
  // The lowest ground height under each footprint's vertices, by rays against the whole grid.
  const auto lowest = [&](std::initializer_list<glm::vec2> en) {
    float h = 1e30f;
    for (const glm::vec2& p : en) {
      const glm::vec3 origin(p.x - 265000.0f, 1000.0f, -(p.y - 145000.0f));
      const std::vector<float> hits = rayHits(*ground.mesh, origin, {0, -1, 0});
      // Two hits where the vertex lies on an edge shared by two triangles: the same height.
      EXPECT_GE(hits.size(), 1u);
      h = std::min(h, 1000.0f - *std::min_element(hits.begin(), hits.end()));
    }
    return h;
  };
  const float first =
      lowest({{265050, 145050}, {265080, 145050}, {265080, 145070}, {265050, 145070}});
  const float second = lowest({{265120, 145120}, {265150, 145125}, {265130, 145160}});
  std::vector<float> heights;
  for (const glm::vec3& p : blocks.mesh->positions)
    if (std::find(heights.begin(), heights.end(), p.y) == heights.end()) heights.push_back(p.y);
  std::sort(heights.begin(), heights.end());
  std::vector<float> expected = {first, first + 12.0f, second, second + 7.0f};
  std::sort(expected.begin(), expected.end());
  // The rays start at other heights, so t rounds differently: 1e-3 m.
  ASSERT_EQ(heights.size(), expected.size());
  for (std::size_t i = 0; i < heights.size(); ++i) EXPECT_NEAR(heights[i], expected[i], 1e-3f) << i;
  // Without "on" the blocks stand on y = 0.
  const Bounds flat = scene.find("flat")->mesh->bounds();
  EXPECT_EQ(flat.min, glm::vec3(50, 0, -160));
  EXPECT_EQ(flat.max.y, 3.0f);
  fs::remove_all(dir);
}

// A GIS field mapped to a pipe's radius (docs/scene-format.md, "networks"): scaled per feature;
// 0 (a layer's "unknown") and a missing value take the default; a value outside the radius's
// range is refused (tests/test_scene.cpp).
TEST(GeoScene, PipeRadiiComeFromAFieldPerFeature) {
  const fs::path dir = fs::temp_directory_path() / ("cutaway-pipes-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "p.geojson") << R"({"type": "FeatureCollection", "features": [
     {"type": "Feature", "properties": {"DIAM": 600}, "geometry": {"type": "LineString",
      "coordinates": [[0, 0], [10, 0]]}},
     {"type": "Feature", "properties": {"DIAM": 0}, "geometry": {"type": "LineString",
      "coordinates": [[0, 5], [10, 5]]}},
     {"type": "Feature", "properties": {"DIAM": null}, "geometry": {"type": "LineString",
      "coordinates": [[0, 10], [10, 10]]}}]})";
  const std::string text = R"({"objects": [],
    "networks": [{"name": "n", "radius": {"field": "DIAM", "scale": 0.0005, "default": 0.2},
                  "wallThickness": 0.05, "pipes": [{"file": "p.geojson"}]}]})";
  const Scene scene = parseScene(text, "pipes.json", dir);
  ASSERT_EQ(scene.networks.size(), 1u);
  std::map<std::int64_t, float> radius;
  for (const Pipe& p : scene.networks[0].pipes) radius[p.featureId] = p.radius;
  ASSERT_EQ(radius.size(), 3u);
  EXPECT_FLOAT_EQ(radius.begin()->second, 0.3f);             // 600 × 0.0005
  EXPECT_FLOAT_EQ(std::next(radius.begin())->second, 0.2f);  // 0: the default
  EXPECT_FLOAT_EQ(std::prev(radius.end())->second, 0.2f);    // null: the default
  fs::remove_all(dir);
}

// Shafts from a point layer (docs/scene-format.md, "networks"): without a height under the
// terrain or a "depth", the floor lies under the lowest stretch of a pipe within the shaft's
// radius, also where the pipe passes between its nodes or drops vertically; a z at or above
// the terrain is the cover's; a shaft over no pipe is refused with its feature.
TEST(GeoScene, AShaftsFloorLiesUnderThePipePassingBeneathIt) {
  const fs::path dir = fs::temp_directory_path() / ("cutaway-shafts-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // A pipe falling from height −1 to −4 over 12 units, then dropping vertically to −6 at
  // x = 20.
  std::ofstream(dir / "p.geojson") << R"({"type": "FeatureCollection", "features": [
     {"type": "Feature", "properties": {}, "geometry": {"type": "LineString",
      "coordinates": [[0, 0, -1], [12, 0, -4], [20, 0, -4], [20, 0, -6]]}}]})";
  const auto floorAt = [&](const std::string& coordinates) {
    std::ofstream(dir / "m.geojson") << R"({"type": "FeatureCollection", "features": [
       {"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": )"
                                     << coordinates << "}}]}";
    const Scene scene = parseScene(R"({"objects": [],
      "networks": [{"name": "n", "radius": 0.5, "pipes": [{"file": "p.geojson"}],
                    "shafts": {"file": "m.geojson", "radius": 1}}]})",
                                   "shafts.json", dir);
    EXPECT_EQ(scene.networks.at(0).shafts.size(), 1u);
    EXPECT_FLOAT_EQ(scene.networks[0].shafts.at(0).top, 0.0f);
    return scene.networks[0].shafts.at(0).bottom.y;
  };
  // Within the radius the pipe spans x ∈ [5, 7]: lowest at x = 7, −1 − 3·7/12 = −2.75.
  EXPECT_FLOAT_EQ(floorAt("[6, 0]"), -2.75f - 0.5f);
  EXPECT_FLOAT_EQ(floorAt("[6, 0, 0]"), -2.75f - 0.5f);  // the cover's height
  EXPECT_FLOAT_EQ(floorAt("[6, 0, 5]"), -2.75f - 0.5f);
  EXPECT_FLOAT_EQ(floorAt("[6, 0, -8]"), -8.0f);        // its own floor
  EXPECT_FLOAT_EQ(floorAt("[20.5, 0]"), -6.0f - 0.5f);  // over the vertical drop
  test::expectError([&] { floorAt("[40, 0]"); },
                    {"shafts.json: /networks/0/shafts/file: shaft feature 0 meets no pipe under "
                     "the terrain and has no height below it: give \"depth\""});
  fs::remove_all(dir);
}

// Issue 17: a mesh in UTM coordinates (E ≈ 5e5, N ≈ 4.8e6 m, each vertex a float exactly),
// rotated by 30° about the vertical and moved near the origin by the scene's transform. Each
// vertex as the vertex shader places it (the object's float matrix times its float position)
// lands within a millimetre of the same transform worked in double; composed and applied in
// float it drifted by up to a metre (a float's step at 4.8e6 is 0.5).
TEST(GeoScene, AMeshInUtmCoordinatesKeepsItsMillimetresThroughTheTransform) {
  const fs::path dir = fs::temp_directory_path() / ("cutaway-utm-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::vector<glm::dvec3> vertices = {{500000.25, 12.0, -4800000.0},
                                            {500010.75, 12.0, -4800000.5},
                                            {500004.5, 19.5, -4800014.0},
                                            {500001.0, 12.0, -4800021.5}};
  {
    std::ofstream obj(dir / "utm.obj");
    obj.precision(17);
    for (const glm::dvec3& v : vertices) obj << "v " << v.x << ' ' << v.y << ' ' << v.z << '\n';
    obj << "f 1 2 3\nf 1 3 4\n";
  }
  const glm::dmat4 rotate =
      glm::rotate(glm::dmat4(1.0), glm::radians(30.0), glm::dvec3(0.0, 1.0, 0.0));
  // The translation that brings the first vertex, rotated, back to (1, 2, 3).
  const glm::dvec3 translate =
      glm::dvec3(1.0, 2.0, 3.0) - glm::dvec3(rotate * glm::dvec4(vertices[0], 1.0));
  std::ostringstream text;
  text.precision(17);
  text << R"({"objects": [{"name": "utm", "file": "utm.obj", "transform": {"translate": [)"
       << translate.x << ", " << translate.y << ", " << translate.z
       << R"(], "rotate": {"axis": [0, 1, 0], "degrees": 30}}}]})";
  const Scene scene = parseScene(text.str(), "utm.json", dir);
  const SceneObject& o = scene.objects.at(0);
  const glm::dmat4 exact = glm::translate(glm::dmat4(1.0), translate) * rotate;
  // Each placed position against the nearest vertex placed in double (the importer may repeat
  // vertices per face); every vertex is some position's.
  std::vector<bool> matched(vertices.size(), false);
  ASSERT_GE(o.mesh->positions.size(), vertices.size());
  for (const glm::vec3& p : o.mesh->positions) {
    const glm::dvec3 placed(glm::vec3(o.transform * glm::vec4(p, 1.0f)));
    double nearest = 1e30;
    std::size_t which = 0;
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      const double d = glm::length(placed - glm::dvec3(exact * glm::dvec4(vertices[i], 1.0)));
      if (d < nearest) nearest = d, which = i;
    }
    EXPECT_LT(nearest, 1e-3) << "placed (" << placed.x << ", " << placed.y << ", " << placed.z
                             << "), " << nearest << " from vertex " << which << " in double";
    matched[which] = true;
  }
  for (std::size_t i = 0; i < vertices.size(); ++i) EXPECT_TRUE(matched[i]) << i;
  fs::remove_all(dir);
}
