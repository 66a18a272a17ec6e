#include "attali_cost.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

namespace geotandem::tandem::detail {
namespace {

// Eigenvalues below this fraction of the trace count as zero: the matrices are normalised (H / W_c
// has trace 1), so this is about the square of the smallest meaningful curvature ratio.
constexpr double kRelativeEigenFloor = 1e-9;
// |N|^2 below this: the collapse cannot change the enclosed volume (a degenerate patch).
constexpr double kNoVolumeChange = 1e-24;

template <int N> void pseudo_solve(const double* m, const double* r, const double* ref, double* y) {
  using Mat = Eigen::Matrix<double, N, N>;
  using Vec = Eigen::Matrix<double, N, 1>;
  Mat a;
  Vec rhs, r0;
  for (int i = 0; i < N; ++i) {
    for (int j = 0; j < N; ++j)
      a(i, j) = m[i * N + j];
    rhs(i) = r[i];
    r0(i) = ref[i];
  }
  Eigen::SelfAdjointEigenSolver<Mat> eig;
  if constexpr (N == 1) {
    eig.compute(a);
  } else {
    eig.computeDirect(a);
  }
  const Vec lambda = eig.eigenvalues();
  const double floor = kRelativeEigenFloor * std::max(lambda.cwiseAbs().sum(), std::numeric_limits<double>::min());
  const Vec residual = rhs - a * r0;
  Vec proj = eig.eigenvectors().transpose() * residual;
  for (int i = 0; i < N; ++i)
    proj(i) = std::abs(lambda(i)) > floor ? proj(i) / lambda(i) : 0.0;
  const Vec sol = r0 + eig.eigenvectors() * proj;
  for (int i = 0; i < N; ++i)
    y[i] = sol(i);
}

} // namespace

void solve_symmetric(int n, const double* m, const double* r, const double* ref, double* y) {
  if (n == 1) {
    const double floor = kRelativeEigenFloor * std::abs(m[0]);
    y[0] = std::abs(m[0]) > std::max(floor, std::numeric_limits<double>::min()) ? r[0] / m[0] : ref[0];
    return;
  }
  if (n == 2) {
    const double det = m[0] * m[3] - m[1] * m[2];
    const double tr = std::abs(m[0]) + std::abs(m[3]);
    if (std::abs(det) > kRelativeEigenFloor * tr * tr) {
      y[0] = (r[0] * m[3] - m[1] * r[1]) / det;
      y[1] = (m[0] * r[1] - r[0] * m[2]) / det;
      return;
    }
    pseudo_solve<2>(m, r, ref, y);
    return;
  }
  // n == 3: Cramer's rule when clearly regular (the common case with alpha > 0), else eigen.
  const double c00 = m[4] * m[8] - m[5] * m[7];
  const double c01 = m[5] * m[6] - m[3] * m[8];
  const double c02 = m[3] * m[7] - m[4] * m[6];
  const double det = m[0] * c00 + m[1] * c01 + m[2] * c02;
  const double tr = std::abs(m[0]) + std::abs(m[4]) + std::abs(m[8]);
  if (std::abs(det) > kRelativeEigenFloor * tr * tr * tr) {
    const double inv = 1.0 / det;
    const double c10 = m[2] * m[7] - m[1] * m[8];
    const double c11 = m[0] * m[8] - m[2] * m[6];
    const double c12 = m[1] * m[6] - m[0] * m[7];
    const double c20 = m[1] * m[5] - m[2] * m[4];
    const double c21 = m[2] * m[3] - m[0] * m[5];
    const double c22 = m[0] * m[4] - m[1] * m[3];
    // inverse = adjugate / det, adjugate = transpose of cofactors.
    y[0] = (c00 * r[0] + c10 * r[1] + c20 * r[2]) * inv;
    y[1] = (c01 * r[0] + c11 * r[1] + c21 * r[2]) * inv;
    y[2] = (c02 * r[0] + c12 * r[1] + c22 * r[2]) * inv;
    return;
  }
  pseudo_solve<3>(m, r, ref, y);
}

AttaliCost::Prepared AttaliCost::prepare(const CostInputs& in) const {
  Prepared p;
  p.in = &in;
  const double area = in.isotropy.area;
  if (!(in.weight > 0.0) || !(area > 0.0)) {
    p.degenerate = true;
    return p;
  }
  p.inv_weight = 1.0 / in.weight;
  const double big_w = 3.0 * area * std::sqrt(in.weight) / max_error_;
  const double ws = (1.0 - alpha_) * p.inv_weight;
  for (int i = 0; i < 10; ++i)
    p.combined.m[static_cast<std::size_t>(i)] = ws * in.shape.m[static_cast<std::size_t>(i)];
  if (alpha_ > 0.0) {
    // + alpha / W times the isotropy quadric [[A I, -s], [-s^T, q]].
    const double wg = alpha_ / big_w;
    const Isotropy& g = in.isotropy;
    p.combined.m[0] += wg * g.area;
    p.combined.m[4] += wg * g.area;
    p.combined.m[7] += wg * g.area;
    p.combined.m[3] -= wg * g.s[0];
    p.combined.m[6] -= wg * g.s[1];
    p.combined.m[8] -= wg * g.s[2];
    p.combined.m[9] += wg * g.q;
  }
  return p;
}

Candidate AttaliCost::at(const Prepared& p, const Vec3& c) const {
  Candidate out;
  out.position = c;
  if (p.degenerate) return out;
  out.cost = std::sqrt(std::max(0.0, p.combined.eval(c)));
  out.shape_error = std::sqrt(std::max(0.0, p.in->shape.eval(c) * p.inv_weight));
  return out;
}

namespace {

// The volume plane restricted to the free coordinates: n . y = k (absolute coordinates). Returns
// |n|^2 (tiny when the collapse cannot change the volume along the free axes).
double restricted_plane(const CostInputs& in, const Vec3& mid, int count, const int* free_axes, double* n, double& k) {
  k = in.volume_offset;
  for (std::size_t j = 0; j < 3; ++j)
    if (in.fixed_axes & (1u << j)) k -= in.volume_normal[j] * (in.fixed_value[j] - mid[j]);
  // The plane is given relative to the midpoint; the free coordinates are absolute.
  double nn = 0.0;
  for (int row = 0; row < count; ++row) {
    const auto axis = static_cast<std::size_t>(free_axes[row]);
    n[row] = in.volume_normal[axis];
    k += n[row] * mid[axis];
    nn += n[row] * n[row];
  }
  return nn;
}

// Moves the unconstrained minimiser y of the free coordinates onto the volume plane along the
// metric of the quadric (Lagrange multiplier): y - lambda M^-1 n. When M^-1 n is useless (n in
// the null space of a singular M), projects orthogonally instead.
void constrain_to_plane(const CostInputs& in, const Vec3& mid, int count, const int* free_axes, const double* m,
                        double* y) {
  double n[3], k = 0.0;
  const double nn = restricted_plane(in, mid, count, free_axes, n, k);
  if (!(nn > kNoVolumeChange)) return;
  double ny = 0.0;
  for (int row = 0; row < count; ++row)
    ny += n[row] * y[row];
  double zero[3] = {0.0, 0.0, 0.0}, z[3];
  solve_symmetric(count, m, n, zero, z);
  double nz = 0.0, trace = 0.0;
  for (int row = 0; row < count; ++row) {
    nz += n[row] * z[row];
    trace += std::abs(m[row * count + row]);
  }
  if (nz > 1e-9 * nn / std::max(trace, std::numeric_limits<double>::min())) {
    const double lambda = (ny - k) / nz;
    for (int row = 0; row < count; ++row)
      y[row] -= lambda * z[row];
  } else {
    const double t = (k - ny) / nn;
    for (int row = 0; row < count; ++row)
      y[row] += t * n[row];
  }
}

int free_axes_of(const CostInputs& in, int* free_axes) {
  int n = 0;
  for (int i = 0; i < 3; ++i)
    if (!(in.fixed_axes & (1u << i))) free_axes[n++] = i;
  return n;
}

Vec3 with_fixed(const CostInputs& in, Vec3 c) {
  for (int i = 0; i < 3; ++i)
    if (in.fixed_axes & (1u << i)) c[i] = in.fixed_value[i];
  return c;
}
} // namespace

int AttaliCost::fallback_positions(const Prepared& p, Vec3 out[3]) const {
  const CostInputs& in = *p.in;
  const Vec3 mid = with_fixed(in, 0.5 * (in.a + in.b));
  const Vec3 a = with_fixed(in, in.a), b = with_fixed(in, in.b);
  if (!in.preserve_volume) {
    out[0] = mid;
    out[1] = a;
    out[2] = b;
    return 3;
  }
  int free_axes[3];
  const int count = free_axes_of(in, free_axes);
  double n[3], k = 0.0;
  const double nn = restricted_plane(in, 0.5 * (in.a + in.b), count, free_axes, n, k);
  if (!(nn > kNoVolumeChange)) { // the volume does not depend on c
    out[0] = mid;
    out[1] = a;
    out[2] = b;
    return 3;
  }
  // The midpoint projected on the plane.
  double nm = 0.0, na = 0.0, nb = 0.0;
  for (int row = 0; row < count; ++row) {
    const auto axis = static_cast<std::size_t>(free_axes[row]);
    nm += n[row] * mid[axis];
    na += n[row] * a[axis];
    nb += n[row] * b[axis];
  }
  int found = 0;
  Vec3 projected = mid;
  for (int row = 0; row < count; ++row)
    projected[static_cast<std::size_t>(free_axes[row])] += (k - nm) / nn * n[row];
  out[found++] = projected;
  // The line through a and b meets the plane at t (0 at a, 1 at b): keep it near the segment.
  if (std::abs(nb - na) > 1e-12 * std::sqrt(nn) * (1.0 + norm(b - a))) {
    const double t = (k - na) / (nb - na);
    if (t >= -0.5 && t <= 1.5) out[found++] = a + t * (b - a);
  }
  return found;
}

Candidate AttaliCost::best_fallback(const Prepared& p) const {
  Vec3 positions[3];
  const int count = fallback_positions(p, positions);
  Candidate best = at(p, positions[0]);
  for (int i = 1; i < count; ++i) {
    Candidate c = at(p, positions[i]);
    if (c.cost < best.cost) best = c;
  }
  best.fallback = true;
  return best;
}

bool AttaliCost::best_free(const Prepared& p, Vec3& c) const {
  const CostInputs& in = *p.in;
  const auto& q = p.combined.m;
  // M = [[q0 q1 q2] [q1 q4 q5] [q2 q5 q7]] is symmetric: six cofactors.
  const double c00 = q[4] * q[7] - q[5] * q[5], c01 = q[2] * q[5] - q[1] * q[7], c02 = q[1] * q[5] - q[2] * q[4];
  const double c11 = q[0] * q[7] - q[2] * q[2], c12 = q[1] * q[2] - q[0] * q[5], c22 = q[0] * q[4] - q[1] * q[1];
  const double det = q[0] * c00 + q[1] * c01 + q[2] * c02;
  const double tr = std::abs(q[0]) + std::abs(q[4]) + std::abs(q[7]);
  if (!(std::abs(det) > kRelativeEigenFloor * tr * tr * tr)) return false;
  const double inv = 1.0 / det;
  auto apply = [&](double x, double y, double z, Vec3& out) {
    out[0] = (c00 * x + c01 * y + c02 * z) * inv;
    out[1] = (c01 * x + c11 * y + c12 * z) * inv;
    out[2] = (c02 * x + c12 * y + c22 * z) * inv;
  };
  apply(-q[3], -q[6], -q[8], c);
  if (in.preserve_volume) {
    // Onto the plane n.(c - mid) = k along the metric of M (Lagrange): c - lambda M^-1 n.
    const Vec3& n = in.volume_normal;
    const double nn = dot(n, n);
    if (nn > kNoVolumeChange) {
      const Vec3 mid = 0.5 * (in.a + in.b);
      const double gap = dot(n, c - mid) - in.volume_offset;
      Vec3 z;
      apply(n[0], n[1], n[2], z);
      const double nz = dot(n, z);
      if (nz > 1e-9 * nn / tr) {
        c = c - (gap / nz) * z;
      } else {
        c = c - (gap / nn) * n;
      }
    }
  }
  return true;
}

Candidate AttaliCost::best(const Prepared& p) const {
  const CostInputs& in = *p.in;
  const Vec3 mid = with_fixed(in, 0.5 * (in.a + in.b));
  if (p.degenerate) return at(p, mid);
  const double limit2 = norm2(in.a - in.b) + in.isotropy.area;
  if (in.fixed_axes == 0) {
    Vec3 c;
    if (best_free(p, c)) {
      if (!(norm2(c - mid) <= limit2)) return best_fallback(p); // also catches NaN
      return at(p, c);
    }
  }
  // Gradient of x^T Q x (homogeneous) vanishes where A c = -b; fixed coordinates move to the
  // right-hand side and the remaining rows form a smaller symmetric system.
  int free_axes[3];
  const int n = free_axes_of(in, free_axes);
  Vec3 c = mid;
  if (n > 0) {
    double m[9], r[3], ref[3], y[3];
    for (int row = 0; row < n; ++row) {
      const int i = free_axes[row];
      double rhs = -p.combined.at(i, 3);
      for (int j = 0; j < 3; ++j)
        if (in.fixed_axes & (1u << j)) rhs -= p.combined.at(i, j) * in.fixed_value[j];
      r[row] = rhs;
      ref[row] = mid[i];
      for (int col = 0; col < n; ++col)
        m[row * n + col] = p.combined.at(i, free_axes[col]);
    }
    solve_symmetric(n, m, r, ref, y);
    if (in.preserve_volume) constrain_to_plane(in, 0.5 * (in.a + in.b), n, free_axes, m, y);
    for (int row = 0; row < n; ++row)
      c[free_axes[row]] = y[row];
  }
  // A minimiser far outside the patch comes from a nearly singular system: distrust it.
  if (!(norm2(c - mid) <= limit2)) return best_fallback(p); // also catches NaN
  return at(p, c);
}

} // namespace geotandem::tandem::detail
