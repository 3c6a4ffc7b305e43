// SHA-256 of bytes and files (runtime/dds/file_digest.hpp).
#include "runtime/dds/file_digest.hpp"

#include <gtest/gtest.h>

#include "runtime/base/error.hpp"
#include "tests/support/temp_file.hpp"

namespace robodds {
namespace {

TEST(FileDigest, IsSha256) {
  // FIPS 180-2, appendix B.1.
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(FileDigest, OfAFileItsContentAndAnUnreadableFileIsNamed) {
  EXPECT_EQ(sha256_of_file(test_support::write_test_file("d.txt", "abc")), sha256_hex("abc"));
  try {
    sha256_of_file("/nonexistent/x.xml");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/x.xml"), std::string::npos);
  }
}

}  // namespace
}  // namespace robodds
