#pragma once
// Byte streams of the working-surface wire form (surface_wire.cpp): core's byte streams plus
// points; a damaged payload is a DataError.
#include <span>

#include "geotandem/core/byte_stream.hpp"
#include "geotandem/core/error.hpp"
#include "working_mesh.hpp"

namespace geotandem::tandem::detail {

class Writer : public ByteWriter {
public:
  using ByteWriter::put;
  void put(const Vec3& v) {
    for (double x : v)
      put(x);
  }
};

class Reader : public ByteReader<DataError> {
public:
  explicit Reader(std::span<const std::byte> in) : ByteReader<DataError>(in, "working-surface record") {}
  Vec3 vec() {
    Vec3 v;
    for (double& x : v)
      x = get<double>("a point");
    return v;
  }
};

} // namespace geotandem::tandem::detail
