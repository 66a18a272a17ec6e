#pragma once
// The smoothed gradient structure tensor of a box, streamed plane by plane along axis 0.
//
// Per sample it is the same arithmetic as filtering whole 3D arrays pass after pass (gradient:
// along the trace, then crossline, then inline; tensor smoothing in the same order), so the result
// is independent of the box and of the streaming. What streaming changes is memory traffic: a
// plane of every intermediate stays in cache while it is used, instead of 30-odd passes over
// arrays of the whole tile, and working memory is a few dozen planes, not a dozen tiles.

#include <array>
#include <functional>

#include "array3.hpp"
#include "filters.hpp"
#include "geotandem/volume/volume.hpp"

namespace geotandem::attributes::detail {

struct TensorFilters {
  Kernel smooth;       // Gaussian of the gradient
  Kernel derive;       // its derivative
  Kernel across;       // tensor smoothing on axes 0 and 1
  Kernel along;        // tensor smoothing on axis 2
  volume::Index3 halo; // what the tensor at a box needs around it: gradient plus smoothing radii
};

// Components T00, T11, T22, T01, T02, T12 of one output plane (n1 x n2 samples each, C order).
using TensorPlane = std::array<const float*, 6>;

// Calls `plane(i, t)` for each plane i = 0 .. n0 - 1 of `box`, in order, with the tensor of that
// plane (valid during the call). Reads the input once (box grown by filters.halo, mirrored).
void stream_structure_tensor(const volume::Volume& input, const volume::Box& box, const TensorFilters& filters,
                             const std::function<void(std::int64_t, const TensorPlane&)>& plane);

} // namespace geotandem::attributes::detail
