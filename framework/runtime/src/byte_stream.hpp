#pragma once
// The runtime's messages in core's byte streams: a damaged payload is a ProtocolError.
#include <span>

#include "geotandem/core/byte_stream.hpp"
#include "geotandem/runtime/protocol.hpp"

namespace geotandem::runtime::detail {

using ByteWriter = geotandem::ByteWriter;

class ByteReader : public geotandem::ByteReader<ProtocolError> {
public:
  explicit ByteReader(std::span<const std::byte> in) : geotandem::ByteReader<ProtocolError>(in, "message") {}
};

} // namespace geotandem::runtime::detail
