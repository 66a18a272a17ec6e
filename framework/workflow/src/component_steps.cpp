#include "geotandem/workflow/component_steps.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/measure.hpp"

namespace geotandem::workflow {
namespace {

std::vector<store::ComponentRow> rows_of(const store::ComponentStore& store, const std::string& selection) {
  store::Query q;
  if (!selection.empty()) q.selection = selection;
  return store.query(q);
}

// Area of the sphere that encloses `volume`: (36 pi V^2)^(1/3).
double sphere_area(double volume) {
  return std::cbrt(36.0 * std::numbers::pi * volume * volume);
}

bool in_axial_range(double a, double lo, double hi) {
  return lo <= hi ? a >= lo && a <= hi : a >= lo || a <= hi;
}

} // namespace

BubbleResult remove_bubbles(store::ComponentStore& store, const BubbleRemoval& rules) {
  if (rules.min_volume < 0 || rules.min_volume_fraction < 0 || rules.min_volume_fraction > 1 ||
      rules.min_volume_percentile < 0 || rules.min_volume_percentile > 100)
    throw InvalidArgument("remove_bubbles: a rule is out of range", {store.directory().string()},
                          "min_volume >= 0, min_volume_fraction in [0, 1], min_volume_percentile in [0, 100]");
  if (rules.min_samples < 0)
    throw InvalidArgument("remove_bubbles: min_samples is negative", {store.directory().string()});
  auto rows = rows_of(store, rules.from);
  if (rules.min_samples > 0)
    for (const auto& r : rows)
      if (!r.samples_counted)
        throw InvalidArgument("remove_bubbles: component " + std::to_string(r.key) +
                                  " has no volume in samples (the store was written before samples were counted)",
                              {store.directory().string()}, "use min_volume, or extract again into a new store");
  BubbleResult result;
  result.before = rows.size();
  std::vector<double> volumes;
  for (const auto& r : rows)
    if (r.stats.closed) volumes.push_back(r.stats.volume);
  std::sort(volumes.begin(), volumes.end());
  double threshold = rules.min_volume;
  if (!volumes.empty()) {
    threshold = std::max(threshold, rules.min_volume_fraction * volumes.back());
    if (rules.min_volume_percentile > 0) {
      // Nearest-rank percentile.
      auto rank = static_cast<std::size_t>(std::ceil(rules.min_volume_percentile / 100.0 * double(volumes.size())));
      threshold = std::max(threshold, volumes[std::clamp<std::size_t>(rank, 1, volumes.size()) - 1]);
    }
  }
  result.threshold = threshold;
  // Volumes are signed: the inner surface of a hollow body encloses a negative volume, so any
  // volume rule drops it, but without one nothing is dropped for its volume.
  const bool by_volume = rules.min_volume > 0 || rules.min_volume_fraction > 0 || rules.min_volume_percentile > 0;
  std::vector<const store::ComponentRow*> kept;
  for (const auto& r : rows) {
    if (r.stats.triangle_count < rules.min_triangles) continue;
    if (rules.min_samples > 0 && r.stats.samples < rules.min_samples) continue;
    // Cut bodies are closed by caps and measured like any other, unless closed_only drops them.
    if (rules.closed_only && r.stats.cut_by_border) continue;
    const bool big = !by_volume || (r.stats.closed ? r.stats.volume >= threshold
                                                   : !rules.closed_only && r.stats.area >= sphere_area(threshold));
    if (big) kept.push_back(&r);
  }
  std::sort(kept.begin(), kept.end(), [](const auto* a, const auto* b) {
    return a->stats.volume != b->stats.volume ? a->stats.volume > b->stats.volume : a->key < b->key;
  });
  for (const auto* r : kept)
    result.kept.push_back(r->key);
  result.after = kept.size();
  nlohmann::json params = {{"step", "remove_bubbles"},
                           {"min_volume", rules.min_volume},
                           {"min_volume_fraction", rules.min_volume_fraction},
                           {"min_volume_percentile", rules.min_volume_percentile},
                           {"min_triangles", rules.min_triangles},
                           {"min_samples", rules.min_samples},
                           {"closed_only", rules.closed_only},
                           {"from", rules.from},
                           {"threshold", threshold},
                           {"before", result.before},
                           {"after", result.after}};
  store.save_selection(rules.selection, result.kept, params.dump(), true);
  return result;
}

AzimuthResult sort_by_azimuth(store::ComponentStore& store, const AzimuthSorting& rules) {
  if (rules.bins < 1 || rules.bins > 180)
    throw InvalidArgument("sort_by_azimuth: bins is " + std::to_string(rules.bins), {store.directory().string()},
                          "use 1 to 180 bins");
  std::string from = rules.from;
  if (from.empty()) {
    auto all = store.selections();
    auto newest =
        std::max_element(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.created < b.created; });
    if (newest != all.end() && newest->name != rules.selection) from = newest->name;
  }
  auto rows = rows_of(store, from);
  AzimuthResult result;
  result.before = rows.size();
  result.histogram.assign(static_cast<std::size_t>(rules.bins), 0);
  std::vector<const store::ComponentRow*> inside;
  std::vector<double> azimuths, weights;
  for (const auto& r : rows) {
    double a = std::fmod(std::fmod(r.stats.azimuth, 180.0) + 180.0, 180.0);
    if (!in_axial_range(a, rules.azimuth_min, rules.azimuth_max)) continue;
    inside.push_back(&r);
    auto bin = std::min<std::size_t>(static_cast<std::size_t>(a / 180.0 * rules.bins), result.histogram.size() - 1);
    ++result.histogram[bin];
    azimuths.push_back(a);
    weights.push_back(r.stats.volume > 0 ? r.stats.volume : r.stats.area);
  }
  result.after = inside.size();
  if (!azimuths.empty()) {
    result.mean_azimuth = mesh::axial_mean_deg(azimuths, weights);
    double s = 0, c = 0, w = 0;
    for (std::size_t n = 0; n < azimuths.size(); ++n) {
      double t = 2.0 * azimuths[n] * std::numbers::pi / 180.0;
      s += weights[n] * std::sin(t);
      c += weights[n] * std::cos(t);
      w += weights[n];
    }
    result.resultant_length = w > 0 ? std::hypot(s, c) / w : 0.0;
  }
  auto bin_of = [&](const store::ComponentRow* r) {
    double a = std::fmod(std::fmod(r->stats.azimuth, 180.0) + 180.0, 180.0);
    return std::min<std::size_t>(static_cast<std::size_t>(a / 180.0 * rules.bins), result.histogram.size() - 1);
  };
  std::sort(inside.begin(), inside.end(), [&](const auto* a, const auto* b) {
    auto ca = result.histogram[bin_of(a)], cb = result.histogram[bin_of(b)];
    if (ca != cb) return ca > cb;
    if (bin_of(a) != bin_of(b)) return bin_of(a) < bin_of(b);
    return a->stats.volume != b->stats.volume ? a->stats.volume > b->stats.volume : a->key < b->key;
  });
  for (const auto* r : inside)
    result.ranking.push_back(r->key);
  nlohmann::json params = {{"step", "sort_by_azimuth"},
                           {"bins", rules.bins},
                           {"azimuth_min", rules.azimuth_min},
                           {"azimuth_max", rules.azimuth_max},
                           {"from", from},
                           {"histogram", result.histogram},
                           {"mean_azimuth", result.mean_azimuth},
                           {"resultant_length", result.resultant_length},
                           {"ranking", result.ranking}};
  store.save_selection(rules.selection, result.ranking, params.dump(), true);
  return result;
}

} // namespace geotandem::workflow
