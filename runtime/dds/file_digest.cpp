#include "runtime/dds/file_digest.hpp"

#include <openssl/evp.h>

#include <fstream>
#include <sstream>

#include "runtime/base/error.hpp"

namespace robodds {

std::string sha256_hex(const std::string& bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), digest, &size, EVP_sha256(), nullptr) != 1) {
    throw RunError("OpenSSL could not compute a SHA-256 digest");
  }
  static const char* kHex = "0123456789abcdef";
  std::string hex;
  for (unsigned int i = 0; i < size; ++i) {
    hex += kHex[digest[i] >> 4];
    hex += kHex[digest[i] & 0xf];
  }
  return hex;
}

std::string sha256_of_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream content;
  if (!in || !(content << in.rdbuf())) {
    throw ConfigError(located(path, "", "cannot read it to compute its digest"));
  }
  return sha256_hex(content.str());
}

}  // namespace robodds
