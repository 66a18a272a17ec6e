// Coordinate reference systems through GDAL's OSR (module side): parsing what a user gives
// (volume/crs.hpp) and describing what a file declares (gdal_common.hpp).

#include <ogr_spatialref.h>

#include <cmath>

#include "gdal_common.hpp"
#include "gdal_module.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::volume::detail {
namespace gdal {
namespace {

// "m", "ft" or "ftUS" for the units OSR names; the name itself for any other.
std::string unit_symbol(const std::string& name, double metres) {
  if (std::abs(metres - 1.0) < 1e-12) return "m";
  if (std::abs(metres - 0.3048) < 1e-12) return "ft";
  if (std::abs(metres - 1200.0 / 3937.0) < 1e-12) return "ftUS";
  return name.empty() ? "unit" : name;
}

} // namespace

Crs describe(const OGRSpatialReference& srs, const std::string& what) {
  if (srs.IsGeographic() && !srs.IsProjected())
    throw InvalidArgument(what + " is a geographic CRS (" + std::string(srs.GetName() ? srs.GetName() : "unnamed") +
                              ": latitude and longitude in degrees)",
                          {},
                          "geotandem's map coordinates are projected x (east) and y (north) in a linear unit; give "
                          "the survey's projected CRS, e.g. EPSG:23031 (ED50 / UTM zone 31N)");
  Crs crs;
  crs.name = srs.GetName() ? srs.GetName() : "";
  const char* authority = srs.GetAuthorityName(nullptr);
  const char* code = srs.GetAuthorityCode(nullptr);
  if (authority && code) {
    crs.code = std::string(authority) + ":" + code;
  } else {
    // A WKT without an identifier: the EPSG code when OSR recognises the definition.
    OGRSpatialReference copy(srs);
    ErrorCapture quiet;
    if (copy.AutoIdentifyEPSG() == OGRERR_NONE && copy.GetAuthorityName(nullptr) && copy.GetAuthorityCode(nullptr))
      crs.code = std::string(copy.GetAuthorityName(nullptr)) + ":" + copy.GetAuthorityCode(nullptr);
  }
  char* wkt = nullptr;
  const char* const options[] = {"FORMAT=WKT2_2019", "MULTILINE=NO", nullptr};
  if (srs.exportToWkt(&wkt, options) != OGRERR_NONE || !wkt || !*wkt) {
    CPLFree(wkt);
    throw InvalidArgument(what + ": OSR cannot write it as WKT", {}, "give an EPSG code such as EPSG:23031");
  }
  crs.wkt = wkt;
  CPLFree(wkt);
  const char* unit_name = nullptr;
  const double metres = srs.GetLinearUnits(&unit_name);
  crs.unit_name = unit_name ? unit_name : "";
  crs.metres_per_unit = metres > 0.0 ? metres : 1.0;
  crs.unit = unit_symbol(crs.unit_name, crs.metres_per_unit);
  return crs;
}

Crs parse_crs(const std::string& text) {
  register_drivers();
  if (text.empty())
    throw InvalidArgument("the CRS is empty", {}, "give an EPSG code such as EPSG:23031, or the CRS's WKT");
  ErrorCapture errors;
  OGRSpatialReference srs;
  const std::string shown = text.size() > 60 ? text.substr(0, 57) + "..." : text;
  // No files, no URLs: the text itself is the CRS.
  if (srs.SetFromUserInput(text.c_str(), OGRSpatialReference::SET_FROM_USER_INPUT_LIMITATIONS) != OGRERR_NONE)
    throw InvalidArgument("'" + shown + "' is not a coordinate reference system GDAL knows" + errors.text(), {},
                          "give an EPSG code of a projected CRS (EPSG:23031 is ED50 / UTM zone 31N; see "
                          "https://epsg.io), or the CRS's WKT");
  return describe(srs, "'" + shown + "'");
}

std::optional<Crs> crs_of_text(const std::string& text, const std::string& where, const std::string& path) {
  try {
    return parse_crs(text);
  } catch (const InvalidArgument& e) {
    throw FormatError(where + ": " + e.message(), {path},
                      "give the CRS yourself with --crs (input.crs in a recipe), which replaces the file's");
  }
}

std::optional<Crs> crs_of_srs(const OGRSpatialReference* srs, const std::string& where, const std::string& path) {
  if (!srs || srs->IsEmpty()) return std::nullopt;
  try {
    return describe(*srs, where);
  } catch (const InvalidArgument& e) {
    throw FormatError(e.message(), {path},
                      "give the CRS yourself with --crs (input.crs in a recipe), which replaces the file's");
  }
}

} // namespace gdal
} // namespace geotandem::volume::detail
