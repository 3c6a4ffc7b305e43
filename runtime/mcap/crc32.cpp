#include "runtime/mcap/crc32.hpp"

#include <array>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define ROBODDS_CRC32_CLMUL 1
#endif

namespace robodds::mcap {
namespace {

// Slicing-by-8 tables: eight bytes per step instead of one. Used for buffers too short to fold
// and the tail after the folding below, and everywhere on a CPU without carry-less multiply.
using Tables = std::array<std::array<std::uint32_t, 256>, 8>;

Tables make_tables() {
  Tables t{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1U) ? (0xEDB88320U ^ (c >> 1)) : (c >> 1);
    t[0][i] = c;
  }
  for (std::uint32_t i = 0; i < 256; ++i) {
    for (std::size_t s = 1; s < 8; ++s) t[s][i] = (t[s - 1][i] >> 8) ^ t[0][t[s - 1][i] & 0xFFU];
  }
  return t;
}

const Tables& tables() {
  static const Tables t = make_tables();
  return t;
}

/// The running (inverted) CRC `c` over `size` more bytes, eight at a time.
std::uint32_t sliced(std::uint32_t c, const std::uint8_t* p, std::size_t size) {
  const Tables& t = tables();
  while (size >= 8) {
    // Little-endian load independent of the host's byte order and alignment.
    const std::uint32_t lo = c ^ (std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 |
                                  std::uint32_t{p[3]} << 24);
    c = t[7][lo & 0xFFU] ^ t[6][(lo >> 8) & 0xFFU] ^ t[5][(lo >> 16) & 0xFFU] ^ t[4][lo >> 24] ^ t[3][p[4]] ^
        t[2][p[5]] ^ t[1][p[6]] ^ t[0][p[7]];
    p += 8;
    size -= 8;
  }
  while (size-- > 0) c = t[0][(c ^ *p++) & 0xFFU] ^ (c >> 8);
  return c;
}

#ifdef ROBODDS_CRC32_CLMUL
// Folding with carry-less multiplication (PCLMULQDQ), after Intel's "Fast CRC Computation for
// Generic Polynomials Using PCLMULQDQ Instruction" (2009), bit-reflected constants for the
// polynomial 0x04C11DB7 as zlib and Linux use them: four 16-byte lanes are folded 64 bytes at a
// time, then into one lane, then reduced to 32 bits (Barrett). ~10x the sliced tables on a
// recorder's 1 MiB chunks (docs/performance.md, "Recording in the run"), the same CRC.
constexpr std::size_t kFoldMin = 64;  // one block of the four lanes

// (Lambdas would not inherit the target attribute, so these are functions.)
__attribute__((target("pclmul,sse4.1"))) inline __m128i load(const std::uint8_t* at) {
  return _mm_loadu_si128(reinterpret_cast<const __m128i*>(at));
}

/// acc folded over 128 bits by the constants `k` and combined with the next 16 bytes.
__attribute__((target("pclmul,sse4.1"))) inline __m128i fold16(__m128i acc, __m128i k, __m128i next) {
  const __m128i lo = _mm_clmulepi64_si128(acc, k, 0x00);
  return _mm_xor_si128(_mm_xor_si128(_mm_clmulepi64_si128(acc, k, 0x11), next), lo);
}

__attribute__((target("pclmul,sse4.1"))) std::uint32_t folded(std::uint32_t c, const std::uint8_t* p,
                                                                  std::size_t size) {
  // size >= 64 and a multiple of 16.
  alignas(16) static const std::uint64_t k1k2[2] = {0x0154442bd4ULL, 0x01c6e41596ULL};  // x^(4*128+32), x^(4*128-32) mod P
  alignas(16) static const std::uint64_t k3k4[2] = {0x01751997d0ULL, 0x00ccaa009eULL};  // x^(128+32), x^(128-32) mod P
  alignas(16) static const std::uint64_t k5k0[2] = {0x0163cd6124ULL, 0};                 // x^64 mod P
  alignas(16) static const std::uint64_t poly[2] = {0x01db710641ULL, 0x01f7011641ULL};  // P', mu (Barrett)
  __m128i x1 = _mm_xor_si128(load(p), _mm_cvtsi32_si128(static_cast<int>(c)));
  __m128i x2 = load(p + 16);
  __m128i x3 = load(p + 32);
  __m128i x4 = load(p + 48);
  p += 64;
  size -= 64;
  __m128i k = _mm_load_si128(reinterpret_cast<const __m128i*>(k1k2));
  while (size >= 64) {
    x1 = fold16(x1, k, load(p));
    x2 = fold16(x2, k, load(p + 16));
    x3 = fold16(x3, k, load(p + 32));
    x4 = fold16(x4, k, load(p + 48));
    p += 64;
    size -= 64;
  }
  // Four lanes into one, then the remaining 16-byte blocks.
  k = _mm_load_si128(reinterpret_cast<const __m128i*>(k3k4));
  x1 = fold16(x1, k, x2);
  x1 = fold16(x1, k, x3);
  x1 = fold16(x1, k, x4);
  while (size >= 16) {
    x1 = fold16(x1, k, load(p));
    p += 16;
    size -= 16;
  }
  // 128 bits to 64.
  const __m128i mask32 = _mm_setr_epi32(~0, 0, ~0, 0);
  x2 = _mm_clmulepi64_si128(x1, k, 0x10);
  x1 = _mm_xor_si128(_mm_srli_si128(x1, 8), x2);
  k = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(k5k0));
  x2 = _mm_srli_si128(x1, 4);
  x1 = _mm_xor_si128(_mm_clmulepi64_si128(_mm_and_si128(x1, mask32), k, 0x00), x2);
  // Barrett reduction to 32 bits.
  k = _mm_load_si128(reinterpret_cast<const __m128i*>(poly));
  x2 = _mm_clmulepi64_si128(_mm_and_si128(x1, mask32), k, 0x10);
  x2 = _mm_clmulepi64_si128(_mm_and_si128(x2, mask32), k, 0x00);
  x1 = _mm_xor_si128(x1, x2);
  return static_cast<std::uint32_t>(_mm_extract_epi32(x1, 1));
}

bool cpu_folds() {
  static const bool folds = __builtin_cpu_supports("pclmul") && __builtin_cpu_supports("sse4.1");
  return folds;
}
#endif

}  // namespace

std::uint32_t crc32_update(std::uint32_t crc, const void* data, std::size_t size) {
  const auto* p = static_cast<const std::uint8_t*>(data);
  std::uint32_t c = ~crc;
#ifdef ROBODDS_CRC32_CLMUL
  if (size >= kFoldMin && cpu_folds()) {
    const std::size_t whole = size & ~std::size_t{15};
    c = folded(c, p, whole);
    p += whole;
    size -= whole;
  }
#endif
  return ~sliced(c, p, size);
}

}  // namespace robodds::mcap
