// cutaway/io/raster_terrain.hpp — terrain grids from elevation rasters through GDAL (GeoTIFF and
// every other GDAL raster format): the ground that Konev18 §4 opens above the network, and
// a synthetic DEM for tiles that come without heights.
//
// Band 1 is sampled at its pixel centres (every `step`-th pixel along rows and columns, from
// the north-west pixel) and each sample becomes a grid node; two triangles per grid cell,
// smooth vertex normals. A node's easting and northing are reprojected to `targetCrs` (in
// double, when given and different from the raster's), the offset is subtracted in double,
// and the node is placed as the scene's GeoFrame says: x = E − E0, y = h·heightScale − H0,
// z = −(N − N0). Nodata samples (and NaN) take the height of the nearest valid node of the
// sampled grid — fewest steps along rows and columns, ties to the valid node first in row
// order (a breadth-first search from all valid nodes) — and are counted; a raster with no valid
// sample is an error.
//
//   cutaway::RasterTerrainOptions options{.step = 2, .targetCrs = "EPSG:27700",
//                                         .offset = {265000.0, 145000.0, 0.0}};
//   cutaway::RasterTerrain t = cutaway::importRasterTerrain("dem.tif", options);
//   const glm::vec3 node = t.mesh.positions[t.node(3, 4)];   // column 3, row 4 (from north)
//
// Errors (cutaway::Error, file + reason): a missing file, a file GDAL cannot read as a raster,
// no geotransform, a rotated geotransform, an unknown target CRS or a raster without a CRS
// when a reprojection is asked for, a grid of fewer than 2 × 2 nodes, no valid sample.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "cutaway/geometry/mesh.hpp"
#include "cutaway/io/gis_import.hpp"

namespace cutaway {

struct RasterTerrainOptions {
  int step = 1;              // use every step-th sample along rows and columns (≥ 1)
  double heightScale = 1.0;  // raster values × heightScale = heights in the CRS's units
  std::string targetCrs;     // empty: keep the raster's CRS
  glm::dvec3 offset{0.0};    // E0, N0, H0, subtracted in double
};

struct RasterTerrain {
  Mesh mesh;                             // scene coordinates (y up, north towards −z)
  int columns = 0, rows = 0;             // grid nodes
  GisCrs crs;                            // the raster's
  GisCrs sceneCrs;                       // the mesh's: the target CRS, or the raster's
  std::array<double, 6> geoTransform{};  // GDAL's: x0, dx, 0, y0, 0, dy (dy < 0: north up)
  std::int64_t filledNodata = 0;         // nodes whose height came from a neighbour
  double minHeight = 0, maxHeight = 0;   // of the valid samples used, before heightScale
  std::uint32_t node(int column, int row) const {
    return std::uint32_t(row) * std::uint32_t(columns) + std::uint32_t(column);
  }
};

// A grid of more nodes than this is refused (it would take gigabytes); a larger step thins it.
inline constexpr std::size_t kMaxTerrainNodes = std::size_t(1) << 25;

RasterTerrain importRasterTerrain(const std::filesystem::path& file,
                                  const RasterTerrainOptions& options = {});

// What `cutaway info` prints about a raster.
struct RasterInfo {
  std::string driver;  // "GTiff"
  int width = 0, height = 0, bands = 0;
  std::string dataType;  // of band 1: "Float32"
  GisCrs crs;
  std::optional<std::array<double, 6>> geoTransform;
  std::optional<double> nodata;            // of band 1
  std::optional<double> minimum, maximum;  // of band 1's valid samples; absent when none
};

// Whether GDAL opens `file` as a raster with at least one band.
bool isRaster(const std::filesystem::path& file);
RasterInfo describeRaster(const std::filesystem::path& file);

// A synthetic DEM: fractal value noise (core/noise.hpp), for tiles whose real heights are not
// at hand. Heights are base + relief · Σₒ 2⁻ᵒ·valueNoise(2ᵒ·u, 2ᵒ·v, seed + o) / Σₒ 2⁻ᵒ with
// u, v the distances from the extent's south-west corner in wavelengths, rounded to
// centimetres (a DEM's usual precision; it lets the file compress).
struct SyntheticDemOptions {
  glm::dvec2 min{0.0}, max{0.0};  // extent: west, south, east, north
  std::string crs;                // anything OGR's SetFromUserInput takes
  double cell = 10.0;             // pixel size; the extent must hold a whole number of them
  double base = 0.0, relief = 25.0;
  double wavelength = 1000.0;  // size of the largest hills
  int octaves = 5;
  std::uint32_t seed = 1;
};
double syntheticDemHeight(const SyntheticDemOptions& options, double easting, double northing);
// Writes it as a Float32 GeoTIFF (DEFLATE, floating-point predictor) with its CRS and
// geotransform, one sample per cell centre; atomically (a failure leaves no file). An unknown
// CRS is an Error at place "crs"; an extent of no whole number of cells, or past ±90° of
// latitude in a geographic CRS, at place "extent".
void writeSyntheticDem(const std::filesystem::path& file, const SyntheticDemOptions& options);

}  // namespace cutaway
