#pragma once
// Chaos from the gradient structure tensor:
//   g = grad(G_sigma_g * u)                 (derivative-of-Gaussian filters, separable)
//   T = G_sigma_t * (g g^T)                 (sigma_t_across on inline and crossline, sigma_t_along
//                                            on the sample axis)
// with eigenvalues l1 >= l2 >= l3 of T at each voxel, and
//   planarity (default): 2 l2 / (l1 + l2), in [0, 1]   (1 - planarity in some papers)
//   marfurt:             2 l2 / (l1 + l3), in [0, 2]
// Flat or dipping parallel reflectors give a rank-one T and chaos 0; isotropic noise gives values
// near the top of the range. Where T is zero (a constant input) chaos is 0.
//
// Gaussians are truncated at radius r(sigma) = max(1, ceil(3 sigma)) and normalised; the halo is
// r(sigma_g) + r(sigma_t) per axis: (9, 9, 12) with the defaults. Gradients are in samples (index
// space), not metres. Beyond the cube the input is mirrored (attribute.hpp).

#include "geotandem/attributes/attribute.hpp"
#include "geotandem/attributes/params.hpp"

namespace geotandem::attributes {

enum class ChaosFormula { planarity, marfurt };
const char* to_string(ChaosFormula formula);

struct ChaosOptions : DeclaredOptions<ChaosOptions> {
  ChaosFormula formula = ChaosFormula::planarity;
  double sigma_g = 1.0;        // samples, gradient smoothing (all axes)
  double sigma_t_across = 2.0; // samples, tensor smoothing on inline and crossline
  double sigma_t_along = 3.0;  // samples, tensor smoothing along the trace

  // Its declaration (spec(), from_params(), to_params() and validate() follow: DeclaredOptions).
  static const OptionsTable<ChaosOptions>& table();
};

class Chaos final : public Attribute {
public:
  // Throws InvalidArgument for a null input or invalid options.
  explicit Chaos(VolumePtr input, const ChaosOptions& options = {});
  const ChaosOptions& options() const { return options_; }

protected:
  void compute(const Box& box, std::span<float> out) const override;

private:
  ChaosOptions options_;
};

} // namespace geotandem::attributes
