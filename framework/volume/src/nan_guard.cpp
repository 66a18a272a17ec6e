#include <cmath>
#include <limits>
#include <optional>

#include "formats.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/core/params.hpp"

namespace geotandem::volume::detail {
namespace {

// The NaN policy over a reader: NaN and infinite samples, and samples equal to the no-data value
// given when opening or declared by the file, are missing (an error, or the fill value).
class NanGuard final : public Volume {
public:
  NanGuard(std::unique_ptr<Volume> inner, const OpenOptions& options)
      : inner_(std::move(inner)), policy_(options.nan_policy), fill_(options.fill_value),
        given_(options.no_data.value_or(kNone)), declared_(inner_->declared_no_data().value_or(kNone)) {}

  const Geometry& geometry() const override { return inner_->geometry(); }
  std::string format() const override { return inner_->format(); }
  std::string source() const override { return inner_->source(); }
  std::vector<FormatDetail> format_details() const override {
    std::vector<FormatDetail> details = inner_->format_details();
    if (!std::isnan(given_))
      details.push_back({"no_data_given", number_text(given_) + " (samples equal to it are missing)"});
    return details;
  }
  std::optional<float> declared_no_data() const override { return inner_->declared_no_data(); }
  std::string reopen_hint() const override { return inner_->reopen_hint(); }
  std::string use_block_copy(const std::string& directory, Progress* progress,
                             const CancelToken& cancel) const override {
    return inner_->use_block_copy(directory, progress, cancel);
  }

protected:
  void read_box(const Box& box, std::span<float> out) const override {
    inner_->read(box, out);
    for (std::size_t n = 0; n < out.size(); ++n) {
      const float v = out[n];
      if (std::isfinite(v) && v != given_ && v != declared_) continue; // kNone equals nothing
      if (policy_ == NanPolicy::fill) {
        out[n] = fill_;
        continue;
      }
      // Recover the sample's global index from its offset in the box's C order.
      auto nk = static_cast<std::size_t>(box.size(2)), nj = static_cast<std::size_t>(box.size(1));
      Index3 at{box.lo[0] + static_cast<std::int64_t>(n / (nj * nk)),
                box.lo[1] + static_cast<std::int64_t>((n / nk) % nj), box.lo[2] + static_cast<std::int64_t>(n % nk)};
      std::string what = std::isnan(v) ? "NaN" : std::isinf(v) ? "infinite" : "no-data";
      what += " sample at index (" + std::to_string(at[0]) + ", " + std::to_string(at[1]) + ", " +
              std::to_string(at[2]) + ")";
      if (v == given_)
        what += " (" + number_text(v) + ", the no-data value given)";
      else if (v == declared_)
        what += " (the file declares " + number_text(v) + " as no data)";
      throw DataError(what, {inner_->source(), {}, {}, "box " + box.to_string(), {}},
                      "pass --nan fill to treat such samples as outside every body, or repair the file");
    }
  }

private:
  static constexpr float kNone = std::numeric_limits<float>::quiet_NaN();

  std::unique_ptr<Volume> inner_;
  NanPolicy policy_;
  float fill_;
  float given_;    // OpenOptions::no_data, or kNone
  float declared_; // the file's own, or kNone
};

} // namespace

std::unique_ptr<Volume> guard_nan(std::unique_ptr<Volume> inner, const OpenOptions& options) {
  return std::make_unique<NanGuard>(std::move(inner), options);
}

} // namespace geotandem::volume::detail
