// A volume with the CRS a user gave (volume/crs.hpp). parse_crs is in gdal_loader.cpp: it forwards
// to the GDAL module.

#include "geotandem/volume/crs.hpp"

#include <vector>

namespace geotandem::volume {
namespace {

// Everything as the inner volume has it, but the geometry's CRS.
class GeoreferencedVolume final : public Volume {
public:
  GeoreferencedVolume(std::shared_ptr<const Volume> inner, const Crs& crs) : inner_(std::move(inner)) {
    geometry_ = inner_->geometry();
    file_crs_ = geometry_.crs;
    geometry_.crs = crs;
  }
  const Geometry& geometry() const override { return geometry_; }
  std::string format() const override { return inner_->format(); }
  std::string source() const override { return inner_->source(); }
  std::vector<FormatDetail> format_details() const override {
    auto details = inner_->format_details();
    // The given CRS's unit is the one used: a file's warning about units without a CRS is moot.
    std::erase_if(details, [](const FormatDetail& d) { return d.key == "units_warning"; });
    if (!file_crs_.empty() && !(file_crs_ == geometry_.crs))
      details.push_back({"crs_override", "the file says the CRS is " + file_crs_.label() + "; " +
                                             geometry_.crs.label() + " as given replaces it"});
    return details;
  }
  std::optional<float> declared_no_data() const override { return inner_->declared_no_data(); }
  Index3 source_halo() const override { return inner_->source_halo(); }
  std::string reopen_hint() const override { return inner_->reopen_hint(); }
  std::string use_block_copy(const std::string& directory, Progress* progress,
                             const CancelToken& cancel) const override {
    return inner_->use_block_copy(directory, progress, cancel);
  }

protected:
  void read_box(const Box& box, std::span<float> out) const override { inner_->read(box, out); }

private:
  std::shared_ptr<const Volume> inner_;
  Geometry geometry_;
  Crs file_crs_;
};

} // namespace

std::unique_ptr<Volume> with_crs(std::unique_ptr<Volume> volume, const Crs& crs) {
  return std::make_unique<GeoreferencedVolume>(std::shared_ptr<const Volume>(std::move(volume)), crs);
}

std::shared_ptr<const Volume> with_crs(std::shared_ptr<const Volume> volume, const Crs& crs) {
  return std::make_shared<GeoreferencedVolume>(std::move(volume), crs);
}

} // namespace geotandem::volume
