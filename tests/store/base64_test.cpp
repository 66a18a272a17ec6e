// The streaming base64 encoder behind the VTP export: RFC 4648's vectors, and long inputs written
// in uneven pieces across its chunk boundaries, decoded back by the tests' own decoder.

#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "base64.hpp"
#include "base64_decode.hpp"

namespace geotandem::store {
namespace {

using detail::Base64Writer;

std::string encode(const std::string& bytes) {
  std::ostringstream out;
  Base64Writer writer(out);
  writer.write(bytes.data(), bytes.size());
  writer.finish();
  return out.str();
}

TEST(Base64Writer, EncodesTheRfc4648Vectors) {
  EXPECT_EQ(encode(""), "");
  EXPECT_EQ(encode("f"), "Zg==");
  EXPECT_EQ(encode("fo"), "Zm8=");
  EXPECT_EQ(encode("foo"), "Zm9v");
  EXPECT_EQ(encode("foob"), "Zm9vYg==");
  EXPECT_EQ(encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(encode(std::string("\xff\xfe\x00\x3e\x3f", 5)), "//4APj8=");
}

TEST(Base64Writer, UnevenPiecesAcrossChunksEncodeAsOneWrite) {
  std::mt19937 random(7);
  for (std::size_t size : {Base64Writer::chunk_bytes - 1, Base64Writer::chunk_bytes, 3 * Base64Writer::chunk_bytes + 2,
                           3 * Base64Writer::chunk_bytes + 7}) {
    std::string bytes(size, '\0');
    for (auto& b : bytes)
      b = static_cast<char>(random() & 0xff);
    std::ostringstream out;
    Base64Writer writer(out);
    std::size_t at = 0;
    for (std::size_t piece = 1; at < size; piece = piece * 7 % 65521 + 1) { // 1 byte up to ~64 KiB
      const std::size_t n = std::min(piece, size - at);
      writer.write(bytes.data() + at, n);
      at += n;
    }
    writer.finish();
    const auto text = out.str();
    EXPECT_EQ(text, encode(bytes)) << size;
    EXPECT_EQ(text.size(), (size + 2) / 3 * 4) << size;
    EXPECT_EQ(text.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/="),
              std::string::npos);
    EXPECT_EQ(testing::decode_base64(text), bytes) << size;
  }
}

TEST(Base64Writer, FinishEndsOneTextAndTheNextWriteStartsAnother) {
  std::ostringstream out;
  Base64Writer writer(out);
  writer.write("f", 1);
  writer.finish();
  writer.finish(); // nothing buffered: writes nothing
  writer.write("fo", 2);
  writer.finish();
  EXPECT_EQ(out.str(), "Zg==Zm8=");
}

} // namespace
} // namespace geotandem::store
