#include "geotandem/store/query.hpp"

#include <charconv>
#include <cmath>
#include <vector>

#include "geotandem/core/error.hpp"

namespace geotandem::store {
namespace {

std::string trim(const std::string& text) {
  auto begin = text.find_first_not_of(" \t");
  if (begin == std::string::npos) return {};
  auto end = text.find_last_not_of(" \t");
  return text.substr(begin, end - begin + 1);
}

std::optional<double> parse_number(const std::string& raw) {
  std::string text = trim(raw);
  if (!text.empty() && text.front() == '+') text.erase(0, 1);
  double value = 0.0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty() || !std::isfinite(value))
    return std::nullopt;
  return value;
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    auto at = text.find(separator, start);
    parts.push_back(text.substr(start, at == std::string::npos ? std::string::npos : at - start));
    if (at == std::string::npos) return parts;
    start = at + 1;
  }
}

double reduce_axial(double degrees) {
  if (degrees >= 0.0 && degrees <= 180.0) return degrees;
  double r = std::fmod(degrees, 180.0);
  return r < 0.0 ? r + 180.0 : r;
}

} // namespace

bool AzimuthRange::contains(double azimuth) const {
  if (from <= to) return azimuth >= from && azimuth <= to;
  return azimuth >= from || azimuth <= to;
}

bool WorldBox::intersects(const std::array<double, 3>& other_min, const std::array<double, 3>& other_max) const {
  for (int a = 0; a < 3; ++a)
    if (other_max[a] < min[a] || other_min[a] > max[a]) return false;
  return true;
}

AzimuthRange parse_azimuth_range(const std::string& text) {
  auto parts = split(text, ':');
  std::optional<double> from, to;
  if (parts.size() == 2) {
    from = parse_number(parts[0]);
    to = parse_number(parts[1]);
  }
  if (!from || !to)
    throw InvalidArgument("bad azimuth range '" + text + "'", {},
                          "write FROM:TO in degrees clockwise from north, e.g. 30:60, or 170:10 to wrap through north");
  return AzimuthRange{reduce_axial(*from), reduce_axial(*to)};
}

WorldBox parse_world_box(const std::string& text) {
  auto parts = split(text, ',');
  std::vector<double> values;
  if (parts.size() == 6)
    for (const auto& part : parts)
      if (auto v = parse_number(part)) values.push_back(*v);
  if (values.size() != 6)
    throw InvalidArgument("bad box '" + text + "'", {},
                          "write six numbers x0,y0,z0,x1,y1,z1: two opposite corners in world coordinates");
  WorldBox box;
  for (int a = 0; a < 3; ++a) {
    box.min[a] = std::min(values[a], values[a + 3]);
    box.max[a] = std::max(values[a], values[a + 3]);
  }
  return box;
}

SortKey parse_sort_key(const std::string& text) {
  if (text == "key") return SortKey::key;
  if (text == "volume") return SortKey::volume;
  if (text == "azimuth") return SortKey::azimuth;
  if (text == "selection") return SortKey::selection;
  throw InvalidArgument("unknown sort order '" + text + "'", {}, "use key, volume, azimuth or selection");
}

const char* to_string(SortKey key) {
  switch (key) {
  case SortKey::key: return "key";
  case SortKey::volume: return "volume";
  case SortKey::azimuth: return "azimuth";
  case SortKey::selection: return "selection";
  }
  return "key";
}

} // namespace geotandem::store
