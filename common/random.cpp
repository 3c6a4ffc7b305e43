#include "common/random.hpp"

#include <array>
#include <cmath>
#include <cstddef>

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

namespace {

double gaussian_density(double x) { return std::exp(-0.5 * x * x); }  // unnormalised

/// Layers of the ziggurat (Marsaglia & Tsang 2000, 128 layers of equal area kArea): layer i
/// covers x in [0, x[i]] and y in [f(x[i]), f(x[i+1])]; x[1] = kTailStart, x[128] = 0, and
/// x[0] = kArea / f(kTailStart) is the virtual width of the base layer (rectangle + tail).
struct ZigguratTables {
  static constexpr int kLayers = 128;
  static constexpr double kTailStart = 3.442619855899;
  static constexpr double kArea = 9.91256303526217e-3;
  std::array<double, kLayers + 1> x{};
  std::array<double, kLayers + 1> f{};

  ZigguratTables() {
    x[0] = kArea / gaussian_density(kTailStart);
    x[1] = kTailStart;
    for (int i = 1; i < kLayers - 1; ++i) {
      x[i + 1] = std::sqrt(-2.0 * std::log(gaussian_density(x[i]) + kArea / x[i]));
    }
    x[kLayers] = 0.0;
    for (int i = 0; i <= kLayers; ++i) {
      f[i] = gaussian_density(x[i]);
    }
  }
};

double positive_uniform(RandomEngine& engine) {
  double u = uniform01(engine);
  while (u <= 0.0) {
    u = uniform01(engine);
  }
  return u;
}

}  // namespace

double standard_normal(RandomEngine& engine) {
  // Ziggurat: one 64-bit draw gives the layer (bits 0-6), the sign (bit 7) and a 53-bit
  // uniform (bits 11-63), independent bit fields. ~98.8 % of the draws are accepted at once;
  // Box-Muller cost a log, a sqrt and a cos per value, which dominated the particle filter.
  static const ZigguratTables tables;
  while (true) {
    const std::uint64_t bits = engine();
    const auto layer = static_cast<std::size_t>(bits & 127U);
    const bool negative = ((bits >> 7) & 1U) != 0;
    const double u = static_cast<double>(bits >> 11) * (1.0 / 9007199254740992.0);
    const double x = u * tables.x[layer];
    if (x < tables.x[layer + 1]) {
      return negative ? -x : x;  // inside the layer's rectangle, under the curve for any y
    }
    if (layer == 0) {
      // Beyond the base rectangle: the tail x > kTailStart (Marsaglia's exponential method).
      double a = 0.0;
      double b = 0.0;
      do {
        a = -std::log(positive_uniform(engine)) / ZigguratTables::kTailStart;
        b = -std::log(positive_uniform(engine));
      } while (b + b < a * a);
      const double tail = ZigguratTables::kTailStart + a;
      return negative ? -tail : tail;
    }
    // The wedge between the rectangle and the curve: accept if under the density.
    const double y = tables.f[layer] + uniform01(engine) * (tables.f[layer + 1] - tables.f[layer]);
    if (y < gaussian_density(x)) {
      return negative ? -x : x;
    }
  }
}

}  // namespace robodds
