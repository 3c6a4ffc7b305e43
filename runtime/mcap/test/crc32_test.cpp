#include "runtime/mcap/crc32.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>

namespace robodds::mcap {
namespace {

// Bit-at-a-time reference of the same polynomial.
std::uint32_t reference_crc(const std::string& s) {
  std::uint32_t c = 0xFFFFFFFFU;
  for (unsigned char byte : s) {
    c ^= byte;
    for (int k = 0; k < 8; ++k) c = (c & 1U) ? (0xEDB88320U ^ (c >> 1)) : (c >> 1);
  }
  return ~c;
}

TEST(Crc32, CheckValueOfTheStandard) {
  EXPECT_EQ(crc32("123456789", 9), 0xCBF43926U);  // the CRC-32/ISO-HDLC check value
  EXPECT_EQ(crc32("", 0), 0U);
}

TEST(Crc32, SlicedEqualsBitwiseAtEveryLengthAndAlignment) {
  std::string data;
  for (int i = 0; i < 300; ++i) data.push_back(static_cast<char>((i * 131 + 7) & 0xFF));
  for (std::size_t start = 0; start < 8; ++start) {
    for (std::size_t n = 0; start + n <= data.size(); n += 13) {
      ASSERT_EQ(crc32(data.data() + start, n), reference_crc(data.substr(start, n))) << start << " " << n;
    }
  }
}

// Published CRC-32 (zlib crc32()) values of well-known strings.
TEST(Crc32, KnownVectors) {
  const auto of = [](const std::string& s) { return crc32(s.data(), s.size()); };
  EXPECT_EQ(of("a"), 0xE8B7BE43U);
  EXPECT_EQ(of("abc"), 0x352441C2U);
  EXPECT_EQ(of("The quick brown fox jumps over the lazy dog"), 0x414FA339U);
  EXPECT_EQ(of(std::string(32, '\0')), 0x190A55ADU);
  EXPECT_EQ(of(std::string(32, '\xFF')), 0xFF6CAB0BU);
  // 64 bytes and more take the folded path where the CPU has carry-less multiply.
  EXPECT_EQ(of(std::string(1 << 20, '\0')), 0xA738EA1CU);  // 1 MiB of zeros
}

// Random buffers at every length around the folding's thresholds (64 bytes, multiples of 16) and
// up to a few chunks of lanes, at every alignment, and continued across pieces of random sizes:
// the same CRC as the bit-at-a-time definition.
TEST(Crc32, EqualsBitwiseOnRandomBuffers) {
  std::mt19937 random(25);
  std::string data(5000, '\0');
  for (char& c : data) c = static_cast<char>(random() & 0xFFU);
  for (std::size_t start = 0; start < 16; ++start) {
    for (std::size_t n = 0; n <= 300; ++n) {
      ASSERT_EQ(crc32(data.data() + start, n), reference_crc(data.substr(start, n))) << start << " " << n;
    }
  }
  for (std::size_t n : {1023U, 1024U, 1025U, 4096U, 4990U}) {
    ASSERT_EQ(crc32(data.data() + 3, n), reference_crc(data.substr(3, n))) << n;
  }
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t total = random() % data.size();
    std::uint32_t crc = 0;
    for (std::size_t at = 0; at < total;) {
      const std::size_t piece = std::min<std::size_t>(total - at, random() % 200);
      crc = crc32_update(crc, data.data() + at, piece);
      at += piece;
    }
    ASSERT_EQ(crc, reference_crc(data.substr(0, total))) << total;
  }
}

TEST(Crc32, UpdateContinuesAcrossPieces) {
  const std::string a = "hello, ", b = "mcap world";
  EXPECT_EQ(crc32_update(crc32(a.data(), a.size()), b.data(), b.size()), crc32((a + b).data(), a.size() + b.size()));
}

}  // namespace
}  // namespace robodds::mcap
