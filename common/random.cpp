#include "common/random.hpp"

#include <cmath>

namespace robodds {

std::uint64_t stable_hash(std::string_view text) {
  std::uint64_t hash = 14695981039346656037ULL;
  for (unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ULL;
  }
  return hash;
}

std::uint64_t derive_seed(std::uint64_t scenario_seed, std::string_view stream_name) {
  // splitmix64 finaliser over (seed, name hash): nearby seeds give unrelated streams.
  std::uint64_t z = scenario_seed ^ (stable_hash(stream_name) + 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

double uniform01(RandomEngine& engine) {
  // 53 random bits -> [0, 1), exactly representable.
  return static_cast<double>(engine() >> 11) * (1.0 / 9007199254740992.0);
}

double standard_normal(RandomEngine& engine) {
  // Box-Muller; one value per call keeps the stream position easy to reason about.
  double u1 = uniform01(engine);
  while (u1 <= 0.0) {
    u1 = uniform01(engine);
  }
  const double u2 = uniform01(engine);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2);
}

}  // namespace robodds
