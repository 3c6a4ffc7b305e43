#include "common/random.hpp"

#include <algorithm>
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

namespace {

constexpr std::uint64_t kGoldenGamma = 0x9E3779B97F4A7C15ULL;

/// The splitmix64 finaliser (Steele, Lea & Flood 2014): a bijective 64-bit mix.
std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

/// splitmix64: advances `state` by the golden gamma and returns its mix.
std::uint64_t splitmix64(std::uint64_t& state) {
  state += kGoldenGamma;
  return mix64(state);
}

constexpr double kTailStart = 3.442619855899;    // x[1] of the 128-layer ziggurat
constexpr double kLayerArea = 9.91256303526217e-3;

double gaussian_density(double x) { return std::exp(-0.5 * x * x); }  // unnormalised

double positive_uniform(RandomEngine& engine) {
  double u = uniform01(engine);
  while (u <= 0.0) {
    u = uniform01(engine);
  }
  return u;
}

}  // namespace

std::uint64_t derive_seed(std::uint64_t scenario_seed, std::string_view stream_name) {
  // splitmix64 finaliser over (seed, name hash): nearby seeds give unrelated streams.
  return mix64(scenario_seed ^ (stable_hash(stream_name) + kGoldenGamma));
}

RandomEngine::RandomEngine(std::uint64_t seed) {
  // splitmix64 never yields four zero words from one seed, so the state is never all zero
  // (the one state xoshiro cannot leave).
  for (std::uint64_t& word : state_) {
    word = splitmix64(seed);
  }
}

namespace detail {

ZigguratTables::ZigguratTables() {
  x[0] = kLayerArea / gaussian_density(kTailStart);
  x[1] = kTailStart;
  for (int i = 1; i < kLayers - 1; ++i) {
    x[i + 1] = std::sqrt(-2.0 * std::log(gaussian_density(x[i]) + kLayerArea / x[i]));
  }
  x[kLayers] = 0.0;
  for (int i = 0; i <= kLayers; ++i) {
    f[i] = gaussian_density(x[i]);
  }
}

double standard_normal_outside_rectangle(RandomEngine& engine, std::uint64_t bits) {
  const ZigguratTables& tables = ziggurat_tables();
  while (true) {
    const auto layer = static_cast<std::size_t>(bits & 127U);
    const bool negative = ((bits >> 7) & 1U) != 0;
    const double x = top53_to_unit(bits) * tables.x[layer];
    if (x < tables.x[layer + 1]) {
      return negative ? -x : x;  // inside the layer's rectangle, under the curve for any y
    }
    if (layer == 0) {
      // Beyond the base rectangle: the tail x > kTailStart (Marsaglia's exponential method).
      double a = 0.0;
      double b = 0.0;
      do {
        a = -std::log(positive_uniform(engine)) / kTailStart;
        b = -std::log(positive_uniform(engine));
      } while (b + b < a * a);
      const double tail = kTailStart + a;
      return negative ? -tail : tail;
    }
    // The wedge between the rectangle and the curve: accept if under the density.
    const double y = tables.f[layer] + uniform01(engine) * (tables.f[layer + 1] - tables.f[layer]);
    if (y < gaussian_density(x)) {
      return negative ? -x : x;
    }
    bits = engine();
  }
}

}  // namespace detail

double gauss_markov_step(double x, double dt_s, double tau_s, double sigma, double unit_normal) {
  const double a = std::exp(-dt_s / tau_s);
  return a * x + std::sqrt(std::max(0.0, 1.0 - a * a)) * sigma * unit_normal;
}

}  // namespace robodds
