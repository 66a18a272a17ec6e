#pragma once
// Coordinate reference systems given as text (an EPSG code such as "EPSG:23031", or a WKT), checked
// through GDAL's OSR, and a volume whose geometry carries the CRS a user gave. The CRS itself is
// volume::Crs (geometry.hpp): plain text, readable without GDAL.

#include <memory>
#include <string>

#include "geotandem/volume/geometry.hpp"
#include "geotandem/volume/volume.hpp"

namespace geotandem::volume {

// Parses `text` ("EPSG:23031", "epsg:2227", a WKT 1 or 2 string, "EPSG:23031+5715") through OSR.
// Loads the GDAL module (gdal_module.hpp). Throws InvalidArgument with OSR's reason when OSR does
// not know the text (a wrong code), and when the CRS is geographic (latitude and longitude in
// degrees: geotandem's map coordinates are projected x and y in a linear unit). Files and URLs are
// not read (OSR's user-input limitations).
Crs parse_crs(const std::string& text);

// `volume` with `crs` in its geometry, replacing what the file says. When the file says another
// CRS, the volume's format details say so (key "crs_override", shown as a warning by
// open_warnings).
std::unique_ptr<Volume> with_crs(std::unique_ptr<Volume> volume, const Crs& crs);
std::shared_ptr<const Volume> with_crs(std::shared_ptr<const Volume> volume, const Crs& crs);

} // namespace geotandem::volume
