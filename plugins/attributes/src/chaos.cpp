#include "geotandem/attributes/chaos.hpp"

#include <array>

#include "filters.hpp"
#include "geotandem/core/error.hpp"
#include "mirror.hpp"
#include "sym3_eigenvalues.hpp"

namespace geotandem::attributes {

const char* to_string(ChaosFormula formula) {
  return formula == ChaosFormula::planarity ? "planarity" : "marfurt";
}

const AttributeSpec& ChaosOptions::spec() {
  static const AttributeSpec spec{
      "chaos",
      "chaos from the eigenvalues l1 >= l2 >= l3 of the gradient structure tensor",
      1,
      {{"formula",
        ParamType::choice,
        std::string("planarity"),
        {},
        false,
        {"planarity", "marfurt"},
        "",
        "planarity: 2 l2/(l1+l2) in [0, 1]; marfurt: 2 l2/(l1+l3) in [0, 2]"},
       {"sigma_g",
        ParamType::real,
        1.0,
        {0, 20, true},
        false,
        {},
        "samples",
        "Gaussian width of the gradient (derivative-of-Gaussian filters, truncated at 3 sigma)"},
       {"sigma_t_across",
        ParamType::real,
        2.0,
        {0, 20, true},
        false,
        {},
        "samples",
        "Gaussian width of the tensor smoothing on the inline and crossline axes (truncated at 3 sigma)"},
       {"sigma_t_along",
        ParamType::real,
        3.0,
        {0, 20, true},
        false,
        {},
        "samples",
        "Gaussian width of the tensor smoothing along the trace (truncated at 3 sigma)"}}};
  return spec;
}

ChaosOptions ChaosOptions::from_params(const ParamValues& params) {
  ParamValues p = resolve(spec(), params);
  ChaosOptions options;
  options.formula = get_choice(p, "formula") == "marfurt" ? ChaosFormula::marfurt : ChaosFormula::planarity;
  options.sigma_g = get_real(p, "sigma_g");
  options.sigma_t_across = get_real(p, "sigma_t_across");
  options.sigma_t_along = get_real(p, "sigma_t_along");
  return options;
}

ParamValues ChaosOptions::to_params() const {
  return {{"formula", std::string(to_string(formula))},
          {"sigma_g", sigma_g},
          {"sigma_t_across", sigma_t_across},
          {"sigma_t_along", sigma_t_along}};
}

void ChaosOptions::validate() const {
  if (formula != ChaosFormula::planarity && formula != ChaosFormula::marfurt)
    throw InvalidArgument("attribute 'chaos': unknown formula value " + std::to_string(static_cast<int>(formula)));
  check_real(spec(), "sigma_g", sigma_g);
  check_real(spec(), "sigma_t_across", sigma_t_across);
  check_real(spec(), "sigma_t_along", sigma_t_along);
}

namespace {

ChaosOptions validated(const ChaosOptions& options) {
  options.validate();
  return options;
}

// The chaos of n samples from their smoothed tensor components T00, T11, T22, T01, T02, T12.
// Branch-free, so it vectorises; an AVX2 clone is picked at run time where the processor has it
// (the same operations in the same order: results do not depend on the clone).
[[gnu::target_clones("avx2", "default")]] void chaos_of_tensor(std::array<const float*, 6> t, float* out, std::size_t n,
                                                               bool planarity) {
  const float *t00 = t[0], *t11 = t[1], *t22 = t[2], *t01 = t[3], *t02 = t[4], *t12 = t[5];
  for (std::size_t m = 0; m < n; ++m) {
    const auto l = detail::sym3_eigenvalues(t00[m], t11[m], t22[m], t01[m], t02[m], t12[m]);
    // T is positive semi-definite; rounding can make its small eigenvalues slightly negative.
    const double l1 = std::max(l[0], 0.0), l2 = std::max(l[1], 0.0), l3 = std::max(l[2], 0.0);
    const double denominator = planarity ? l1 + l2 : l1 + l3;
    const bool positive = denominator > 0.0;
    const double value = 2.0 * l2 / (positive ? denominator : 1.0);
    out[m] = positive ? static_cast<float>(value) : 0.0f;
  }
}

Index3 chaos_halo(const ChaosOptions& o) {
  const int g = detail::gaussian_radius(o.sigma_g);
  return {g + detail::gaussian_radius(o.sigma_t_across), g + detail::gaussian_radius(o.sigma_t_across),
          g + detail::gaussian_radius(o.sigma_t_along)};
}

} // namespace

Chaos::Chaos(VolumePtr input, const ChaosOptions& options)
    : Attribute("chaos", to_string(validated(options).to_params()), {std::move(input)}, chaos_halo(options)),
      options_(options) {}

void Chaos::compute(const Box& box, std::span<float> out) const {
  using detail::Array3;
  using detail::correlate;
  const detail::Kernel smooth = detail::gaussian_kernel(options_.sigma_g);
  const detail::Kernel derive = detail::gaussian_derivative_kernel(options_.sigma_g);
  const detail::Kernel across = detail::gaussian_kernel(options_.sigma_t_across);
  const detail::Kernel along = detail::gaussian_kernel(options_.sigma_t_along);

  // Gradient on the box grown by the tensor's halo: 8 one-dimensional passes, sharing the first two.
  Array3 grad[3];
  {
    Array3 u = detail::read_mirrored(*inputs().front(), box, halo());
    Array3 a = correlate(u, 2, smooth);
    Array3 b = correlate(u, 2, derive);
    u.reset();
    Array3 aa = correlate(a, 1, smooth);
    Array3 ab = correlate(a, 1, derive);
    a.reset();
    Array3 ba = correlate(b, 1, smooth);
    b.reset();
    grad[0] = correlate(aa, 0, derive);
    grad[1] = correlate(ab, 0, smooth);
    grad[2] = correlate(ba, 0, smooth);
  }

  // Tensor components T00, T11, T22, T01, T02, T12, smoothed on the box itself.
  static constexpr int pairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};
  Array3 tensor[6];
  {
    Array3 product(grad[0].shape);
    for (int c = 0; c < 6; ++c) {
      const float* x = grad[pairs[c][0]].data.get();
      const float* y = grad[pairs[c][1]].data.get();
      float* p = product.data.get();
      for (std::size_t n = 0; n < product.count(); ++n)
        p[n] = x[n] * y[n];
      tensor[c] = correlate(correlate(correlate(product, 2, along), 1, across), 0, across);
    }
  }

  chaos_of_tensor({tensor[0].data.get(), tensor[1].data.get(), tensor[2].data.get(), tensor[3].data.get(),
                   tensor[4].data.get(), tensor[5].data.get()},
                  out.data(), out.size(), options_.formula == ChaosFormula::planarity);
}

} // namespace geotandem::attributes
