#pragma once
// SHA-256 (OpenSSL, linked here for DDS Security) of bytes and of files: the digests hosts
// announce of what they loaded (runtime/bus/run_digest.hpp). SHA-256 rather than a 64-bit FNV:
// the library is already linked, and its strength costs nothing here; what the check guards
// against is accidents, not attackers (docs/security.md).

#include <string>

namespace robodds {

/// Lower-case hex SHA-256 of `bytes`.
std::string sha256_hex(const std::string& bytes);

/// Lower-case hex SHA-256 of the file's content; ConfigError naming the file when unreadable.
std::string sha256_of_file(const std::string& path);

}  // namespace robodds
