#include "geotandem/tandem/layer.hpp"

namespace geotandem::tandem {

volume::Index3 LatticeIds::start(std::uint64_t id) const {
  std::uint64_t cell = id / 3u;
  auto nk = static_cast<std::uint64_t>(shape[2]), nj = static_cast<std::uint64_t>(shape[1]);
  return {static_cast<std::int64_t>(cell / (nj * nk)), static_cast<std::int64_t>((cell / nk) % nj),
          static_cast<std::int64_t>(cell % nk)};
}

} // namespace geotandem::tandem
