#include <cmath>

#include "formats.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::volume::detail {
namespace {

class NanGuard final : public Volume {
public:
  NanGuard(std::unique_ptr<Volume> inner, const OpenOptions& options)
      : inner_(std::move(inner)), policy_(options.nan_policy), fill_(options.fill_value) {}

  const Geometry& geometry() const override { return inner_->geometry(); }
  std::string format() const override { return inner_->format(); }
  std::string source() const override { return inner_->source(); }
  std::vector<FormatDetail> format_details() const override { return inner_->format_details(); }

protected:
  void read_box(const Box& box, std::span<float> out) const override {
    inner_->read(box, out);
    for (std::size_t n = 0; n < out.size(); ++n) {
      if (std::isfinite(out[n])) continue;
      if (policy_ == NanPolicy::fill) {
        out[n] = fill_;
        continue;
      }
      // Recover the sample's global index from its offset in the box's C order.
      auto nk = static_cast<std::size_t>(box.size(2)), nj = static_cast<std::size_t>(box.size(1));
      Index3 at{box.lo[0] + static_cast<std::int64_t>(n / (nj * nk)),
                box.lo[1] + static_cast<std::int64_t>((n / nk) % nj), box.lo[2] + static_cast<std::int64_t>(n % nk)};
      std::string declared;
      for (const FormatDetail& d : inner_->format_details())
        if (d.key == kNoDataDetail)
          declared = " (the file declares " + d.value.substr(0, d.value.find(' ')) + " as its no-data value)";
      throw DataError(std::string(std::isnan(out[n]) ? "NaN" : "infinite") + " sample at index (" +
                          std::to_string(at[0]) + ", " + std::to_string(at[1]) + ", " + std::to_string(at[2]) + ")" +
                          declared,
                      {inner_->source(), {}, {}, "box " + box.to_string(), {}},
                      "pass --nan fill to treat such samples as outside every body, or repair the file");
    }
  }

private:
  std::unique_ptr<Volume> inner_;
  NanPolicy policy_;
  float fill_;
};

} // namespace

std::unique_ptr<Volume> guard_nan(std::unique_ptr<Volume> inner, const OpenOptions& options) {
  return std::make_unique<NanGuard>(std::move(inner), options);
}

} // namespace geotandem::volume::detail
