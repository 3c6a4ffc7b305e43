#include "runtime/mcap/crc32.hpp"

#include <gtest/gtest.h>

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

TEST(Crc32, UpdateContinuesAcrossPieces) {
  const std::string a = "hello, ", b = "mcap world";
  EXPECT_EQ(crc32_update(crc32(a.data(), a.size()), b.data(), b.size()), crc32((a + b).data(), a.size() + b.size()));
}

}  // namespace
}  // namespace robodds::mcap
