#include "geotandem/volume/volume.hpp"

#include "geotandem/core/error.hpp"

namespace geotandem::volume {

void Volume::read(const Box& box, std::span<float> out) const {
  const Geometry& g = geometry();
  if (box.empty() || !g.bounds().contains(box))
    throw InvalidArgument("box " + box.to_string() + " is not inside the cube " + g.bounds().to_string(), {source()},
                          "ask for a box within the cube's shape");
  if (out.size() != box.count())
    throw InvalidArgument("buffer of " + std::to_string(out.size()) + " samples for box " + box.to_string() + " of " +
                              std::to_string(box.count()) + " samples",
                          {source()});
  read_box(box, out);
}

std::vector<float> Volume::read(const Box& box) const {
  std::vector<float> out(box.count());
  read(box, out);
  return out;
}

MemoryVolume::MemoryVolume(Geometry geometry, std::vector<float> samples, std::string source)
    : geometry_(std::move(geometry)), samples_(std::move(samples)), source_(std::move(source)) {
  geometry_.validate();
  if (samples_.size() != geometry_.sample_count())
    throw InvalidArgument("memory volume of shape " + geometry_.bounds().to_string() + " needs " +
                          std::to_string(geometry_.sample_count()) + " samples, got " +
                          std::to_string(samples_.size()));
}

std::unique_ptr<MemoryVolume> MemoryVolume::copy_of(const Volume& volume) {
  const Geometry& g = volume.geometry();
  return std::make_unique<MemoryVolume>(g, volume.read(g.bounds()), volume.source());
}

void MemoryVolume::read_box(const Box& box, std::span<float> out) const {
  copy_region(samples_.data(), geometry_.bounds(), out.data(), box, box);
}

std::vector<std::string> open_warnings(const Volume& volume) {
  std::vector<std::string> out;
  for (const FormatDetail& detail : volume.format_details()) {
    if (detail.key == "coordinates")
      out.push_back(volume.source() + ": trace coordinates in " + detail.value);
    else if (detail.key == "assumed")
      out.push_back(volume.source() + ": not in the file, assumed: " + detail.value);
    else if (detail.key == "missing_lines")
      out.push_back(volume.source() + ": missing lines: " + detail.value);
    else if (detail.key == "slow_reads" || detail.key == "crs_override" || detail.key == "units_warning")
      out.push_back(volume.source() + ": " + detail.value);
  }
  return out;
}

} // namespace geotandem::volume
