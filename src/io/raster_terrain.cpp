// Terrain grids from elevation rasters through GDAL, and the synthetic DEM writer
// (io/raster_terrain.hpp). Like the vector import, coordinates stay in double until the
// offset is gone.
#include "cutaway/io/raster_terrain.hpp"

#include <cpl_conv.h>
#include <cpl_string.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <deque>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cutaway/core/atomic_file.hpp"
#include "cutaway/core/contained.hpp"
#include "cutaway/core/error.hpp"
#include "cutaway/core/noise.hpp"
#include "io/gdal_support.hpp"
#include "io/wire_fields.hpp"

namespace cutaway {

namespace {

// A number as short as it can be written and read back the same (10, not 10.000000;
// 1000000.5, not %g's 1e+06).
std::string number(double v) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, v).ptr);
}

GDALDatasetUniquePtr openRaster(const std::filesystem::path& file) {
  gdal::registerDrivers();
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw Error(file.string(), "", "raster file not found");
  GDALDatasetUniquePtr dataset(GDALDataset::Open(file.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY,
                                                 nullptr, nullptr, nullptr));
  if (!dataset || dataset->GetRasterCount() < 1)
    throw Error(file.string(), "", "cannot open as a raster" + gdal::QuietErrors::lastMessage());
  return dataset;
}

struct DestroyTransform {
  void operator()(OGRCoordinateTransformation* t) const {
    OGRCoordinateTransformation::DestroyCT(t);
  }
};
using Transform = std::unique_ptr<OGRCoordinateTransformation, DestroyTransform>;

// Nodata nodes take the height of the nearest valid node in grid steps: a breadth-first
// search from all valid nodes at once, so each node is reached first by its nearest one.
std::int64_t fillNodata(std::vector<double>& heights, const std::vector<bool>& valid, int columns,
                        int rows) {
  std::deque<int> queue;
  std::vector<bool> reached = valid;
  for (int i = 0; i < columns * rows; ++i)
    if (valid[std::size_t(i)]) queue.push_back(i);
  std::int64_t filled = 0;
  while (!queue.empty()) {
    const int i = queue.front();
    queue.pop_front();
    const int c = i % columns, r = i / columns;
    for (const auto& [dc, dr] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const int nc = c + dc, nr = r + dr;
      if (nc < 0 || nr < 0 || nc >= columns || nr >= rows) continue;
      const int n = nr * columns + nc;
      if (reached[std::size_t(n)]) continue;
      reached[std::size_t(n)] = true;
      heights[std::size_t(n)] = heights[std::size_t(i)];
      ++filled;
      queue.push_back(n);
    }
  }
  return filled;
}

// Area-weighted vertex normals: a smooth surface with no creases, whatever the grid's shape.
void smoothNormals(Mesh& mesh) {
  mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f));
  for (std::size_t i = 0, count = mesh.triangleCount(); i < count; ++i) {
    const glm::uvec3 t = mesh.triangle(i);
    const glm::vec3 n = glm::cross(mesh.positions[t.y] - mesh.positions[t.x],
                                   mesh.positions[t.z] - mesh.positions[t.x]);
    for (int k = 0; k < 3; ++k) mesh.normals[t[k]] += n;
  }
  for (glm::vec3& n : mesh.normals) n = glm::normalize(n);
}

// The readers themselves, in whichever process runs them.
bool isRasterHere(const std::filesystem::path& file) {
  gdal::registerDrivers();
  gdal::QuietErrors quiet;
  GDALDatasetUniquePtr dataset(GDALDataset::Open(file.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY,
                                                 nullptr, nullptr, nullptr));
  return dataset && dataset->GetRasterCount() > 0;
}

RasterInfo describeRasterHere(const std::filesystem::path& file) {
  gdal::QuietErrors quiet;
  GDALDatasetUniquePtr dataset = openRaster(file);
  RasterInfo info;
  info.driver = dataset->GetDriver() ? dataset->GetDriver()->GetDescription() : "";
  info.width = dataset->GetRasterXSize();
  info.height = dataset->GetRasterYSize();
  info.bands = dataset->GetRasterCount();
  GDALRasterBand* band = dataset->GetRasterBand(1);
  info.dataType = GDALGetDataTypeName(band->GetRasterDataType());
  info.crs = gdal::describeCrs(dataset->GetSpatialRef());
  std::array<double, 6> gt;
  if (dataset->GetGeoTransform(gt.data()) == CE_None) info.geoTransform = gt;
  int hasNodata = 0;
  const double nodata = band->GetNoDataValue(&hasNodata);
  if (hasNodata) info.nodata = nodata;
  double minMax[2];
  // Exact (every sample read), not the approximate overview statistics. No minimum where every
  // sample is nodata; a sample that cannot be read (a truncated file) is an error, as in render.
  CPLErrorReset();
  if (band->ComputeRasterMinMax(FALSE, minMax) == CE_None)
    info.minimum = minMax[0], info.maximum = minMax[1];
  else if (CPLGetLastErrorType() >= CE_Failure && CPLGetLastErrorNo() != CPLE_None &&
           std::string(CPLGetLastErrorMsg()).find("valid") == std::string::npos)
    throw Error(file.string(), "", "cannot read band 1" + gdal::QuietErrors::lastMessage());
  return info;
}

RasterTerrain importRasterTerrainHere(const std::filesystem::path& file,
                                      const RasterTerrainOptions& options) {
  gdal::QuietErrors quiet;
  const std::string name = file.string();
  if (options.step < 1) throw Error(name, "", "step must be at least 1");
  GDALDatasetUniquePtr dataset = openRaster(file);
  RasterTerrain out;
  if (dataset->GetGeoTransform(out.geoTransform.data()) != CE_None)
    throw Error(name, "",  // GDAL's last message tells a file cut short from a plain image
                "the raster has no geotransform (it is not georeferenced)" +
                    gdal::QuietErrors::lastMessage());
  const std::array<double, 6>& gt = out.geoTransform;
  if (!std::all_of(gt.begin(), gt.end(), [](double v) { return std::isfinite(v); }))
    throw Error(name, "", "the geotransform is not finite");
  if (gt[2] != 0.0 || gt[4] != 0.0)
    throw Error(name, "", "rotated geotransforms are not supported (warp it north-up first)");
  if (gt[1] == 0.0 || gt[5] == 0.0) throw Error(name, "", "the cell size is 0");
  const OGRSpatialReference* source = dataset->GetSpatialRef();
  out.crs = gdal::describeCrs(source);
  out.sceneCrs = out.crs;
  Transform transform;
  if (!options.targetCrs.empty()) {
    if (!source || source->IsEmpty())
      throw Error(name, "",
                  "the raster has no CRS, so it cannot be reprojected to " + options.targetCrs);
    OGRSpatialReference from(*source), to;
    if (to.SetFromUserInput(options.targetCrs.c_str()) != OGRERR_NONE)
      throw Error(
          name, "",
          "unknown target CRS " + quote(options.targetCrs) + gdal::QuietErrors::lastMessage());
    from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    to.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    out.sceneCrs = gdal::describeCrs(&to);
    if (!from.IsSame(&to)) {  // the same CRS: no transformation, no rounding through PROJ
      transform.reset(OGRCreateCoordinateTransformation(&from, &to));
      if (!transform)
        throw Error(name, "",
                    "no transformation to " + options.targetCrs + gdal::QuietErrors::lastMessage());
    }
  }

  const int width = dataset->GetRasterXSize(), height = dataset->GetRasterYSize();
  out.columns = (width - 1) / options.step + 1;
  out.rows = (height - 1) / options.step + 1;
  if (out.columns < 2 || out.rows < 2)
    throw Error(name, "",
                "a terrain grid needs at least 2 × 2 nodes, got " + std::to_string(out.columns) +
                    " × " + std::to_string(out.rows) + " (raster " + std::to_string(width) + " × " +
                    std::to_string(height) + ", step " + std::to_string(options.step) + ")");
  const std::size_t nodes = std::size_t(out.columns) * std::size_t(out.rows);
  // About 80 bytes per node go into the grid and its mesh: a header claiming 64752 × 65535
  // samples asked for 34 GB (fuzzing).
  if (nodes > kMaxTerrainNodes)
    throw Error(name, "",
                "a terrain grid of " + std::to_string(out.columns) + " × " +
                    std::to_string(out.rows) + " nodes is beyond the limit of " +
                    std::to_string(kMaxTerrainNodes) + " (raster " + std::to_string(width) + " × " +
                    std::to_string(height) + "); give a larger \"step\"");
  GDALRasterBand* band = dataset->GetRasterBand(1);
  int hasNodata = 0;
  const double nodata = band->GetNoDataValue(&hasNodata);

  std::vector<double> heights(nodes), row(static_cast<std::size_t>(width));
  std::vector<bool> valid(nodes);
  out.minHeight = std::numeric_limits<double>::infinity();
  out.maxHeight = -out.minHeight;
  bool anyValid = false;
  for (int r = 0; r < out.rows; ++r) {
    // Only the rows the grid samples are read, one at a time.
    if (band->RasterIO(GF_Read, 0, r * options.step, width, 1, row.data(), width, 1, GDT_Float64, 0,
                       0, nullptr) != CE_None)
      throw Error(name, "row " + std::to_string(r * options.step),
                  "cannot read band 1" + gdal::QuietErrors::lastMessage());
    for (int c = 0; c < out.columns; ++c) {
      const double h = row[std::size_t(c * options.step)];
      const std::size_t i = out.node(c, r);
      valid[i] = std::isfinite(h) && !(hasNodata && h == nodata);
      if (!valid[i]) continue;
      heights[i] = h;
      anyValid = true;
      out.minHeight = std::min(out.minHeight, h);
      out.maxHeight = std::max(out.maxHeight, h);
    }
  }
  if (!anyValid) throw Error(name, "", "band 1 holds no valid sample (all nodata)");
  out.filledNodata = fillNodata(heights, valid, out.columns, out.rows);

  // Pixel centres in the raster's CRS, then (in double) in the scene's.
  std::vector<double> xs(nodes), ys(nodes);
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < out.columns; ++c) {
      const double px = c * options.step + 0.5, py = r * options.step + 0.5;
      xs[out.node(c, r)] = gt[0] + px * gt[1];
      ys[out.node(c, r)] = gt[3] + py * gt[5];
    }
  if (transform) {
    std::vector<int> ok(nodes);
    if (!transform->Transform(nodes, xs.data(), ys.data(), nullptr, ok.data()))
      for (std::size_t i = 0; i < nodes; ++i)
        if (!ok[i])
          throw Error(name, "",
                      "cannot transform grid node (" + std::to_string(i % out.columns) + ", " +
                          std::to_string(i / out.columns) + ") to " + options.targetCrs +
                          gdal::QuietErrors::lastMessage());
  }
  Mesh& mesh = out.mesh;
  mesh.positions.resize(nodes);
  const auto nodeName = [&](std::size_t i) {
    return "grid node (" + std::to_string(i % std::size_t(out.columns)) + ", " +
           std::to_string(i / std::size_t(out.columns)) + ")";
  };
  for (std::size_t i = 0; i < nodes; ++i) {
    const glm::vec3 p(float(xs[i] - options.offset.x),
                      float(heights[i] * options.heightScale - options.offset.z),
                      float(-(ys[i] - options.offset.y)));
    // Beyond float's reach (a corner at 1e300) the nodes would become infinite.
    if (!(sceneReach(p) <= kMaxSceneReach)) {
      std::ostringstream message;
      message << nodeName(i) << " lies " << sceneReach(p)
              << " scene units from the origin, beyond the 1e15 a scene may reach";
      throw Error(name, "", message.str());
    }
    mesh.positions[i] = p;
  }
  // Cells too small for floats where the grid lies would leave triangles of no area.
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < out.columns; ++c) {
      const glm::vec3& p = mesh.positions[out.node(c, r)];
      for (const std::size_t n : {c + 1 < out.columns ? out.node(c + 1, r) : nodes,
                                  r + 1 < out.rows ? out.node(c, r + 1) : nodes})
        if (n < nodes && mesh.positions[n].x == p.x && mesh.positions[n].z == p.z)
          throw Error(name, "",
                      nodeName(out.node(c, r)) + " and " + nodeName(n) +
                          " fall on one point in the scene's 32-bit floats: cells too small "
                          "for where the grid lies");
    }
  // The triangles are implied by the grid. Row r + 1 lies south of row r (towards +z):
  // (c, r), (c, r+1), (c+1, r) turns clockwise seen from above, so the triangles face up. A
  // west-to-east raster (dx > 0) keeps that; a mirrored one flips each cell's order.
  mesh.grid = GridLayout{out.columns, out.rows};
  if ((gt[1] > 0.0) == (gt[5] < 0.0))
    mesh.grid->cell = {{{0, 2, 1}, {1, 2, 3}}};
  else
    mesh.grid->cell = {{{0, 1, 2}, {1, 3, 2}}};
  smoothNormals(mesh);
  mesh.report.normalsComputed = true;
  return out;
}

}  // namespace

template <class Archive>
void wireFields(Archive& a, RasterInfo& i) {
  a(i.driver, i.width, i.height, i.bands, i.dataType, i.crs, i.geoTransform, i.nodata, i.minimum,
    i.maximum);
}

template <class Archive>
void wireFields(Archive& a, RasterTerrain& t) {
  a(t.mesh, t.columns, t.rows, t.crs, t.sceneCrs, t.geoTransform, t.filledNodata, t.minHeight,
    t.maxHeight);
}

template <class Archive>
void wireFields(Archive& a, RasterTerrainOptions& o) {
  a(o.step, o.heightScale, o.targetCrs, o.offset);
}

// GDAL runs in a worker process (cutaway/core/contained.hpp).
const ContainedReader<bool, &isRasterHere> containedIsRaster("raster-test", "GDAL");
const ContainedReader<RasterInfo, &describeRasterHere> containedDescription("raster-info", "GDAL");
const ContainedReader<RasterTerrain, &importRasterTerrainHere, RasterTerrainOptions>
    containedTerrain("raster-terrain", "GDAL");

bool isRaster(const std::filesystem::path& file) {
  return containedIsRaster(file);
}

RasterInfo describeRaster(const std::filesystem::path& file) {
  return containedDescription(file);
}

RasterTerrain importRasterTerrain(const std::filesystem::path& file,
                                  const RasterTerrainOptions& options) {
  return containedTerrain(file, options);
}

double syntheticDemHeight(const SyntheticDemOptions& o, double easting, double northing) {
  const double u = (easting - o.min.x) / o.wavelength, v = (northing - o.min.y) / o.wavelength;
  double sum = 0.0, weights = 0.0;
  for (int octave = 0; octave < o.octaves; ++octave) {
    const double frequency = std::ldexp(1.0, octave), weight = 1.0 / frequency;
    sum += weight *
           valueNoise(float(u * frequency), float(v * frequency), o.seed + std::uint32_t(octave));
    weights += weight;
  }
  return std::round((o.base + o.relief * sum / weights) * 100.0) / 100.0;
}

void writeSyntheticDem(const std::filesystem::path& file, const SyntheticDemOptions& o) {
  const std::string name = file.string();
  gdal::registerDrivers();
  gdal::QuietErrors quiet;
  if (!(o.cell > 0.0)) throw Error(name, "", "the cell size must be positive");
  if (!(o.wavelength > 0.0)) throw Error(name, "", "the wavelength must be positive");
  if (o.octaves < 1 || o.octaves > 16) throw Error(name, "", "octaves must be in [1, 16]");
  if (!std::isfinite(o.max.x - o.min.x) || !std::isfinite(o.max.y - o.min.y))
    throw Error(name, "extent", "the extent's width and height overflow 64-bit floats");
  const glm::dvec2 size = (o.max - o.min) / o.cell;
  const glm::dvec2 whole = glm::round(size);
  if (!(size.x >= 1.0 && size.y >= 1.0) ||
      glm::any(glm::greaterThan(glm::abs(size - whole), glm::dvec2(1e-6))))
    throw Error(name, "extent",
                "the extent (" + number(o.min.x) + ", " + number(o.min.y) + ") to (" +
                    number(o.max.x) + ", " + number(o.max.y) +
                    ") must hold a whole, positive number of " + number(o.cell) +
                    "-unit cells along each axis");
  if (whole.x * whole.y > 1e8)
    throw Error(name, "cell", "more than 10⁸ cells: choose larger cells");
  OGRSpatialReference crs;
  if (crs.SetFromUserInput(o.crs.c_str()) != OGRERR_NONE)
    throw Error(name, "crs", "unknown CRS " + quote(o.crs) + gdal::QuietErrors::lastMessage());
  // Degrees of a geographic CRS: west and east as longitudes, south and north as latitudes.
  if (crs.IsGeographic() &&
      !(o.min.y >= -90.0 && o.max.y <= 90.0 && o.min.x >= -360.0 && o.max.x <= 360.0))
    throw Error(name, "extent",
                "the extent (" + number(o.min.x) + ", " + number(o.min.y) + ") to (" +
                    number(o.max.x) + ", " + number(o.max.y) + ") lies beyond the degrees of " +
                    quote(o.crs) + " (latitudes in [-90, 90], longitudes in [-360, 360])");
  const int width = int(whole.x), height = int(whole.y);
  std::vector<float> samples(std::size_t(width) * std::size_t(height));
  for (int r = 0; r < height; ++r)
    for (int c = 0; c < width; ++c)
      samples[std::size_t(r) * std::size_t(width) + std::size_t(c)] =
          float(syntheticDemHeight(o, o.min.x + (c + 0.5) * o.cell, o.max.y - (r + 0.5) * o.cell));
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (!driver) throw Error(name, "", "GDAL has no GeoTIFF driver");
  replaceFileAtomically(file, [&](const std::filesystem::path& temporary) {
    // GDAL's reason names the temporary file: the user gave `name`.
    const auto failed = [&](const std::string& what) {
      std::string reason = what + gdal::QuietErrors::lastMessage();
      const std::string temporaryName = temporary.string();
      for (std::size_t at = 0; (at = reason.find(temporaryName, at)) != std::string::npos;
           at += name.size())
        reason.replace(at, temporaryName.size(), name);
      return Error(name, "", reason);
    };
    CPLStringList creation;
    creation.SetNameValue("COMPRESS", "DEFLATE");
    creation.SetNameValue("PREDICTOR", "3");  // floating-point differencing: smooth heights
    creation.SetNameValue("ZLEVEL", "9");
    GDALDatasetUniquePtr dataset(
        driver->Create(temporary.c_str(), width, height, 1, GDT_Float32, creation.List()));
    if (!dataset) throw failed("cannot create");
    double gt[6] = {o.min.x, o.cell, 0.0, o.max.y, 0.0, -o.cell};
    if (dataset->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, width, height, samples.data(), width,
                                            height, GDT_Float32, 0, 0, nullptr) != CE_None ||
        dataset->SetGeoTransform(gt) != CE_None || dataset->SetSpatialRef(&crs) != CE_None)
      throw failed("cannot write");
    // Closing writes the compressed strips; a failure there shows only as GDAL's last error.
    CPLErrorReset();
    dataset.reset();
    if (CPLGetLastErrorType() >= CE_Failure) throw failed("cannot write");
  });
}

}  // namespace cutaway
