#pragma once
// A plain base64 decoder for the tests, written apart from the store's encoder so that the two
// check each other: standard alphabet, '=' padding only at the end, nothing else allowed.

#include <optional>
#include <string>
#include <string_view>

namespace geotandem::store::testing {

// The bytes `text` encodes; nullopt for a length that is not a multiple of 4, a character outside
// the alphabet (whitespace included), or padding anywhere but in the last two places.
inline std::optional<std::string> decode_base64(std::string_view text) {
  if (text.size() % 4 != 0) return std::nullopt;
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::string bytes;
  bytes.reserve(text.size() / 4 * 3);
  for (std::size_t i = 0; i < text.size(); i += 4) {
    const bool last = i + 4 == text.size();
    const int pad = last ? (text[i + 3] == '=') + (text[i + 2] == '=') : 0;
    if (pad == 1 && text[i + 2] == '=') return std::nullopt; // "x=y=" style padding
    unsigned long group = 0;
    for (int k = 0; k < 4; ++k) {
      const int v = k >= 4 - pad ? 0 : value(text[i + k]);
      if (v < 0) return std::nullopt;
      group = group << 6 | static_cast<unsigned long>(v);
    }
    bytes.push_back(static_cast<char>(group >> 16 & 0xff));
    if (pad < 2) bytes.push_back(static_cast<char>(group >> 8 & 0xff));
    if (pad < 1) bytes.push_back(static_cast<char>(group & 0xff));
  }
  return bytes;
}

} // namespace geotandem::store::testing
