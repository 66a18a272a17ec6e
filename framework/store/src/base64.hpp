#pragma once
// Base64 (RFC 4648: standard alphabet, '=' padding, no line breaks), written to a stream as the
// bytes arrive. Memory stays bounded: the bytes pass through a fixed buffer whose size is a
// multiple of 3, so every full buffer encodes without padding and a multi-gigabyte array is never
// copied whole.

#include <cstddef>
#include <cstdint>
#include <ostream>
#include <vector>

namespace geotandem::store::detail {

class Base64Writer {
public:
  // Bytes buffered before they are encoded and written: 48 KiB (64 KiB of text).
  static constexpr std::size_t chunk_bytes = std::size_t{48} * 1024;
  static_assert(chunk_bytes % 3 == 0, "a chunk must end on a 3-byte group, or padding would split the text");

  explicit Base64Writer(std::ostream& out);
  Base64Writer(const Base64Writer&) = delete;
  Base64Writer& operator=(const Base64Writer&) = delete;

  // Appends `size` bytes to the text being encoded.
  void write(const void* data, std::size_t size);
  // Writes what is buffered, padded with '=' to a multiple of 4 characters, and ends the text: the
  // next write starts a new one. Stream errors are left in the stream's state.
  void finish();

private:
  void encode_buffered();

  std::ostream& out_;
  std::vector<unsigned char> bytes_;
  std::vector<char> text_;
  std::size_t used_ = 0;
};

} // namespace geotandem::store::detail
