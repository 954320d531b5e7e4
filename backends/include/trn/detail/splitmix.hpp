#pragma once
// The project's one deterministic random-number generator, SplitMix64 (Steele, Lea & Flood 2014),
// with a uniform double and a Box-Muller normal built on it: the same numbers on every platform
// and standard library, which <random>'s distributions do not promise. The filter, the simulator,
// the studies and random sampling plans all draw from it, and published results (docs/RESULTS.md)
// depend on these exact sequences: change nothing here without regenerating them.
//
// An implementation detail shared by the layers, not API: header-only, outside TRN_API_BEGIN/END,
// so each library keeps its own hidden inline copies and exports nothing. The state is a plain
// std::uint64_t owned by the caller, who also chooses how a seed becomes a state.
#include <cmath>
#include <cstdint>
#include <numbers>

namespace trn::splitmix {

// The Weyl increment (2^64 / golden ratio) that advances the state.
inline constexpr std::uint64_t kGamma = 0x9E3779B97F4A7C15ull;

// SplitMix64's output function (Stafford's variant 13): a strong 64-bit finaliser, also useful
// on its own to turn a seed into a well-mixed state.
constexpr std::uint64_t mix64(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// The next 64 random bits: advance the state by kGamma, return the mixed state.
constexpr std::uint64_t next64(std::uint64_t& state) { return mix64(state += kGamma); }

// A double in [0, 1) from the top 53 bits of `bits` (every value a multiple of 2^-53).
constexpr double unit(std::uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }

// Uniform in [0, 1).
constexpr double uniform(std::uint64_t& state) { return unit(next64(state)); }

// Standard normal by Box-Muller: two uniforms per deviate, u1 drawn first (1 - u1 > 0 keeps the log
// finite), cosine branch only (the sine partner is discarded, so every call costs two draws).
inline double normal(std::uint64_t& state) {
    const double u1 = 1.0 - uniform(state), u2 = uniform(state);
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2 * std::numbers::pi * u2);
}

}  // namespace trn::splitmix
