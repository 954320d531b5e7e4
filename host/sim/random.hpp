#pragma once
// The simulator's deterministic random tools (private header): the project's SplitMix64
// (trn/detail/splitmix.hpp) under the names the simulator uses, plus a hash of a seed and a few
// integers for per-pixel and per-cell noise that needs no state.
#include <cstdint>

#include "trn/detail/splitmix.hpp"

namespace trn::sim::detail {

using splitmix::mix64;
using splitmix::next64;
using splitmix::normal;
using splitmix::uniform;
using splitmix::unit;

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

// The k-th independent uniform derived from one hash.
inline double unit(std::uint64_t h, int k) { return unit(mix64(h + splitmix::kGamma * (k + 1))); }

}  // namespace trn::sim::detail
