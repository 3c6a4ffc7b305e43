#pragma once
// Chunk compression: zstd (libzstd), lz4 frame format (liblz4), or none, named as MCAP names
// them in the Chunk record ("zstd", "lz4", "").

#include <cstddef>
#include <cstdint>
#include <string>

namespace robodds::mcap {

enum class Compression { kNone, kZstd, kLz4 };

/// "none" / "zstd" / "lz4"; ConfigError naming `option_name` and the accepted values.
Compression parse_compression(const std::string& text, const std::string& option_name);
/// The name in the Chunk record: "", "zstd", "lz4".
const char* record_name(Compression compression);
/// "none", "zstd", "lz4" (for people).
const char* display_name(Compression compression);

/// Appends the compressed form of [data, data + size) to `out`. Throws std::runtime_error when the
/// library fails (it does not on valid input).
void compress_append(Compression compression, const void* data, std::size_t size, std::string& out);

/// Decompresses a chunk's records compressed with the record name `compression` ("", "zstd", "lz4")
/// into exactly `uncompressed_size` bytes. Returns false and sets `reason` ("unknown compression
/// 'x'", "zstd: ...", "decompressed to N bytes, chunk says M") on failure.
bool decompress(const std::string& compression, const std::uint8_t* data, std::size_t size,
                std::uint64_t uncompressed_size, std::string& out, std::string& reason);

}  // namespace robodds::mcap
