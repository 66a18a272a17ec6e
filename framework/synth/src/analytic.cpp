// The analytic kind: a smooth attribute-like field in [0, 1] whose isosurface at 0.5 is exactly
// the surface of the planted bodies.

#include "analytic.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geotandem/synth/synthetic.hpp"
#include "hash.hpp"
#include "item_grid.hpp"
#include "validate.hpp"

namespace geotandem::synth {
namespace detail {
namespace {

// Value of one body at signed distance estimate d (see transition_width).
inline double profile(double d) {
  const double t = d / transition_width;
  if (t >= 1.0) return 1.0;
  if (t <= -1.0) return 0.0;
  return 0.5 + 0.25 * t * (3.0 - t * t);
}

// A low, smooth background in [0, 0.24], well below the iso value, so that the field looks like an
// attribute and an extraction has to cope with values that vary everywhere.
struct Background {
  std::array<double, 3> omega{}, phase{};

  explicit Background(std::uint64_t seed) {
    LayoutRng rng(key(seed, Stream::background));
    for (int a = 0; a < 3; ++a) {
      omega[a] = 2.0 * std::numbers::pi / rng.uniform(20.0, 60.0);
      phase[a] = rng.uniform(0.0, 2.0 * std::numbers::pi);
    }
  }
  double term(int axis, std::int64_t index) const {
    return std::sin(omega[axis] * static_cast<double>(index) + phase[axis]);
  }
};

// An item's influence box in 32-bit indices (it is clipped to the cube, whose axes check_shape
// keeps within 2^20 samples): half the room of a volume::Box, for the 190,000 or so items of a
// 1024^3 cube.
class InfluenceBox {
public:
  InfluenceBox() = default;
  explicit InfluenceBox(const volume::Box& box) {
    for (int a = 0; a < 3; ++a) {
      lo_[static_cast<std::size_t>(a)] = static_cast<std::int32_t>(box.lo[a]);
      hi_[static_cast<std::size_t>(a)] = static_cast<std::int32_t>(box.hi[a]);
    }
  }
  volume::Box box() const {
    volume::Box box;
    for (int a = 0; a < 3; ++a) {
      box.lo[a] = lo_[static_cast<std::size_t>(a)];
      box.hi[a] = hi_[static_cast<std::size_t>(a)];
    }
    return box;
  }

private:
  std::array<std::int32_t, 3> lo_{}, hi_{};
};

class AnalyticCube final : public SyntheticCube {
public:
  AnalyticCube(const AnalyticOptions& options, const Frame& frame, AnalyticLayout layout)
      : SyntheticCube(std::move(layout.truth)), frame_(frame), grid_(options.shape, 32), background_(options.seed) {
    // Bodies first, then bubbles, each in storage of exactly its size.
    std::size_t bubbles = 0;
    for (const Item& item : layout.items)
      if (std::holds_alternative<Sphere>(item)) ++bubbles;
    const std::size_t body_count = layout.items.size() - bubbles;
    bodies_.reserve(body_count);
    bubbles_.reserve(bubbles);
    influence_.resize(layout.items.size());
    for (std::size_t n = 0; n < layout.items.size(); ++n) {
      const Item& item = layout.items[n];
      const std::size_t id = std::holds_alternative<Sphere>(item) ? body_count + bubbles_.size() : bodies_.size();
      if (const auto* sphere = std::get_if<Sphere>(&item))
        bubbles_.push_back(*sphere);
      else
        bodies_.push_back(item);
      influence_[id] = InfluenceBox(layout.influence[n]);
      grid_.add(static_cast<std::uint32_t>(id), layout.influence[n]);
    }
    grid_.seal();
  }

protected:
  void read_box(const volume::Box& box, std::span<float> out) const override {
    fill_background(box, out);
    for (std::uint32_t id : grid_.query(box)) {
      const volume::Box region = influence_[id].box().intersection(box);
      if (region.empty()) continue;
      if (id < bodies_.size())
        std::visit([&](const auto& item) { apply(item, region, box, out); }, bodies_[id]);
      else
        apply(bubbles_[id - bodies_.size()], region, box, out);
    }
  }

private:
  void fill_background(const volume::Box& box, std::span<float> out) const {
    std::array<std::vector<double>, 3> terms;
    for (int a = 0; a < 3; ++a)
      for (auto n = box.lo[a]; n < box.hi[a]; ++n)
        terms[a].push_back(background_.term(a, n));
    std::size_t at = 0;
    for (double ti : terms[0])
      for (double tj : terms[1])
        for (double tk : terms[2])
          out[at++] = static_cast<float>(0.12 + 0.04 * (ti + tj + tk));
  }

  // Raises the samples of `region` to the item's value where it is higher. Max is exact and
  // commutative, so the order of the items does not change a single bit. Every shape's distance
  // is split into what depends on x and y, computed once per column of samples, and the rest (the
  // same bits as point by point: shapes.hpp).
  template <class Shape>
  void apply(const Shape& shape, const volume::Box& region, const volume::Box& box, std::span<float> out) const {
    for (auto i = region.lo[0]; i < region.hi[0]; ++i)
      for (auto j = region.lo[1]; j < region.hi[1]; ++j) {
        float* row = out.data() + box.offset({i, j, region.lo[2]});
        auto column = shape.column(frame_.to_frame(static_cast<double>(i), static_cast<double>(j), 0.0));
        for (auto k = region.lo[2]; k < region.hi[2]; ++k) {
          const double d = shape.signed_distance(column, static_cast<double>(k));
          if (d <= -transition_width) continue;
          float& sample = row[k - region.lo[2]];
          sample = std::max(sample, static_cast<float>(profile(d)));
        }
      }
  }

  Frame frame_;
  // Bubbles are most of the items of a large cube (about 170,000 at 1024^3) and the smallest, so
  // they are kept apart: a variant takes the room of its largest shape, six times a sphere's.
  // Item ids run over the bodies, then the bubbles; influence_ is indexed by id.
  std::vector<Item> bodies_;
  std::vector<Sphere> bubbles_;
  std::vector<InfluenceBox> influence_;
  ItemGrid grid_;
  Background background_;
};

} // namespace
} // namespace detail

std::unique_ptr<SyntheticCube> make_analytic(const AnalyticOptions& options) {
  detail::check_shape("analytic cube shape", options.shape);
  detail::check_range("body_density", options.body_density, {0.0, 200.0}, "bodies per million samples");
  detail::check_range("bubble_density", options.bubble_density, {0.0, 2000.0}, "bubbles per million samples");
  detail::Frame frame(options.survey, options.shape);
  auto layout = detail::layout_analytic(options, frame);
  return std::make_unique<detail::AnalyticCube>(options, frame, std::move(layout));
}

} // namespace geotandem::synth
