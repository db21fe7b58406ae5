// What the GDAL readers share (gis_import.cpp, raster_terrain.cpp): driver registration, quiet
// error capture, and CRS descriptions.
#pragma once

#include <cpl_error.h>
#include <ogr_spatialref.h>

#include <string>

#include "cutaway/io/gis_import.hpp"

namespace cutaway::gdal {

void registerDrivers();

// GDAL reports problems through a global handler that prints to stderr by default; while we
// read, errors are kept quiet and the last message goes into our own Error instead.
class QuietErrors {
 public:
  QuietErrors() {
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
  }
  ~QuietErrors() { CPLPopErrorHandler(); }
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;
  // ": <GDAL's last message>", or "" when it said nothing.
  static std::string lastMessage() {
    const char* m = CPLGetLastErrorMsg();
    return m && *m ? std::string(": ") + m : std::string();
  }
};

// Name, authority code (found by matching when the source has none, as ESRI .prj files) and
// WKT2; empty for a missing or empty CRS.
GisCrs describeCrs(const OGRSpatialReference* srs);

}  // namespace cutaway::gdal
