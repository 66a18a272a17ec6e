#include "base64.hpp"

#include <algorithm>
#include <cstring>

namespace geotandem::store::detail {
namespace {

constexpr char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

} // namespace

Base64Writer::Base64Writer(std::ostream& out) : out_(out), bytes_(chunk_bytes), text_(chunk_bytes / 3 * 4) {}

void Base64Writer::write(const void* data, std::size_t size) {
  const auto* in = static_cast<const unsigned char*>(data);
  while (size > 0) {
    const std::size_t take = std::min(size, chunk_bytes - used_);
    std::memcpy(bytes_.data() + used_, in, take);
    used_ += take;
    in += take;
    size -= take;
    if (used_ == chunk_bytes) encode_buffered();
  }
}

void Base64Writer::finish() {
  encode_buffered();
}

// Encodes the buffer; a last group of 1 or 2 bytes (only at finish: full chunks are multiples of
// 3) is padded.
void Base64Writer::encode_buffered() {
  const unsigned char* in = bytes_.data();
  char* out = text_.data();
  std::size_t left = used_;
  for (; left >= 3; left -= 3, in += 3, out += 4) {
    const std::uint32_t group = std::uint32_t{in[0]} << 16 | std::uint32_t{in[1]} << 8 | in[2];
    out[0] = alphabet[group >> 18];
    out[1] = alphabet[group >> 12 & 63];
    out[2] = alphabet[group >> 6 & 63];
    out[3] = alphabet[group & 63];
  }
  if (left > 0) {
    const std::uint32_t group = std::uint32_t{in[0]} << 16 | (left == 2 ? std::uint32_t{in[1]} << 8 : 0);
    out[0] = alphabet[group >> 18];
    out[1] = alphabet[group >> 12 & 63];
    out[2] = left == 2 ? alphabet[group >> 6 & 63] : '=';
    out[3] = '=';
    out += 4;
  }
  out_.write(text_.data(), out - text_.data());
  used_ = 0;
}

} // namespace geotandem::store::detail
