#pragma once
// Internals of the analytic kind: the planted items and their layout.

#include <variant>
#include <vector>

#include "frame.hpp"
#include "geotandem/synth/ground_truth.hpp"
#include "geotandem/synth/options.hpp"
#include "shapes.hpp"

namespace geotandem::synth::detail {

// Half width (body-frame units) of the smooth step from 0 to 1 across a body surface: the field is
// 0.5 + 0.5 * phi(d / w), phi(t) = t (3 - t^2) / 2 clamped to [-1, 1], d the signed distance
// estimate. So value >= 0.5 exactly inside, and the field has no kink near the surface.
inline constexpr double transition_width = 1.5;

// Components smaller than this are bubbles. Every planted bubble is at most 4/3 pi 1.2^3 = 7.2
// samples; every planted body is at least 4/3 pi 5 * 3 * 2.5 = 157 samples.
inline constexpr double analytic_bubble_threshold = 20.0;

using Item = std::variant<Ellipsoid, Shell, Tube, Sphere>;

struct AnalyticLayout {
  std::vector<Item> items;
  std::vector<volume::Box> influence; // samples where each item can exceed the background
  GroundTruth truth;
};

// Places the bodies and bubbles of a cube (deterministic in options.seed and options.shape).
AnalyticLayout layout_analytic(const AnalyticOptions& options, const Frame& frame);

} // namespace geotandem::synth::detail
