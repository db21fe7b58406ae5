// GIS vector import through GDAL/OGR: Konev18 §5's pipe network ("a set of lines in the .SHP
// format", each pipe a list of 3-D nodes with a radius and a water level), its shafts, and
// the footprints of the buildings over it.
// Coordinates are reprojected and shifted by a declared offset in double precision before
// they become floats (see gis_import.hpp for why).
#include "cutaway/io/gis_import.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <mutex>

#include "cutaway/core/contained.hpp"
#include "cutaway/core/error.hpp"
#include "cutaway/geometry/mesh.hpp"
#include "io/gdal_support.hpp"
#include "io/wire_fields.hpp"

namespace cutaway {

namespace gdal {

void registerDrivers() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

GisCrs describeCrs(const OGRSpatialReference* srs) {
  GisCrs crs;
  if (!srs || srs->IsEmpty()) return crs;
  OGRSpatialReference copy(*srs);
  // An ESRI .prj carries names but no authority code: look for the one EPSG definition it
  // matches (GDAL's own confidence scale; 90 and above means equivalent up to names).
  if (!copy.GetAuthorityName(nullptr)) {
    int count = 0;
    int* confidence = nullptr;
    OGRSpatialReferenceH* matches = copy.FindMatches(nullptr, &count, &confidence);
    if (matches && count >= 1 && confidence[0] >= 90)
      copy = *OGRSpatialReference::FromHandle(matches[0]);
    OSRFreeSRSArray(matches);
    CPLFree(confidence);
  }
  if (const char* n = copy.GetName()) crs.name = n;
  const char* authority = copy.GetAuthorityName(nullptr);
  const char* code = copy.GetAuthorityCode(nullptr);
  if (authority && code) crs.authority = std::string(authority) + ":" + code;
  char* wkt = nullptr;
  const char* const options[] = {"FORMAT=WKT2_2019", nullptr};
  if (copy.exportToWkt(&wkt, options) == OGRERR_NONE && wkt) crs.wkt = wkt;
  CPLFree(wkt);
  return crs;
}

}  // namespace gdal

namespace {

std::string layerPlace(const OGRLayer& layer) {
  return "layer " + std::string(const_cast<OGRLayer&>(layer).GetName());
}

std::string featurePlace(const OGRLayer& layer, GIntBig fid) {
  return layerPlace(layer) + ", feature " + std::to_string(fid);
}

GisLayerInfo describeLayer(OGRLayer& layer) {
  GisLayerInfo info;
  info.name = layer.GetName();
  info.geometryType = OGRGeometryTypeToName(layer.GetGeomType());
  info.featureCount = layer.GetFeatureCount(TRUE);
  info.crs = gdal::describeCrs(layer.GetSpatialRef());
  OGREnvelope envelope;
  if (info.featureCount > 0 && layer.GetExtent(&envelope, TRUE) == OGRERR_NONE)
    info.extent = GisExtent{{envelope.MinX, envelope.MinY}, {envelope.MaxX, envelope.MaxY}};
  const OGRFeatureDefn* definition = layer.GetLayerDefn();
  for (int i = 0; i < definition->GetFieldCount(); ++i) {
    const OGRFieldDefn* field = definition->GetFieldDefn(i);
    info.fields.emplace_back(field->GetNameRef());
    info.fieldTypes.emplace_back(OGRFieldDefn::GetFieldTypeName(field->GetType()));
  }
  return info;
}

GDALDatasetUniquePtr openVectorSource(const std::filesystem::path& file) {
  gdal::registerDrivers();
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw Error(file.string(), "", "GIS file not found");
  GDALDatasetUniquePtr dataset(GDALDataset::Open(file.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY,
                                                 nullptr, nullptr, nullptr));
  if (!dataset)
    throw Error(file.string(), "",
                "cannot open as a GIS vector data source" + gdal::QuietErrors::lastMessage());
  return dataset;
}

std::string layerNames(GDALDataset& dataset) {
  std::string names;
  for (int i = 0; i < dataset.GetLayerCount(); ++i)
    names += (i ? ", " : "") + std::string(dataset.GetLayer(i)->GetName());
  return names.empty() ? "none" : names;
}

OGRLayer& chooseLayer(GDALDataset& dataset, const std::filesystem::path& file,
                      const std::string& name) {
  if (name.empty()) {
    if (dataset.GetLayerCount() == 1) return *dataset.GetLayer(0);
    throw Error(file.string(), "",
                "the data source has " + std::to_string(dataset.GetLayerCount()) + " layers (" +
                    layerNames(dataset) + "): name one");
  }
  OGRLayer* layer = dataset.GetLayerByName(name.c_str());
  if (!layer)
    throw Error(file.string(), "layer " + name,
                "no such layer (layers: " + layerNames(dataset) + ")");
  return *layer;
}

// Everything a feature loop needs: the layer, its attribute field indices, the coordinate
// transformation and the offset.
class FeatureReader {
 public:
  FeatureReader(const std::filesystem::path& file, OGRLayer& layer, const GisImportOptions& options,
                GisImportReport& report)
      : file_(file), layer_(layer), offset_(options.offset), report_(report) {
    const OGRFeatureDefn* definition = layer.GetLayerDefn();
    for (const std::string& name : options.attributes) {
      const int i = definition->GetFieldIndex(name.c_str());
      if (i < 0) {
        std::string fields;
        for (int k = 0; k < definition->GetFieldCount(); ++k)
          fields += (k ? ", " : "") + std::string(definition->GetFieldDefn(k)->GetNameRef());
        throw Error(file.string(), layerPlace(layer),
                    "no attribute field \"" + name +
                        "\" (fields: " + (fields.empty() ? "none" : fields) + ")");
      }
      const OGRFieldType type = definition->GetFieldDefn(i)->GetType();
      if (type != OFTInteger && type != OFTInteger64 && type != OFTReal)
        throw Error(file.string(), layerPlace(layer),
                    "attribute field " + quote(name) + " holds " +
                        OGRFieldDefn::GetFieldTypeName(type) + " values, not numbers");
      fields_.push_back(i);
    }
    if (!options.targetCrs.empty()) {
      const OGRSpatialReference* source = layer.GetSpatialRef();
      if (!source || source->IsEmpty())
        throw Error(file.string(), layerPlace(layer),
                    "the layer has no CRS, so it cannot be reprojected to " + options.targetCrs);
      OGRSpatialReference from(*source), to;
      if (to.SetFromUserInput(options.targetCrs.c_str()) != OGRERR_NONE)
        throw Error(
            file.string(), layerPlace(layer),
            "unknown target CRS " + quote(options.targetCrs) + gdal::QuietErrors::lastMessage());
      // x = easting / longitude, y = northing / latitude whatever the CRS's axis order
      // (EPSG:4326 is latitude first), as the layer's own coordinates are.
      from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
      to.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
      transform_.reset(OGRCreateCoordinateTransformation(&from, &to));
      if (!transform_)
        throw Error(file.string(), layerPlace(layer),
                    "no transformation to " + options.targetCrs + gdal::QuietErrors::lastMessage());
      crs_ = gdal::describeCrs(&to);
    } else {
      crs_ = gdal::describeCrs(layer.GetSpatialRef());
    }
  }

  const GisCrs& crs() const { return crs_; }

  std::vector<double> attributes(const OGRFeature& feature) {
    std::vector<double> values;
    for (int i : fields_) {
      if (feature.IsFieldSetAndNotNull(i)) {
        values.push_back(feature.GetFieldAsDouble(i));
      } else {
        values.push_back(std::numeric_limits<double>::quiet_NaN());
        ++report_.missingAttributeValues;
      }
    }
    return values;
  }

  // Node k of `points`: reprojected in double, minus the offset in double, then rounded once
  // to float — the order that keeps 465123.25 − 465000 = 123.25 exact.
  glm::vec3 node(const OGRSimpleCurve& curve, int k, GIntBig fid) {
    return place(curve.getX(k), curve.getY(k), curve.getZ(k), fid);
  }
  glm::vec3 place(double x, double y, double z, GIntBig fid) {
    const double sourceX = x, sourceY = y;  // Transform() may overwrite them when it fails
    if (transform_ && !transform_->Transform(1, &x, &y, &z))
      throw Error(file_.string(), featurePlace(layer_, fid),
                  "cannot transform (" + std::to_string(sourceX) + ", " + std::to_string(sourceY) +
                      ") to " + crs_.name + gdal::QuietErrors::lastMessage());
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
      throw Error(file_.string(), featurePlace(layer_, fid), "non-finite coordinate");
    const glm::dvec3 p(x - offset_.x, y - offset_.y, z - offset_.z);
    // Beyond float's reach the nodes would become infinite, or collapse onto one another.
    if (const double reach = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
        reach > double(kMaxSceneReach)) {
      char text[32];
      std::snprintf(text, sizeof text, "%.3g", reach);
      throw Error(file_.string(), featurePlace(layer_, fid),
                  std::string("a node lies ") + text +
                      " scene units from the origin, beyond the 1e15 a scene may reach");
    }
    return glm::vec3(p);
  }

 private:
  struct DestroyTransform {
    void operator()(OGRCoordinateTransformation* t) const {
      OGRCoordinateTransformation::DestroyCT(t);
    }
  };
  const std::filesystem::path& file_;
  OGRLayer& layer_;
  glm::dvec3 offset_;
  GisImportReport& report_;
  std::vector<int> fields_;
  std::unique_ptr<OGRCoordinateTransformation, DestroyTransform> transform_;
  GisCrs crs_;
};

void requireNonEmpty(const std::filesystem::path& file, OGRLayer& layer, std::int64_t count) {
  if (count <= 0) throw Error(file.string(), layerPlace(layer), "the layer is empty");
}

}  // namespace

bool gisCrsKnown(const std::string& crs) {
  gdal::registerDrivers();
  gdal::QuietErrors quiet;
  OGRSpatialReference srs;
  return srs.SetFromUserInput(crs.c_str()) == OGRERR_NONE;
}

namespace {

std::vector<GisLayerInfo> listLayersHere(const std::filesystem::path& file) {
  gdal::QuietErrors quiet;
  GDALDatasetUniquePtr dataset = openVectorSource(file);
  std::vector<GisLayerInfo> layers;
  for (int i = 0; i < dataset->GetLayerCount(); ++i)
    layers.push_back(describeLayer(*dataset->GetLayer(i)));
  return layers;
}

// A layer opened for import: the data source (which owns the layer), the checks shared by
// lines and points, and the feature reader.
struct OpenedLayer {
  GDALDatasetUniquePtr dataset;
  OGRLayer* layer;
  GisLayerInfo info;
  bool hasZ;
};

// `kinds`: the flat geometry types the layer may declare (wkbUnknown, a layer of mixed
// geometries as GeoJSON makes, is always accepted: each feature is checked instead).
OpenedLayer openLayer(const std::filesystem::path& file, const GisImportOptions& options,
                      std::initializer_list<OGRwkbGeometryType> kinds, const char* what) {
  OpenedLayer o{openVectorSource(file), nullptr, {}, false};
  o.layer = &chooseLayer(*o.dataset, file, options.layer);
  o.info = describeLayer(*o.layer);
  const OGRwkbGeometryType type = wkbFlatten(o.layer->GetGeomType());
  if (type != wkbUnknown && std::find(kinds.begin(), kinds.end(), type) == kinds.end())
    throw Error(file.string(), layerPlace(*o.layer),
                "the layer holds " + o.info.geometryType + " geometries, not " + what);
  requireNonEmpty(file, *o.layer, o.info.featureCount);
  o.hasZ = wkbHasZ(o.layer->GetGeomType());
  return o;
}

// Calls visit(fid, geometry, attributes) for every feature with a geometry, counting them.
// A feature GDAL failed to read (a truncated or damaged file: it then gives the feature
// without its geometry) is an error, not a feature without geometry.
template <class Visit>
void forEachFeature(const std::filesystem::path& file, OGRLayer& layer, FeatureReader& reader,
                    GisImportReport& report, bool& hasZ, Visit visit) {
  const auto failed = [&](const std::string& place) {
    if (CPLGetLastErrorType() >= CE_Failure)
      throw Error(file.string(), place,
                  "GDAL could not read it (the file is truncated or damaged)" +
                      gdal::QuietErrors::lastMessage());
  };
  CPLErrorReset();
  for (const OGRFeatureUniquePtr& feature : layer) {
    failed(featurePlace(layer, feature->GetFID()));
    ++report.features;
    const OGRGeometry* geometry = feature->GetGeometryRef();
    if (!geometry || geometry->IsEmpty()) {
      ++report.featuresWithoutGeometry;
      continue;
    }
    hasZ = hasZ || geometry->Is3D();
    visit(feature->GetFID(), *geometry, reader.attributes(*feature));
    CPLErrorReset();
  }
  failed(layerPlace(layer));  // a read that failed after the last feature
}

// What the importers share: the layer opened and checked for `Single` / `Multi` geometries,
// the output's layer, CRS, offset and heights, then visit(out, reader, fid, part index, part,
// attributes) for each single part of every feature (a feature of another geometry is an
// error); an error too when no item came out. `noun`: "line", "point", "polygon"; `none` ends
// the message for an empty result ("with two distinct nodes").
template <class Single, class Multi, class Out, class Item, class Visit>
Out importParts(const std::filesystem::path& file, const GisImportOptions& options,
                OGRwkbGeometryType single, OGRwkbGeometryType multi, const std::string& noun,
                std::vector<Item> Out::*items, const std::string& none, Visit visit) {
  gdal::QuietErrors quiet;
  OpenedLayer opened = openLayer(file, options, {single, multi}, (noun + "s").c_str());
  OGRLayer& layer = *opened.layer;
  Out out;
  out.layer = opened.info;
  out.offset = options.offset;
  out.hasZ = opened.hasZ;
  FeatureReader reader(file, layer, options, out.report);
  out.crs = reader.crs();
  forEachFeature(
      file, layer, reader, out.report, out.hasZ,
      [&](GIntBig fid, const OGRGeometry& geometry, const std::vector<double>& attributes) {
        const OGRwkbGeometryType type = wkbFlatten(geometry.getGeometryType());
        std::vector<const Single*> parts;
        if (type == single)
          parts.push_back(static_cast<const Single*>(&geometry));
        else if (type == multi)
          for (const Single* part : *static_cast<const Multi*>(&geometry)) parts.push_back(part);
        else
          throw Error(file.string(), featurePlace(layer, fid),
                      std::string("geometry is ") + geometry.getGeometryName() + ", not a " + noun);
        for (std::size_t p = 0; p < parts.size(); ++p)
          visit(out, reader, fid, int(p), *parts[p], attributes);
      });
  if ((out.*items).empty())
    throw Error(file.string(), layerPlace(layer),
                "no " + noun + none + " in " + std::to_string(out.report.features) + " features");
  return out;
}

GisLines importLinesHere(const std::filesystem::path& file, const GisImportOptions& options) {
  return importParts<OGRLineString, OGRMultiLineString>(
      file, options, wkbLineString, wkbMultiLineString, "line", &GisLines::polylines,
      " with two distinct nodes",
      [](GisLines& out, FeatureReader& reader, GIntBig fid, int part, const OGRLineString& line,
         const std::vector<double>& attributes) {
        GisPolyline polyline{fid, part, {}, attributes};
        for (int k = 0; k < line.getNumPoints(); ++k) {
          const glm::vec3 node = reader.node(line, k, fid);
          // A node equal (as the renderer will see it, in float) to the previous one makes a
          // zero-length segment with no direction: Konev18 §5's billboards and our rasteriser
          // need a direction per segment, so it is dropped.
          if (!polyline.points.empty() && polyline.points.back() == node) {
            ++out.report.repeatedNodes;
            continue;
          }
          polyline.points.push_back(node);
        }
        if (polyline.points.size() < 2)
          ++out.report.degenerateParts;
        else
          out.polylines.push_back(std::move(polyline));
      });
}

GisPoints importPointsHere(const std::filesystem::path& file, const GisImportOptions& options) {
  return importParts<OGRPoint, OGRMultiPoint>(
      file, options, wkbPoint, wkbMultiPoint, "point", &GisPoints::points, "",
      [](GisPoints& out, FeatureReader& reader, GIntBig fid, int part, const OGRPoint& point,
         const std::vector<double>& attributes) {
        out.points.push_back(
            {fid, part, reader.place(point.getX(), point.getY(), point.getZ(), fid), attributes});
      });
}

// A ring's nodes without repeats (as float) and without the closing node, or empty when fewer
// than three distinct nodes or no area are left (a bow tie's two lobes cancel): such a ring bounds
// nothing a triangulation or an extrusion could use.
std::vector<glm::vec3> readRing(const OGRLinearRing& ring, FeatureReader& reader, GIntBig fid,
                                GisImportReport& report) {
  std::vector<glm::vec3> nodes;
  for (int k = 0; k < ring.getNumPoints(); ++k) {
    const glm::vec3 node = reader.node(ring, k, fid);
    if (!nodes.empty() && nodes.back() == node) {
      ++report.repeatedNodes;
      continue;
    }
    nodes.push_back(node);
  }
  if (nodes.size() > 1 && nodes.back() == nodes.front()) nodes.pop_back();  // the closing node
  double twiceArea = 0.0;  // shoelace in the horizontal plane
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const glm::vec3& a = nodes[i];
    const glm::vec3& b = nodes[(i + 1) % nodes.size()];
    twiceArea += double(a.x) * double(b.y) - double(b.x) * double(a.y);
  }
  if (nodes.size() < 3 || twiceArea == 0.0) {
    ++report.degenerateRings;
    return {};
  }
  return nodes;
}

GisPolygons importPolygonsHere(const std::filesystem::path& file, const GisImportOptions& options) {
  return importParts<OGRPolygon, OGRMultiPolygon>(
      file, options, wkbPolygon, wkbMultiPolygon, "polygon", &GisPolygons::polygons,
      " with three distinct nodes enclosing an area",
      [](GisPolygons& out, FeatureReader& reader, GIntBig fid, int part, const OGRPolygon& shape,
         const std::vector<double>& attributes) {
        const OGRLinearRing* exterior = shape.getExteriorRing();
        if (!exterior) return;  // an empty part of a MultiPolygon
        GisPolygon polygon{fid, part, readRing(*exterior, reader, fid, out.report), {}, attributes};
        if (polygon.outer.empty()) {
          ++out.report.degenerateParts;
          return;
        }
        for (int h = 0; h < shape.getNumInteriorRings(); ++h) {
          std::vector<glm::vec3> hole =
              readRing(*shape.getInteriorRing(h), reader, fid, out.report);
          if (!hole.empty()) polygon.holes.push_back(std::move(hole));
        }
        out.polygons.push_back(std::move(polygon));
      });
}

}  // namespace

// GDAL runs in a worker process (cutaway/core/contained.hpp), its drivers registered once by
// the helper the workers are forked from.
const bool kDriversWarm = registerContainedWarmUp(&gdal::registerDrivers);
const ContainedReader<std::vector<GisLayerInfo>, &listLayersHere> containedLayers("gis-layers",
                                                                                  "GDAL");
const ContainedReader<GisLines, &importLinesHere, GisImportOptions> containedLines("gis-lines",
                                                                                   "GDAL");
const ContainedReader<GisPoints, &importPointsHere, GisImportOptions> containedPoints("gis-points",
                                                                                      "GDAL");
const ContainedReader<GisPolygons, &importPolygonsHere, GisImportOptions> containedPolygons(
    "gis-polygons", "GDAL");

std::vector<GisLayerInfo> listGisLayers(const std::filesystem::path& file) {
  return containedLayers(file);
}

GisLines importGisLines(const std::filesystem::path& file, const GisImportOptions& options) {
  return containedLines(file, options);
}

GisPoints importGisPoints(const std::filesystem::path& file, const GisImportOptions& options) {
  return containedPoints(file, options);
}

GisPolygons importGisPolygons(const std::filesystem::path& file, const GisImportOptions& options) {
  return containedPolygons(file, options);
}

}  // namespace cutaway
