// cutaway/io/gis_import.hpp — pipe networks and shafts from GIS vector data through GDAL/OGR
// (ESRI Shapefile, GeoPackage, GeoJSON and every other OGR vector format): Konev18 §5's input,
// pipes as polylines of 3-D nodes with per-pipe attributes (radius, water level), shafts as
// points, and building footprints as polygons with holes (extruded by geometry/extrude.hpp).
//
// Projected coordinates are large (British National Grid eastings reach 7·10⁵ m, UTM
// northings 10⁷ m) and a float keeps only 24 bits: 465123.25 is already at float's 1/32 m
// resolution. So every coordinate is optionally reprojected (in double), then a declared
// offset is subtracted in double, and only the small remainder becomes a float.
//
//   cutaway::GisImportOptions options{.attributes = {"radius", "water_level"},
//                                     .offset = {465000.0, 164000.0, 0.0}};
//   cutaway::GisLines pipes = cutaway::importGisLines("sewers.shp", options);
//   for (const cutaway::GisPolyline& p : pipes.polylines)
//     std::printf("feature %lld: %zu nodes, radius %g\n", (long long)p.featureId,
//                 p.points.size(), p.attributes[0]);
//
// Errors (cutaway::Error, file + "layer NAME" or "layer NAME, feature FID" + reason): a
// missing or unreadable file, no such layer, a layer of the wrong geometry type, an empty
// layer, a missing or non-numeric attribute field, an unknown CRS or one that cannot be
// transformed when a reprojection is asked for. Repeated consecutive nodes (zero-length
// segments) and parts left with a single node are dropped and counted in the report; so are
// polygon rings left with fewer than three distinct nodes or no area.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cutaway/core/geo_frame.hpp"

namespace cutaway {

struct GisCrs {
  std::string name;       // "OSGB 1936 / British National Grid"; empty: the layer has no CRS
  std::string authority;  // "EPSG:27700"; empty where no authority code is known
  std::string wkt;        // WKT2 (OGC 2019)
  bool known() const { return !wkt.empty(); }
};

// An axis-aligned box in the layer's own CRS, in double precision.
struct GisExtent {
  glm::dvec2 min{0.0}, max{0.0};
};

struct GisLayerInfo {
  std::string name;
  std::string geometryType;  // OGR's name: "Line String", "3D Multi Line String", "Point"…
  std::int64_t featureCount = 0;
  GisCrs crs;
  std::optional<GisExtent> extent;  // absent for an empty layer
  std::vector<std::string> fields;      // attribute field names, in the layer's order
  std::vector<std::string> fieldTypes;  // their OGR types: "Integer", "Real", "String"…
};

// Whether OGR understands `crs` ("EPSG:27700", WKT, a PROJ string).
bool gisCrsKnown(const std::string& crs);

// The layers of a vector data source, for inspection (`cutaway info`).
std::vector<GisLayerInfo> listGisLayers(const std::filesystem::path& file);

struct GisImportOptions {
  std::string layer;                    // empty: the data source's only layer
  std::vector<std::string> attributes;  // numeric fields read per feature, in this order
  std::string targetCrs;   // empty: keep the layer's CRS; else anything OGR's SetFromUserInput
                           // takes ("EPSG:25832", WKT, PROJ strings)
  glm::dvec3 offset{0.0};  // subtracted (after any reprojection) before converting to float
};
// Import options for a layer in the scene's frame: reprojected to its CRS, offset removed.
inline GisImportOptions gisImportOptions(const GeoFrame& geo) {
  GisImportOptions options;
  options.targetCrs = geo.crs;
  options.offset = geo.offset;
  return options;
}

struct GisImportReport {
  std::int64_t features = 0;  // features read
  std::int64_t featuresWithoutGeometry = 0;
  std::int64_t repeatedNodes = 0;           // consecutive nodes equal (as float) to the previous
  std::int64_t degenerateParts = 0;         // parts with fewer than two distinct nodes
  std::int64_t missingAttributeValues = 0;  // null fields, returned as NaN
  std::int64_t degenerateRings = 0;  // polygon rings with < 3 distinct nodes or zero area; a
                                     // degenerate outer ring drops its polygon (its holes too)
};

struct GisPolyline {
  std::int64_t featureId = 0;
  int part = 0;                    // index within a MultiLineString, 0 for a LineString
  std::vector<glm::vec3> points;   // (x, y, z) in the output CRS minus the offset; z = −offset.z
                                   // for 2-D data; at least two, consecutive ones distinct
  std::vector<double> attributes;  // GisImportOptions::attributes' values, NaN where null
};

struct GisPoint {
  std::int64_t featureId = 0;
  int part = 0;  // index within a MultiPoint
  glm::vec3 position{0.0f};
  std::vector<double> attributes;
};

// One polygon: an outer ring and its holes, each ring without the closing node (the first
// node is not repeated at the end), at least three distinct consecutive nodes, non-zero area,
// in the file's own orientation.
struct GisPolygon {
  std::int64_t featureId = 0;
  int part = 0;  // index within a MultiPolygon
  std::vector<glm::vec3> outer;
  std::vector<std::vector<glm::vec3>> holes;
  std::vector<double> attributes;
};

// What every import returns besides its items.
struct GisLayerImport {
  GisLayerInfo layer;  // the source layer (its CRS, and its extent in that CRS)
  GisCrs crs;          // the CRS of the items: the target CRS, or the layer's
  glm::dvec3 offset{0.0};
  bool hasZ = false;  // the layer's geometries carry heights
  GisImportReport report;
};

struct GisLines : GisLayerImport {
  std::vector<GisPolyline> polylines;
};

struct GisPoints : GisLayerImport {
  std::vector<GisPoint> points;
};

struct GisPolygons : GisLayerImport {
  std::vector<GisPolygon> polygons;
};

// A LineString / MultiLineString layer (2-D or 3-D).
GisLines importGisLines(const std::filesystem::path& file, const GisImportOptions& options = {});
// A Point / MultiPoint layer (2-D or 3-D).
GisPoints importGisPoints(const std::filesystem::path& file, const GisImportOptions& options = {});
// A Polygon / MultiPolygon layer (2-D or 3-D), e.g. building footprints.
GisPolygons importGisPolygons(const std::filesystem::path& file,
                              const GisImportOptions& options = {});

}  // namespace cutaway
