#pragma once
// The cost of a collapse ab -> c (Attali, Cohen-Steiner, Edelsbrunner; ALGORITHM.md):
//   eps_alpha(c) = sqrt(c^T [(1 - alpha) H_c / W_c + alpha G_c / W] c),
//   W = 3 area(S_ab) sqrt(W_c) / E0,
// with c the minimiser of eps_alpha and the shape error eps_0(c) = sqrt(h_c(c)) bounded by E0.
// Pure arithmetic on the quadrics: it knows nothing of the mesh, the queues or the constraints.

#include "quadric.hpp"

namespace geotandem::tandem::detail {

// What the cost needs to know about an edge ab.
struct CostInputs {
  Quadric shape;           // H_a + H_b
  double weight = 0.0;     // W_a + W_b
  Isotropy isotropy;       // over S_ab, the triangles containing a or b
  Vec3 a{}, b{};           // current endpoint positions
  unsigned fixed_axes = 0; // bit i: c[i] must equal fixed_value[i] (a cube face)
  Vec3 fixed_value{};
  // Volume preservation (optional): c must satisfy volume_normal . (c - midpoint) = volume_offset,
  // the plane on which the collapse leaves the enclosed volume unchanged.
  bool preserve_volume = false;
  Vec3 volume_normal{};
  double volume_offset = 0.0;
};

struct Candidate {
  Vec3 position{};
  double cost = 0.0;        // eps_alpha(c), the queue key
  double shape_error = 0.0; // eps_0(c) = sqrt(h_c(c)), bounded by E0
  bool fallback = false;    // the minimiser was distrusted: c is the best of a, b, midpoint
};

class AttaliCost {
public:
  // max_error = E0 > 0 (voxel units), alpha in [0, 1].
  AttaliCost(double max_error, double alpha) : max_error_(max_error), alpha_(alpha) {}

  double max_error() const { return max_error_; }
  double alpha() const { return alpha_; }

  // The combined quadric of an edge, ready to be minimised or evaluated anywhere.
  struct Prepared {
    Quadric combined;        // (1 - alpha) H / W_c + alpha G / W
    double inv_weight = 0.0; // 1 / W_c: the shape term is in.shape / W_c
    const CostInputs* in = nullptr;
    bool degenerate = false; // the patch has no area: any position costs nothing
  };
  Prepared prepare(const CostInputs& in) const;

  // The minimiser of eps_alpha under the fixed axes (and on the volume plane when asked). When the
  // system is singular (alpha = 0 on a flat patch) the pseudo-inverse around the midpoint gives the
  // nearest minimiser. A minimiser farther than sqrt(|ab|^2 + area(S_ab)) from the midpoint comes
  // from a nearly singular system: it is replaced by the best of fallback_positions().
  Candidate best(const Prepared& p) const;
  // eps_alpha and eps_0 at a given position (fixed axes are the caller's business).
  Candidate at(const Prepared& p, const Vec3& c) const;
  // Simple positions to try when the minimiser is distrusted or would flip a triangle, all on the
  // fixed axes: with volume preservation, the midpoint projected on the volume plane and the point
  // of the line ab on it (near the segment); without, the midpoint, a and b. Returns the count.
  int fallback_positions(const Prepared& p, Vec3 out[3]) const;
  // The best of fallback_positions() by eps_alpha.
  Candidate best_fallback(const Prepared& p) const;

private:
  // The common case: no fixed axis, a regular system (one inverse serves the minimiser and the
  // volume plane). Returns false when the system is too ill-conditioned for it.
  bool best_free(const Prepared& p, Vec3& c) const;

  double max_error_;
  double alpha_;
};

// Solves M y = r for the symmetric n x n system (n = 1..3, row-major in m[9]) in the least-squares
// sense, with the pseudo-inverse around `ref` when M is singular or ill-conditioned:
// y = ref + M^+ (r - M ref). Exposed for tests.
void solve_symmetric(int n, const double* m, const double* r, const double* ref, double* y);

} // namespace geotandem::tandem::detail
