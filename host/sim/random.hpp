#pragma once
// Small deterministic random tools shared by the simulator (private header): the same numbers on
// every platform and standard library, which std::normal_distribution does not promise.
#include <cmath>
#include <cstdint>

namespace trn::sim::detail {

inline std::uint64_t mix64(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// A hash of a seed and up to four integers (grid cells, block indices, years ...): one strong
// finaliser over a cheap combination, fast enough to call per pixel.
inline std::uint64_t rotl(std::uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }
inline std::uint64_t hash(std::uint64_t seed, std::int64_t a, std::int64_t b = 0, std::int64_t c = 0, std::int64_t d = 0) {
    const std::uint64_t h = seed ^ (static_cast<std::uint64_t>(a) * 0x9E3779B97F4A7C15ull) ^
                            rotl(static_cast<std::uint64_t>(b) * 0xC2B2AE3D27D4EB4Full, 21) ^
                            rotl(static_cast<std::uint64_t>(c) * 0x165667B19E3779F9ull, 42) ^
                            rotl(static_cast<std::uint64_t>(d) * 0xD6E8FEB86659FD93ull, 11);
    return mix64(mix64(h));
}

// Uniform in [0, 1) from 53 bits of a hash.
inline double unit(std::uint64_t h) { return static_cast<double>(h >> 11) * 0x1.0p-53; }

// The k-th independent uniform derived from one hash.
inline double unit(std::uint64_t h, int k) { return unit(mix64(h + 0x9E3779B97F4A7C15ull * (k + 1))); }

inline std::uint64_t next64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    return mix64(z);
}
inline double uniform(std::uint64_t& state) { return unit(next64(state)); }
// Standard normal by Box-Muller.
inline double normal(std::uint64_t& state) {
    const double u1 = 1.0 - uniform(state), u2 = uniform(state);
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

}  // namespace trn::sim::detail
