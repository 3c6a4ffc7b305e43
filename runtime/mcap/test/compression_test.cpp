#include "runtime/mcap/compression.hpp"

#include <gtest/gtest.h>

#include "runtime/base/error.hpp"

namespace robodds::mcap {
namespace {

std::string sample_bytes(std::size_t n) {
  std::string s;
  for (std::size_t i = 0; i < n; ++i) s.push_back(static_cast<char>((i % 17) * (i % 5)));
  return s;
}

TEST(Compression, ParsesTheThreeNamesAndNamesTheOptionOtherwise) {
  EXPECT_EQ(parse_compression("none", "--compression"), Compression::kNone);
  EXPECT_EQ(parse_compression("zstd", "--compression"), Compression::kZstd);
  EXPECT_EQ(parse_compression("lz4", "--compression"), Compression::kLz4);
  try {
    parse_compression("gzip", "--compression");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "--compression: unknown compression 'gzip' (accepted: none, zstd, lz4)");
  }
  try {
    parse_compression("zsdt", "--compression");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "--compression: unknown compression 'zsdt'; did you mean 'zstd'? (accepted: none, zstd, lz4)");
  }
}

TEST(Compression, RoundTripsEachCodec) {
  for (Compression c : {Compression::kNone, Compression::kZstd, Compression::kLz4}) {
    for (std::size_t n : {0UL, 1UL, 100UL, 300000UL}) {
      const std::string in = sample_bytes(n);
      std::string packed = "prefix";
      compress_append(c, in.data(), in.size(), packed);
      ASSERT_EQ(packed.substr(0, 6), "prefix");
      std::string out, reason;
      ASSERT_TRUE(decompress(record_name(c), reinterpret_cast<const std::uint8_t*>(packed.data()) + 6, packed.size() - 6,
                             in.size(), out, reason))
          << display_name(c) << " " << n << ": " << reason;
      EXPECT_EQ(out, in);
    }
  }
}

TEST(Compression, DamagedOrUnknownInputFailsWithAReason) {
  const std::string in = sample_bytes(5000);
  std::string out, reason;
  std::string packed;
  compress_append(Compression::kZstd, in.data(), in.size(), packed);
  EXPECT_FALSE(decompress("zstd", reinterpret_cast<const std::uint8_t*>(packed.data()), packed.size() / 2, in.size(), out, reason));
  EXPECT_NE(reason.find("zstd"), std::string::npos) << reason;
  packed.clear();
  compress_append(Compression::kLz4, in.data(), in.size(), packed);
  EXPECT_FALSE(decompress("lz4", reinterpret_cast<const std::uint8_t*>(packed.data()), packed.size() / 2, in.size(), out, reason));
  EXPECT_NE(reason.find("lz4"), std::string::npos) << reason;
  EXPECT_FALSE(decompress("brotli", reinterpret_cast<const std::uint8_t*>(in.data()), in.size(), in.size(), out, reason));
  EXPECT_EQ(reason, "unknown compression 'brotli' (known: zstd, lz4, none)");
  // A size field claiming far more than any codec produces is refused, not allocated.
  EXPECT_FALSE(decompress("zstd", reinterpret_cast<const std::uint8_t*>(in.data()), 10, std::uint64_t{1} << 40, out, reason));
  EXPECT_NE(reason.find("implausible"), std::string::npos) << reason;
}

}  // namespace
}  // namespace robodds::mcap
