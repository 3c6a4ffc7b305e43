#pragma once
// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320, initial and final XOR 0xFFFFFFFF): the
// checksum MCAP uses for chunks, the data section and the summary (same as zlib's crc32()).

#include <cstddef>
#include <cstdint>

namespace robodds::mcap {

/// Continues a CRC over `size` more bytes: crc32_update(0, a) then crc32_update(that, b) equals
/// the CRC of a followed by b. Start with 0.
std::uint32_t crc32_update(std::uint32_t crc, const void* data, std::size_t size);

inline std::uint32_t crc32(const void* data, std::size_t size) { return crc32_update(0, data, size); }

}  // namespace robodds::mcap
