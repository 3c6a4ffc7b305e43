#pragma once
// Seeded random streams. Every stochastic component draws from its own stream whose seed is
// derived from the scenario seed and a stable name (component instance + robot), so results do
// not depend on which process or host a component runs in, nor on the order components start.

#include <cstdint>
#include <random>
#include <string_view>

namespace robodds {

/// 64-bit FNV-1a: stable across platforms and runs (std::hash is not).
std::uint64_t stable_hash(std::string_view text);

/// Seed for the stream `stream_name` (e.g. "position_sensor/robot3") of a scenario.
std::uint64_t derive_seed(std::uint64_t scenario_seed, std::string_view stream_name);

/// The one random engine type of the project.
using RandomEngine = std::mt19937_64;

/// Standard normal sample. Written here rather than std::normal_distribution, whose algorithm
/// (and so its output for a given engine state) is left to the standard library.
double standard_normal(RandomEngine& engine);

/// Uniform sample in [0, 1).
double uniform01(RandomEngine& engine);

}  // namespace robodds
