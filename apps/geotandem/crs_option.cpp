// --crs on the commands that open a cube (extract, info, run-workflow): the CRS of its map
// coordinates, checked through OSR before any work.

#include "command.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/volume/crs.hpp"

namespace geotandem::app {

void add_crs_option(CLI::App& cmd, std::string& crs) {
  cmd.add_option("--crs", crs,
                 "the coordinate reference system of the cube's map coordinates: an EPSG code (EPSG:23031) or a "
                 "WKT; replaces what the file says (without either, outputs say \"no CRS given\")")
      ->type_name("CRS");
}

std::optional<volume::Crs> crs_option(const std::string& text) {
  if (text.empty()) return std::nullopt;
  try {
    return volume::parse_crs(text);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument("--crs: " + e.message(), {}, e.hint());
  }
}

} // namespace geotandem::app
