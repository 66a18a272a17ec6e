#pragma once
// The constraints on a collapse ab -> c, separate from its cost: when the advancing front allows
// it (time lag) and whether the region's open faces allow it (extended time lag). Each is a small
// interface with one implementation per variant of the algorithm, chosen from the options once.
// Both depend only on a and b (positions, heights, radii), never on c, so a decision stays valid
// until a or b changes.

#include <memory>

#include "geotandem/tandem/region.hpp"
#include "quadric.hpp"

namespace geotandem::tandem::detail {

// What the constraints look at.
struct EdgeGeometry {
  Vec3 a{}, b{};
  double height_a = 0.0, height_b = 0.0;
  double rad_a = 1.0, rad_b = 1.0;

  double length() const { return norm(a - b); }
  Vec3 midpoint() const { return 0.5 * (a + b); }
  double height() const { return 0.5 * (height_a + height_b); }
  double rad() const { return 0.5 * (length() + rad_a + rad_b); }
  double reach() const { return height() + rad(); }
};

// The front: an edge may collapse only while key(edge) < rank(front).
class FrontRule {
public:
  virtual ~FrontRule() = default;
  virtual double key(const EdgeGeometry& e) const = 0;
};

// Attali's time lag: key = reach(c) = height(c) + rad(c).
class TimeLag final : public FrontRule {
public:
  double key(const EdgeGeometry& e) const override { return e.reach(); }
};

// No time lag: only edges with a vertex on the front cross-section wait (the last layer is not
// simplified, so that the next one can be appended). key = the larger coordinate along the axis.
class FrontOnly final : public FrontRule {
public:
  explicit FrontOnly(int axis) : axis_(static_cast<std::size_t>(axis)) {}
  double key(const EdgeGeometry& e) const override { return e.a[axis_] > e.b[axis_] ? e.a[axis_] : e.b[axis_]; }

private:
  std::size_t axis_;
};

// The open faces of the region: which one holds an edge back and where (its index in the
// region's open_faces() and the point of it the edge reaches), or index -1 when none does and the
// edge may collapse.
class FaceRule {
public:
  virtual ~FaceRule() = default;
  virtual Region::NearestFace holding_face(const EdgeGeometry& e, const Region& region) const = 0;
};

// Extended time lag: the ball around the midpoint of ab with radius rad(c) must stay clear of
// every open face (the nearest one holds it back otherwise, at its point nearest the midpoint).
class BallInRegion final : public FaceRule {
public:
  Region::NearestFace holding_face(const EdgeGeometry& e, const Region& region) const override {
    const Region::NearestFace nearest = region.nearest_open_face(e.midpoint());
    return nearest.distance > e.rad() ? Region::NearestFace{} : nearest;
  }
};

// Without the extended time lag: edges with a vertex on an open face are frozen (so that the
// vertices a neighbour will weld to keep their lattice ids), everything else is free.
class FrozenFaceVertices final : public FaceRule {
public:
  Region::NearestFace holding_face(const EdgeGeometry& e, const Region& region) const override {
    for (const auto& p : {e.a, e.b}) {
      const Region::NearestFace nearest = region.nearest_open_face(p);
      if (nearest.distance <= kOnFace) return nearest;
    }
    return {};
  }

private:
  static constexpr double kOnFace = 1e-9; // Region::on_open_face's tolerance
};

inline std::unique_ptr<FrontRule> make_front_rule(bool time_lag, int axis) {
  if (time_lag) return std::make_unique<TimeLag>();
  return std::make_unique<FrontOnly>(axis);
}
inline std::unique_ptr<FaceRule> make_face_rule(bool extended_time_lag) {
  if (extended_time_lag) return std::make_unique<BallInRegion>();
  return std::make_unique<FrozenFaceVertices>();
}

} // namespace geotandem::tandem::detail
