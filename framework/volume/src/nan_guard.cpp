#include <cmath>
#include <cstdio>
#include <optional>

#include "formats.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::volume::detail {
namespace {

class NanGuard final : public Volume {
public:
  NanGuard(std::unique_ptr<Volume> inner, const OpenOptions& options)
      : inner_(std::move(inner)), policy_(options.nan_policy), fill_(options.fill_value), no_data_(options.no_data) {}

  const Geometry& geometry() const override { return inner_->geometry(); }
  std::string format() const override { return inner_->format(); }
  std::string source() const override { return inner_->source(); }
  std::vector<FormatDetail> format_details() const override {
    std::vector<FormatDetail> details = inner_->format_details();
    if (no_data_) details.push_back({"no_data_given", no_data_text(*no_data_) + " (samples equal to it are missing)"});
    return details;
  }

protected:
  void read_box(const Box& box, std::span<float> out) const override {
    inner_->read(box, out);
    for (std::size_t n = 0; n < out.size(); ++n) {
      if (std::isfinite(out[n]) && !(no_data_ && out[n] == *no_data_)) continue;
      if (policy_ == NanPolicy::fill) {
        out[n] = fill_;
        continue;
      }
      // Recover the sample's global index from its offset in the box's C order.
      auto nk = static_cast<std::size_t>(box.size(2)), nj = static_cast<std::size_t>(box.size(1));
      Index3 at{box.lo[0] + static_cast<std::int64_t>(n / (nj * nk)),
                box.lo[1] + static_cast<std::int64_t>((n / nk) % nj), box.lo[2] + static_cast<std::int64_t>(n % nk)};
      const float v = out[n];
      std::string what = std::isnan(v) ? "NaN" : std::isinf(v) ? "infinite" : "no-data";
      what += " sample at index (" + std::to_string(at[0]) + ", " + std::to_string(at[1]) + ", " +
              std::to_string(at[2]) + ")";
      if (no_data_ && v == *no_data_) {
        what += " (" + no_data_text(v) + ", the no-data value given)";
      } else if (std::isnan(v)) {
        for (const FormatDetail& d : inner_->format_details())
          if (d.key == kNoDataDetail)
            what += " (the file declares " + d.value.substr(0, d.value.find(' ')) + " as no data)";
      }
      throw DataError(what, {inner_->source(), {}, {}, "box " + box.to_string(), {}},
                      "pass --nan fill to treat such samples as outside every body, or repair the file");
    }
  }

private:
  static std::string no_data_text(float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", static_cast<double>(value));
    return text;
  }

  std::unique_ptr<Volume> inner_;
  NanPolicy policy_;
  float fill_;
  std::optional<float> no_data_;
};

} // namespace

std::unique_ptr<Volume> guard_nan(std::unique_ptr<Volume> inner, const OpenOptions& options) {
  return std::make_unique<NanGuard>(std::move(inner), options);
}

} // namespace geotandem::volume::detail
