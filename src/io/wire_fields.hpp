// io/wire_fields.hpp — the members of the types file readers hand back from a child process
// (cutaway/core/contained.hpp), named once for writing and reading.
#pragma once

#include "cutaway/geometry/mesh.hpp"
#include "cutaway/geometry/volume.hpp"
#include "cutaway/io/gis_import.hpp"
#include "cutaway/io/volume_import.hpp"

namespace cutaway {

template <class Archive>
void wireFields(Archive& a, MeshReport& r) {
  a(r.droppedDegenerate, r.normalsComputed, r.boundaryEdges, r.nonManifoldEdges, r.misorientedEdges,
    r.watertight, r.windingReversed);
}

template <class Archive>
void wireFields(Archive& a, GridLayout& g) {
  a(g.columns, g.rows, g.cell);
}

template <class Archive>
void wireFields(Archive& a, Mesh& m) {
  a(m.positions, m.normals, m.triangles, m.report, m.grid);
}

template <class Archive>
void wireFields(Archive& a, Volume& v) {
  a(v.dims, v.values, v.indexToWorld, v.voxelType, v.minValue, v.maxValue);
}

template <class Archive>
void wireFields(Archive& a, VolumeLimits& l) {
  a(l.maxVoxels);
}

template <class Archive>
void wireFields(Archive& a, GisCrs& c) {
  a(c.name, c.authority, c.wkt);
}

template <class Archive>
void wireFields(Archive& a, GisImportOptions& o) {
  a(o.layer, o.attributes, o.targetCrs, o.offset);
}

template <class Archive>
void wireFields(Archive& a, GisExtent& e) {
  a(e.min, e.max);
}

template <class Archive>
void wireFields(Archive& a, GisLayerInfo& l) {
  a(l.name, l.geometryType, l.featureCount, l.crs, l.extent, l.fields, l.fieldTypes);
}

template <class Archive>
void wireFields(Archive& a, GisImportReport& r) {
  a(r.features, r.featuresWithoutGeometry, r.repeatedNodes, r.degenerateParts,
    r.missingAttributeValues, r.degenerateRings);
}

template <class Archive>
void wireFields(Archive& a, GisLayerImport& l) {
  a(l.layer, l.crs, l.offset, l.hasZ, l.report);
}

template <class Archive>
void wireFields(Archive& a, GisPolyline& p) {
  a(p.featureId, p.part, p.points, p.attributes);
}

template <class Archive>
void wireFields(Archive& a, GisPoint& p) {
  a(p.featureId, p.part, p.position, p.attributes);
}

template <class Archive>
void wireFields(Archive& a, GisPolygon& p) {
  a(p.featureId, p.part, p.outer, p.holes, p.attributes);
}

template <class Archive>
void wireFields(Archive& a, GisLines& l) {
  a(static_cast<GisLayerImport&>(l), l.polylines);
}

template <class Archive>
void wireFields(Archive& a, GisPoints& p) {
  a(static_cast<GisLayerImport&>(p), p.points);
}

template <class Archive>
void wireFields(Archive& a, GisPolygons& p) {
  a(static_cast<GisLayerImport&>(p), p.polygons);
}

}  // namespace cutaway
