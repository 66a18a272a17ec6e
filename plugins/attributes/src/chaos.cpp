#include "geotandem/attributes/chaos.hpp"
#include "geotandem/core/simd.hpp"

#include <array>

#include "filters.hpp"
#include "geotandem/core/error.hpp"
#include "structure_tensor.hpp"
#include "sym3_eigenvalues.hpp"

namespace geotandem::attributes {

const char* to_string(ChaosFormula formula) {
  return formula == ChaosFormula::planarity ? "planarity" : "marfurt";
}

const OptionsTable<ChaosOptions>& ChaosOptions::table() {
  static const OptionsTable<ChaosOptions> table{
      "chaos",
      "chaos from the eigenvalues l1 >= l2 >= l3 of the gradient structure tensor",
      1,
      {choice(ParamSpec{.name = "formula",
                        .type = ParamType::choice,
                        .help = "planarity: 2 l2/(l1+l2) in [0, 1]; marfurt: 2 l2/(l1+l3) in [0, 2]",
                        .choices = {"planarity", "marfurt"}},
              &ChaosOptions::formula),
       option(gaussian_width("sigma_g",
                             "Gaussian width of the gradient (derivative-of-Gaussian filters, truncated at 3 sigma)"),
              &ChaosOptions::sigma_g),
       option(gaussian_width("sigma_t_across",
                             "Gaussian width of the tensor smoothing on the inline and crossline axes "
                             "(truncated at 3 sigma)"),
              &ChaosOptions::sigma_t_across),
       option(gaussian_width("sigma_t_along",
                             "Gaussian width of the tensor smoothing along the trace (truncated at 3 sigma)"),
              &ChaosOptions::sigma_t_along)}};
  return table;
}

namespace {

// The chaos of n samples from their smoothed tensor components T00, T11, T22, T01, T02, T12.
// Branch-free, so it vectorises; an AVX2 clone is picked at run time where the processor has it
// (the same operations in the same order: results do not depend on the clone).
GEOTANDEM_AVX2_CLONES void chaos_of_tensor(std::array<const float*, 6> t, float* out, std::size_t n, bool planarity) {
  const float *t00 = t[0], *t11 = t[1], *t22 = t[2], *t01 = t[3], *t02 = t[4], *t12 = t[5];
  // planarity: l1 + l2; marfurt: l1 + l3. Weights rather than a select keep the loop vectorisable
  // (adding 0 * l, l finite and >= 0, changes nothing).
  const double w2 = planarity ? 1.0 : 0.0, w3 = 1.0 - w2;
  for (std::size_t m = 0; m < n; ++m) {
    const auto l = detail::sym3_eigenvalues(t00[m], t11[m], t22[m], t01[m], t02[m], t12[m]);
    // T is positive semi-definite; rounding can make its small eigenvalues slightly negative.
    const double l1 = std::max(l[0], 0.0), l2 = std::max(l[1], 0.0), l3 = std::max(l[2], 0.0);
    const double denominator = l1 + w2 * l2 + w3 * l3;
    const double safe = denominator > 0.0 ? denominator : 1.0;
    out[m] = static_cast<float>(denominator > 0.0 ? 2.0 * l2 / safe : 0.0);
  }
}

Index3 chaos_halo(const ChaosOptions& o) {
  const int g = detail::gaussian_radius(o.sigma_g);
  return {g + detail::gaussian_radius(o.sigma_t_across), g + detail::gaussian_radius(o.sigma_t_across),
          g + detail::gaussian_radius(o.sigma_t_along)};
}

} // namespace

Chaos::Chaos(VolumePtr input, const ChaosOptions& options)
    : Attribute("chaos", to_string(ChaosOptions::validated(options).to_params()), {std::move(input)},
                chaos_halo(options)),
      options_(options) {}

void Chaos::compute(const Box& box, std::span<float> out) const {
  const detail::TensorFilters filters{
      detail::gaussian_kernel(options_.sigma_g), detail::gaussian_derivative_kernel(options_.sigma_g),
      detail::gaussian_kernel(options_.sigma_t_across), detail::gaussian_kernel(options_.sigma_t_along), halo()};
  const auto plane_count = static_cast<std::size_t>(box.size(1) * box.size(2));
  const bool planarity = options_.formula == ChaosFormula::planarity;
  detail::stream_structure_tensor(
      *inputs().front(), box, filters, [&](std::int64_t i, const detail::TensorPlane& tensor) {
        chaos_of_tensor(tensor, out.data() + static_cast<std::size_t>(i) * plane_count, plane_count, planarity);
      });
}

} // namespace geotandem::attributes
